// rostest: finger_node under the membrane wall law (test/finger_node_limit.test, config/marchese2015_ribbed.yaml). A
// pressure at or beyond the wall's limit point does not determine the shape: the node publishes no joint_states and no
// new shape, finger_state repeats the last one with STATUS_BEYOND_LIMIT_POINT, diagnostics WARN and say why; a pressure
// below the limit brings the shape back. A Gent wall (namespace gent) snaps through at its limit pressure to its far
// branch, publishes that shape with STATUS_SNAPPED_THROUGH, and snaps back at the far branch's lower turning point.
// Driven by volume (namespace volume, ~volume_topic), the Neo-Hookean wall is followed past its limit point; closing
// on a grasp object (namespace volume_object), the paper's finger takes the contact rule's volume.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>

#include <algorithm>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/GraspObject.h"
#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/self_contact.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "pneumatic_finger/description/finger_urdf.hpp"
#include "grasp_object_support.hpp"
#include "ros_test_support.hpp"

namespace pf = pneumatic_finger;

namespace {

std::mutex mutex;
std::vector<sensor_msgs::JointState> joints;
std::vector<pf::FingerModelState> states;
std::vector<diagnostic_msgs::DiagnosticStatus> diagnostics;

template <class T>
std::size_t countOf(const std::vector<T>& v) {
  std::lock_guard<std::mutex> lock(mutex);
  return v.size();
}

template <class T>
T lastOf(const std::vector<T>& v) {
  std::lock_guard<std::mutex> lock(mutex);
  return v.back();
}

// Waits (wall time) until @p done holds, or @p seconds pass.
template <class F>
bool waitFor(F done, double seconds) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(seconds);
  while (!done() && ros::WallTime::now() < deadline) ros::WallDuration(0.01).sleep();
  return done();
}

// Subscribes to @p topic, appending each message to @p into under the one mutex.
template <class M>
ros::Subscriber collect(ros::NodeHandle& nh, const std::string& topic, std::vector<M>& into) {
  const boost::function<void(const boost::shared_ptr<const M>&)> append = [&into](const boost::shared_ptr<const M>& m) {
    std::lock_guard<std::mutex> lock(mutex);
    into.push_back(*m);
  };
  return nh.subscribe<M>(topic, 100, append);
}

// A finger node's topics under @p ns: its joint_states and finger_state collected, its input advertised.
template <class Input>
struct FingerTopics {
  ros::Subscriber joints, states;
  ros::Publisher input;
  FingerTopics(ros::NodeHandle& nh, const std::string& ns, const std::string& input_topic,
               std::vector<sensor_msgs::JointState>& joint_log, std::vector<pf::FingerModelState>& state_log)
      : joints(collect(nh, ns + "joint_states", joint_log)),
        states(collect(nh, ns + "finger_state", state_log)),
        input(nh.advertise<Input>(ns + input_topic, 10)) {}
  /// The node listens to the input and publishes joint_states (within @p seconds).
  bool connect(double seconds) const {
    return waitFor([this] { return input.getNumSubscribers() > 0 && joints.getNumPublishers() > 0; }, seconds);
  }
};

void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto& s : m->status) {
    // The root namespace's node only: the launch runs the gent and volume nodes too, on the same /diagnostics.
    const bool ours = s.name.rfind("/finger_node: pressure input", 0) == 0 ||
                      s.name.rfind("finger_node: pressure input", 0) == 0;
    if (ours) diagnostics.push_back(s);
  }
}

pf::FingerModel ribbedModel(double locking_jm = 0.0) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/marchese2015_ribbed.yaml", raw);
  raw["wall_locking_jm"] = {{locking_jm}, false};
  return pf::FingerModel(pf::FingerParameters::fromRaw(raw));
}

std::vector<sensor_msgs::JointState> gent_joints;
std::vector<pf::FingerModelState> gent_states;

}  // namespace

TEST(FingerNodeLimitPoint, NothingIsPublishedPastTheLimitPointAndTheShapeReturnsBelowIt) {
  ros::NodeHandle nh;
  const FingerTopics<sensor_msgs::FluidPressure> topics(nh, "", "pressure", joints, states);
  const ros::Subscriber sub_d = nh.subscribe("/diagnostics", 100, onDiagnostics);
  ASSERT_TRUE(topics.connect(30));
  ros::Publisher pub = topics.input;
  const pf::FingerModel model = ribbedModel();
  const double limit = model.limitGaugePa();
  ASSERT_TRUE(std::isfinite(limit)) << "the ribbed segment's Neo-Hookean wall has a limit point";
  auto send = [&pub](double gauge_pa) {
    sensor_msgs::FluidPressure m;
    m.header.stamp = ros::Time::now();
    m.fluid_pressure = gauge_pa + pf_test::kAtm;
    pub.publish(m);
  };

  // Below the limit: the model's shape.
  send(0.8 * limit);
  ASSERT_TRUE(waitFor([] { return countOf(joints) > 0; }, 10));
  pf::FingerWorkspace ws(model);
  const pf::FingerState& below = model.evaluate(0.8 * limit, ws);
  const sensor_msgs::JointState shown = lastOf(joints);
  for (int i = 0; i < model.chamberCount(); ++i) EXPECT_NEAR(shown.position[i], below.joint_angle_rad[i], 1e-12);
  const pf::FingerModelState shape = lastOf(states);
  EXPECT_EQ(shape.status, pf::FingerModelState::STATUS_OK);

  // At and beyond it: finger_state repeats the last shape and says why; no joint_states.
  const std::size_t joints_before = countOf(joints), states_before = countOf(states);
  for (double share : {1.0, 1.3}) {
    send(share * limit);
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_TRUE(waitFor([&] { return countOf(states) >= states_before + 2; }, 10));
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(countOf(joints), joints_before) << "joint_states published past the limit point";
  const pf::FingerModelState past = lastOf(states);
  EXPECT_EQ(past.status, pf::FingerModelState::STATUS_BEYOND_LIMIT_POINT);
  EXPECT_EQ(past.gauge_pa, shape.gauge_pa) << "the repeated shape keeps its own pressure";
  EXPECT_EQ(past.joint_angle_rad, shape.joint_angle_rad);
  EXPECT_EQ(past.tip_angle_rad, shape.tip_angle_rad);
  ASSERT_TRUE(waitFor(
      [] {
        if (countOf(diagnostics) == 0) return false;
        const auto d = lastOf(diagnostics);
        return d.message.find("limit point") != std::string::npos;
      },
      5));
  EXPECT_EQ(lastOf(diagnostics).level, diagnostic_msgs::DiagnosticStatus::WARN);
  // Where the finger snaps, the model's: for this Neo-Hookean wall its limit point.
  const std::vector<diagnostic_msgs::KeyValue> values = lastOf(diagnostics).values;
  const auto snap = std::find_if(values.begin(), values.end(),
                                 [](const diagnostic_msgs::KeyValue& kv) { return kv.key == "snap pressure (Pa gauge)"; });
  ASSERT_NE(snap, values.end());
  EXPECT_EQ(snap->value, pf::formatMessage(model.snapGaugePa()));
  EXPECT_EQ(model.snapGaugePa(), limit);

  // Below it again: a new shape.
  send(0.5 * limit);
  ASSERT_TRUE(waitFor([&] { return countOf(joints) > joints_before; }, 10));
  EXPECT_EQ(lastOf(states).status, pf::FingerModelState::STATUS_OK);
  EXPECT_LT(lastOf(joints).position[0], shown.position[0]);
}

// The ramp up through the snap and down again: each pressure's finger_state and joint_states are the model's on the
// same path (a workspace that saw the same pressures), with the jump up and the jump back both published.
TEST(FingerNodeLimitPoint, AGentWallSnapsThroughAndBackAndBothJumpsArePublished) {
  ros::NodeHandle nh;
  const FingerTopics<sensor_msgs::FluidPressure> topics(nh, "gent/", "pressure", gent_joints, gent_states);
  ASSERT_TRUE(topics.connect(30));
  ros::Publisher pub = topics.input;
  const pf::FingerModel model = ribbedModel(50.0);
  const double limit = model.limitGaugePa(), turning = model.farTurningGaugePa();
  ASSERT_TRUE(std::isfinite(turning)) << "a Gent wall with J_m = 50 stiffens again past its limit";
  pf::FingerWorkspace ws(model);
  struct Step {
    double gauge_pa;
    std::uint8_t status;
  };
  const std::uint8_t ok = pf::FingerModelState::STATUS_OK, snapped = pf::FingerModelState::STATUS_SNAPPED_THROUGH;
  // 1.01 x the limit: the absolute pressure's round trip through the message moves the gauge pressure by an ulp.
  const Step ramp[] = {{0.9 * limit, ok},           {1.01 * limit, snapped},   {1.2 * limit, snapped},
                       {0.5 * (limit + turning), snapped}, {0.9 * turning, ok}, {0.5 * turning, ok}};
  double previous_tip = 0.0;
  for (const Step& step : ramp) {
    SCOPED_TRACE(step.gauge_pa);
    const std::size_t states_before = countOf(gent_states), joints_before = countOf(gent_joints);
    sensor_msgs::FluidPressure m;
    m.header.stamp = ros::Time::now();
    m.fluid_pressure = step.gauge_pa + pf_test::kAtm;
    pub.publish(m);
    ASSERT_TRUE(waitFor([&] { return countOf(gent_states) > states_before && countOf(gent_joints) > joints_before; },
                        10));
    // The node's gauge pressure is the message's absolute one less P_o: the model at that pressure.
    const pf::FingerState& want = model.evaluate((step.gauge_pa + pf_test::kAtm) - pf_test::kAtm, ws);
    const pf::FingerModelState got = lastOf(gent_states);
    // On its far branch this finger curls past a full turn: the status says its backbone meets itself, over the
    // snap, which snapped_through still carries.
    const bool meets = pf::backboneMeetsItself(want.backbone_m, want.joint_angle_rad.data());
    EXPECT_EQ(got.status, meets ? std::uint8_t{pf::FingerModelState::STATUS_MEETS_ITSELF} : step.status);
    EXPECT_EQ(static_cast<bool>(got.snapped_through[0]), step.status == snapped);
    EXPECT_EQ(got.tip_angle_rad, want.tip_angle_rad);
    const sensor_msgs::JointState shown = lastOf(gent_joints);
    for (int i = 0; i < model.chamberCount(); ++i) EXPECT_EQ(shown.position[i], want.joint_angle_rad[i]) << i;
    if (step.gauge_pa == 1.01 * limit) {
      EXPECT_GT(got.tip_angle_rad, previous_tip + 0.3) << "the jump up";
    }
    if (step.gauge_pa == 0.9 * turning) {
      EXPECT_LT(got.tip_angle_rad, previous_tip - 0.3) << "the jump back";
    }
    previous_tip = got.tip_angle_rad;
  }
}

std::vector<sensor_msgs::JointState> volume_joints;
std::vector<pf::FingerModelState> volume_states;

// Volume in: each accepted volume's finger is the core's evaluateVolume, its pressure the answer, past the pressure's
// limit point too (where a pressure gets STATUS_BEYOND_LIMIT_POINT); a NaN volume is refused and nothing published.
TEST(FingerNodeLimitPoint, DrivenByVolumeTheNeoHookeanWallIsFollowedPastItsLimitPoint) {
  ros::NodeHandle nh;
  const FingerTopics<std_msgs::Float64> topics(nh, "volume/", "supplied_volume", volume_joints, volume_states);
  ASSERT_TRUE(topics.connect(30));
  ros::Publisher pub = topics.input;
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/marchese2015_ribbed.yaml", raw);
  raw["dead_volume_m3"] = {{1e-5}, false};
  const pf::FingerModel model(pf::FingerParameters::fromRaw(raw));
  pf::FingerWorkspace ws(model);
  const double at_limit = model.suppliedVolumeAt(model.belowLimitGaugePa());
  ASSERT_EQ(model.volumeLimitM3(), std::numeric_limits<double>::infinity()) << "10 mL of gas: no volume snap";
  double previous_tip = 0.0;
  for (double share : {0.5, 1.5, 3.0}) {
    SCOPED_TRACE(share);
    const std::size_t before = countOf(volume_joints);
    std_msgs::Float64 m;
    m.data = share * at_limit;
    pub.publish(m);
    ASSERT_TRUE(waitFor([&] { return countOf(volume_joints) > before && countOf(volume_states) > 0; }, 10));
    ros::WallDuration(0.05).sleep();
    const pf::FingerState& want = model.evaluateVolume(m.data, ws);
    const pf::FingerModelState got = lastOf(volume_states);
    // Three times the limit point's volume curls it past a full turn: said, the shape still published.
    const bool meets = pf::backboneMeetsItself(want.backbone_m, want.joint_angle_rad.data());
    EXPECT_EQ(meets, share == 3.0);
    EXPECT_EQ(got.status, meets ? pf::FingerModelState::STATUS_MEETS_ITSELF : pf::FingerModelState::STATUS_OK);
    EXPECT_EQ(got.gauge_pa, want.gauge_pa);
    EXPECT_EQ(got.supplied_volume_m3, m.data);
    EXPECT_EQ(got.tip_angle_rad, want.tip_angle_rad);
    const sensor_msgs::JointState shown = lastOf(volume_joints);
    for (int i = 0; i < model.chamberCount(); ++i) EXPECT_EQ(shown.position[i], want.joint_angle_rad[i]) << i;
    if (share > 1.0) {
      EXPECT_LT(got.gauge_pa, model.limitGaugePa()) << "past the limit the pressure has fallen";
    }
    EXPECT_GT(got.tip_angle_rad, previous_tip) << "and the finger bends on";
    previous_tip = got.tip_angle_rad;
  }
  const std::size_t joints_before = countOf(volume_joints), states_before = countOf(volume_states);
  std_msgs::Float64 nan;
  nan.data = std::numeric_limits<double>::quiet_NaN();
  pub.publish(nan);
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(countOf(volume_joints), joints_before) << "a NaN volume is refused";
  EXPECT_EQ(countOf(volume_states), states_before);
  // A volume drawn out is the straight finger with STATUS_VACUUM and the gas's vacuum, as Python
  // and finger_model give it (before: the last shape, with STATUS_BEYOND_LIMIT_POINT).
  std_msgs::Float64 drawn;
  drawn.data = -1e-6;
  pub.publish(drawn);
  ASSERT_TRUE(waitFor([&] { return countOf(volume_joints) > joints_before; }, 10));
  ros::WallDuration(0.05).sleep();
  const pf::FingerState& want = model.evaluateVolume(drawn.data, ws);
  ASSERT_EQ(want.status, pf::EvaluationStatus::kVacuum);
  const pf::FingerModelState got = lastOf(volume_states);
  EXPECT_EQ(got.status, pf::FingerModelState::STATUS_VACUUM);
  EXPECT_EQ(got.gauge_pa, want.gauge_pa);
  EXPECT_DOUBLE_EQ(got.gauge_pa, 101325.0 * -1e-6 / (1e-5 + 1e-6)) << "the dead gas's isothermal vacuum";
  EXPECT_EQ(got.tip_angle_rad, 0.0);
}

std::vector<pf::FingerModelState> object_states;

// Volume in, an object in reach (a sphere in the finger's own frame, cut by the bending plane into the disk the core
// test uses): each volume's pressure is gaugeForVolumeInContact's, its joints the contact rule's there, and
// finger_state's supplied_volume_m3 gives the volume back; joints the object holds are flagged.
TEST(FingerNodeLimitPoint, DrivenByVolumeAFingerOnAnObjectTakesTheContactRulesVolume) {
  ros::NodeHandle nh;
  const ros::Subscriber sub_s = collect(nh, "volume_object/finger_state", object_states);
  ros::Publisher pub = nh.advertise<std_msgs::Float64>("volume_object/supplied_volume", 10);
  ros::Publisher object_pub = nh.advertise<pf::GraspObject>("volume_object/grasp_object", 1, true);
  ASSERT_TRUE(waitFor([&] { return pub.getNumSubscribers() > 0 && sub_s.getNumPublishers() > 0; }, 30));
  ASSERT_TRUE(waitFor([&] { return object_pub.getNumSubscribers() > 0; }, 30));
  object_pub.publish(pf_test::sphereObject(pf::segmentLinkName("vobj_", 0), "sphere", 0.01, 0.075, 0.035));
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/finger.yaml", raw);
  raw["dead_volume_m3"] = {{2e-5}, false};
  const pf::FingerModel model(pf::FingerParameters::fromRaw(raw));
  pf::ContactTracker tracker(model, pf::Obstacle::disk(0.075, 0.035, 0.01));
  const auto contact_at = [&](double p) { return tracker.solve(p); };
  const double most = pf::suppliedVolumeInContact(model, tracker.solve(pf::kModelMaxGaugePa), pf::kModelMaxGaugePa);
  for (double share : {0.3, 0.9}) {
    SCOPED_TRACE(share);
    double gauge = 0.0;
    std::string why;
    ASSERT_TRUE(pf::gaugeForVolumeInContact(model, contact_at, share * most, pf::kModelMaxGaugePa, gauge, why)) << why;
    const pf::ContactState want = tracker.solve(gauge);
    std_msgs::Float64 m;
    m.data = share * most;
    // The object comes in on its own topic: volumes are sent until a state in contact at this pressure comes back.
    ASSERT_TRUE(waitFor(
        [&] {
          pub.publish(m);
          ros::WallDuration(0.05).sleep();
          return countOf(object_states) > 0 && lastOf(object_states).gauge_pa == gauge;
        },
        10));
    const pf::FingerModelState got = lastOf(object_states);
    EXPECT_EQ(got.status, pf::FingerModelState::STATUS_OK);
    EXPECT_NEAR(got.supplied_volume_m3, m.data, 1e-12 * most);
    for (int i = 0; i < model.chamberCount(); ++i) {
      EXPECT_EQ(got.joint_angle_rad[i], want.joint_angle_rad[i]) << i;
      EXPECT_EQ(static_cast<bool>(got.held_by_contact[i]), static_cast<bool>(want.held[static_cast<std::size_t>(i)]))
          << i;
    }
  }
  EXPECT_EQ(tracker.solve(lastOf(object_states).gauge_pa).status, pf::ContactState::Status::kInContact);
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "finger_node_limit_test", 2); }
