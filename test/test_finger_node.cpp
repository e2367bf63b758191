// rostest: the running finger_node against the core model (test/finger_node.test starts it).
#include <dynamic_reconfigure/Reconfigure.h>
#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <visualization_msgs/MarkerArray.h>
#include <ros/topic.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/JointState.h>
#include <tf2/LinearMath/Transform.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <urdf_parser/urdf_parser.h>
#include <visualization_msgs/Marker.h>

#include <sys/wait.h>

#include <limits>
#include <map>
#include <mutex>
#include <set>

#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/PressureForTipAngle.h"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "pneumatic_finger/ros/node_parameters.hpp"
#include "pneumatic_finger/GraspObject.h"
#include "pneumatic_finger/core/contact.hpp"
#include "grasp_object_support.hpp"
#include "ros_test_support.hpp"

namespace pf = pneumatic_finger;

namespace {

const std::string kPrefix = "test_";
const std::array<double, 3> kMountXyz{{0.01, -0.02, 0.03}}, kMountRpy{{0.1, -0.2, 0.3}};

using pf_test::packageParameters;

// Collects everything the node publishes, with who published each tf child frame.
struct Listener {
  std::mutex mutex;
  std::map<ros::Time, sensor_msgs::JointState> joint_states;
  std::map<ros::Time, pf::FingerModelState> finger_states;
  std::map<std::string, std::set<std::string>> frame_publishers;

  void onJointState(const sensor_msgs::JointState::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    joint_states[m->header.stamp] = *m;
  }
  void onFingerState(const pf::FingerModelState::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    finger_states[m->header.stamp] = *m;
  }
  void onTf(const ros::MessageEvent<tf2_msgs::TFMessage const>& event) {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& t : event.getMessage()->transforms) frame_publishers[t.child_frame_id].insert(event.getPublisherName());
  }
};

class FingerNodeTest : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    nh_ = new ros::NodeHandle;
    listener_ = new Listener;
    buffer_ = new tf2_ros::Buffer(ros::Duration(30));
    tf_listener_ = new tf2_ros::TransformListener(*buffer_);
    subs_.push_back(nh_->subscribe("joint_states", 100, &Listener::onJointState, listener_));
    subs_.push_back(nh_->subscribe("finger_state", 100, &Listener::onFingerState, listener_));
    subs_.push_back(nh_->subscribe("/tf", 1000, &Listener::onTf, listener_));
    subs_.push_back(nh_->subscribe("/tf_static", 100, &Listener::onTf, listener_));
    pressure_ = nh_->advertise<sensor_msgs::FluidPressure>("pressure", 100, true);
    // Both ways: the node hears us, and we hear its joint_states and finger_state.
    const ros::Time deadline = ros::Time::now() + ros::Duration(30);
    while ((pressure_.getNumSubscribers() == 0 || subs_[0].getNumPublishers() == 0 ||
            subs_[1].getNumPublishers() == 0) &&
           ros::Time::now() < deadline) {
      ros::Duration(0.05).sleep();
    }
  }

  // Publishes a gauge pressure and waits until the node's joint_states with the same stamp arrive.
  static ros::Time publishAndWait(double gauge_pa) {
    sensor_msgs::FluidPressure msg;
    msg.header.stamp = ros::Time::now();
    msg.fluid_pressure = gauge_pa + 101325.0;
    pressure_.publish(msg);
    const ros::Time deadline = ros::Time::now() + ros::Duration(10);
    while (ros::Time::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(listener_->mutex);
        if (listener_->joint_states.count(msg.header.stamp) && listener_->finger_states.count(msg.header.stamp)) break;
      }
      ros::Duration(0.005).sleep();
    }
    return msg.header.stamp;
  }

  static ros::NodeHandle* nh_;
  static Listener* listener_;
  static tf2_ros::Buffer* buffer_;
  static tf2_ros::TransformListener* tf_listener_;
  static std::vector<ros::Subscriber> subs_;
  static ros::Publisher pressure_;
};

ros::NodeHandle* FingerNodeTest::nh_ = nullptr;
Listener* FingerNodeTest::listener_ = nullptr;
tf2_ros::Buffer* FingerNodeTest::buffer_ = nullptr;
tf2_ros::TransformListener* FingerNodeTest::tf_listener_ = nullptr;
std::vector<ros::Subscriber> FingerNodeTest::subs_;
ros::Publisher FingerNodeTest::pressure_;

const std::vector<double> kGauges = {0.0, 3e4, 98066.5, 150000.0, 196133.0, 280000.0};

}  // namespace

TEST_F(FingerNodeTest, JointStatesEqualTheCoreModel) {
  pf::FingerModel model(packageParameters());
  pf::FingerWorkspace ws(model);
  for (double p : kGauges) {
    const ros::Time stamp = publishAndWait(p);
    std::lock_guard<std::mutex> lock(listener_->mutex);
    ASSERT_TRUE(listener_->joint_states.count(stamp)) << "no joint_states for P = " << p;
    const auto& js = listener_->joint_states[stamp];
    const pf::FingerState& want = model.evaluate(p, ws);
    ASSERT_EQ(js.position.size(), 7u);
    for (int i = 0; i < 7; ++i) {
      EXPECT_EQ(js.name[static_cast<std::size_t>(i)], kPrefix + "joint_" + std::to_string(i + 1));
      // The node runs the same core on the same pressure: the same bits.
      EXPECT_EQ(js.position[static_cast<std::size_t>(i)], want.joint_angle_rad[i]) << "P = " << p;
    }
  }
}

TEST_F(FingerNodeTest, TipFrameResolvesFromTheParentAndEqualsTheModel) {
  pf::FingerModel model(packageParameters());
  pf::FingerWorkspace ws(model);
  tf2::Quaternion mount_q;
  mount_q.setRPY(kMountRpy[0], kMountRpy[1], kMountRpy[2]);
  const tf2::Transform mount(mount_q, tf2::Vector3(kMountXyz[0], kMountXyz[1], kMountXyz[2]));
  for (double p : kGauges) {
    const ros::Time stamp = publishAndWait(p);
    geometry_msgs::TransformStamped got;
    ASSERT_NO_THROW(got = buffer_->lookupTransform("tool0", kPrefix + "tip", stamp, ros::Duration(5))) << "P = " << p;
    const pf::FingerState& want = model.evaluate(p, ws);
    tf2::Quaternion yaw;
    yaw.setRPY(0, 0, want.tip_angle_rad);
    const tf2::Transform expected = mount * tf2::Transform(yaw, tf2::Vector3(want.tip().x(), want.tip().y(), 0));
    // tf composes nine transforms (rounding of order 1e-17 m each), so this one is a tolerance, not an equality.
    EXPECT_NEAR(got.transform.translation.x, expected.getOrigin().x(), 1e-12) << "P = " << p;
    EXPECT_NEAR(got.transform.translation.y, expected.getOrigin().y(), 1e-12);
    EXPECT_NEAR(got.transform.translation.z, expected.getOrigin().z(), 1e-12);
    const tf2::Quaternion r(got.transform.rotation.x, got.transform.rotation.y, got.transform.rotation.z,
                            got.transform.rotation.w);
    EXPECT_NEAR(std::fabs(r.dot(expected.getRotation())), 1.0, 1e-12);
    // Every joint axis too, against the backbone points O_1..O_N.
    for (int n = 1; n <= 7; ++n) {
      const auto seg = buffer_->lookupTransform("tool0", kPrefix + "segment_" + std::to_string(n), stamp);
      const tf2::Vector3 o = mount * tf2::Vector3(want.backbone_m(0, n), want.backbone_m(1, n), 0);
      EXPECT_NEAR(seg.transform.translation.x, o.x(), 1e-12) << "segment " << n;
      EXPECT_NEAR(seg.transform.translation.y, o.y(), 1e-12) << "segment " << n;
    }
  }
}

TEST_F(FingerNodeTest, FingerStateCarriesTheModel) {
  pf::FingerModel model(packageParameters());
  pf::FingerWorkspace ws(model);
  pf::TipUncertainty bars;
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/finger.yaml", raw, &bars);
  ASSERT_EQ(bars.gauge_pa.size(), 4u);
  for (double p : {30000.0, 5e4, 250000.0}) {
    const ros::Time stamp = publishAndWait(p);
    std::lock_guard<std::mutex> lock(listener_->mutex);
    ASSERT_TRUE(listener_->finger_states.count(stamp));
    const auto& s = listener_->finger_states[stamp];
    const pf::FingerState& want = model.evaluate(p, ws);
    EXPECT_EQ(s.header.frame_id, kPrefix + "segment_0");
    // The same core on the same pressure: every number is the same bits.
    EXPECT_EQ(s.gauge_pa, p);
    ASSERT_EQ(s.backbone.size(), 9u);
    for (int n = 0; n < 9; ++n) {
      EXPECT_EQ(s.backbone[static_cast<std::size_t>(n)].x, want.backbone_m(0, n)) << n;
      EXPECT_EQ(s.backbone[static_cast<std::size_t>(n)].y, want.backbone_m(1, n)) << n;
    }
    EXPECT_EQ(s.tip_angle_rad, want.tip_angle_rad);
    EXPECT_EQ(s.supplied_volume_m3, model.suppliedVolumeOf(want));
    EXPECT_GT(s.supplied_volume_m3, 0.0);
    for (int i = 0; i < 7; ++i) {
      const auto k = static_cast<std::size_t>(i);
      EXPECT_EQ(s.stretch[k], want.stretch[i]) << i;
      EXPECT_EQ(s.bulge_m[k], want.bulge_m[i]) << i;
      EXPECT_EQ(s.half_angle_rad[k], want.half_angle_rad[i]) << i;
      EXPECT_EQ(s.joint_angle_rad[k], want.joint_angle_rad[i]) << i;
    }
    EXPECT_TRUE(s.walls_in_contact);
    EXPECT_EQ(s.in_validated_range, p <= 196133.0);
    EXPECT_EQ(s.status, pf::FingerModelState::STATUS_OK);
    // The calibration's error bar, as the parameter file's tip_uncertainty gives it at this pressure (the core's
    // interpolation on the file the node loaded); 250 kPa lies above the calibrated pressures, 30 kPa below them:
    // both extrapolated.
    const pf::TipUncertainty::At bar = bars.at(p);
    EXPECT_EQ(s.tip_angle_uncertainty_rad, bar.tip_angle_rad);
    EXPECT_EQ(s.tip_position_uncertainty_m, bar.tip_position_m);
    EXPECT_EQ(s.tip_uncertainty_extrapolated, p > bars.gauge_pa.back() || p < bars.gauge_pa.front());
    EXPECT_EQ(s.tip_uncertainty_extrapolated, p == 250000.0 || p == 30000.0);
    EXPECT_GT(bar.tip_position_m, 1e-3);  // the file has a real bar: millimetres, not zero
    EXPECT_EQ(s.tip_position_covariance[0], bar.tip_position_m * bar.tip_position_m);
    EXPECT_EQ(s.tip_position_covariance[4], bar.tip_position_m * bar.tip_position_m);
    EXPECT_EQ(s.tip_position_covariance[8], 0.0);
  }
  // The sphere at the tip (latched): the last bar, as a diameter, orange above the calibrated range.
  visualization_msgs::Marker::ConstPtr marker =
      ros::topic::waitForMessage<visualization_msgs::Marker>("tip_uncertainty_marker", *nh_, ros::Duration(10));
  ASSERT_TRUE(marker);
  EXPECT_EQ(marker->header.frame_id, kPrefix + "tip");
  EXPECT_EQ(marker->type, visualization_msgs::Marker::SPHERE);
  EXPECT_TRUE(marker->frame_locked);  // else rviz leaves it where the tip was when it arrived
  EXPECT_EQ(marker->scale.x, 2.0 * bars.at(250000.0).tip_position_m);
  EXPECT_EQ(marker->color.r, 1.0f);
}

TEST_F(FingerNodeTest, UrdfParameterParsesAndNamesTheJointStatesJoints) {
  std::string xml;
  ASSERT_TRUE(nh_->getParam("robot_description", xml));
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  ASSERT_TRUE(model);
  EXPECT_EQ(model->getRoot()->name, "tool0");
  const ros::Time stamp = publishAndWait(1e5);
  std::lock_guard<std::mutex> lock(listener_->mutex);
  const auto& js = listener_->joint_states[stamp];
  ASSERT_EQ(js.name.size(), js.position.size());
  for (std::size_t i = 0; i < js.name.size(); ++i) {
    const auto joint = model->getJoint(js.name[i]);
    ASSERT_TRUE(joint) << js.name[i];
    EXPECT_EQ(joint->type, urdf::Joint::REVOLUTE);
    EXPECT_EQ(joint->axis.z, 1.0);
    // Each joint's own angle lies within its own limits.
    ASSERT_TRUE(joint->limits) << js.name[i];
    EXPECT_LE(joint->limits->lower, js.position[i]) << js.name[i];
    EXPECT_GT(joint->limits->upper, js.position[i]) << js.name[i];
  }
  EXPECT_TRUE(model->getLink(kPrefix + "tip"));
}

TEST_F(FingerNodeTest, EveryFrameHasExactlyOnePublisher) {
  publishAndWait(1.2e5);
  ros::Duration(0.5).sleep();
  std::string xml;
  ASSERT_TRUE(nh_->getParam("robot_description", xml));
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  std::lock_guard<std::mutex> lock(listener_->mutex);
  // Every link below the parent is some frame's child, published by one node; nothing else is published.
  std::set<std::string> links;
  for (const auto& l : model->links_) {
    if (l.first != "tool0") links.insert(l.first);
  }
  std::set<std::string> frames;
  for (const auto& f : listener_->frame_publishers) {
    frames.insert(f.first);
    EXPECT_EQ(f.second.size(), 1u) << f.first << " has " << f.second.size() << " publishers";
  }
  EXPECT_EQ(frames, links);
}

namespace {

// Sets doubles through dynamic_reconfigure's service, as `dynparam set` does; returns the node's answer.
std::map<std::string, double> reconfigure(ros::NodeHandle& nh, const std::map<std::string, double>& values) {
  ros::ServiceClient client = nh.serviceClient<dynamic_reconfigure::Reconfigure>("/finger_node/set_parameters");
  EXPECT_TRUE(client.waitForExistence(ros::Duration(10)));
  dynamic_reconfigure::Reconfigure srv;
  for (const auto& kv : values) {
    dynamic_reconfigure::DoubleParameter d;
    d.name = kv.first;
    d.value = kv.second;
    srv.request.config.doubles.push_back(d);
  }
  EXPECT_TRUE(client.call(srv));
  std::map<std::string, double> answer;
  for (const auto& d : srv.response.config.doubles) answer[d.name] = d.value;
  return answer;
}

}  // namespace

TEST_F(FingerNodeTest, ReconfigureAppliesLiveValidatesAndRepublishesTheUrdf) {
  const pf::FingerParameters package = packageParameters();
  // At start-up the server shows the values the node runs with.
  auto now = reconfigure(*nh_, {});
  EXPECT_EQ(now["shear_modulus_pa"], package.shear_modulus_pa[0]);
  EXPECT_EQ(now["chamber_gap_m"], package.chamber_gap_m[0]);
  EXPECT_EQ(now["base_wall_share"], package.base_wall_share);
  // A new shear modulus: the next pressure is modelled with it, bit for bit, and the URDF's limits follow.
  now = reconfigure(*nh_, {{"shear_modulus_pa", 2.0e8}});
  EXPECT_EQ(now["shear_modulus_pa"], 2.0e8);
  pf::RawParameterMap raw = package.toRaw();
  raw["shear_modulus_pa"] = {{2.0e8}, false};
  const pf::FingerParameters softer = pf::FingerParameters::fromRaw(raw);
  pf::FingerModel model(softer);
  pf::FingerWorkspace ws(model);
  const ros::Time stamp = publishAndWait(150000.0);
  {
    std::lock_guard<std::mutex> lock(listener_->mutex);
    ASSERT_TRUE(listener_->joint_states.count(stamp));
    for (int i = 0; i < 7; ++i) {
      EXPECT_EQ(listener_->joint_states[stamp].position[static_cast<std::size_t>(i)],
                model.evaluate(150000.0, ws).joint_angle_rad[i]);
    }
    // The calibration's error bar belonged to the calibrated actuator: no longer published as if it applied.
    ASSERT_TRUE(listener_->finger_states.count(stamp));
    EXPECT_TRUE(std::isnan(listener_->finger_states[stamp].tip_angle_uncertainty_rad));
    EXPECT_TRUE(std::isnan(listener_->finger_states[stamp].tip_position_uncertainty_m));
  }
  std::string xml;
  ASSERT_TRUE(nh_->getParam("robot_description", xml));
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(xml);
  ASSERT_TRUE(urdf);
  EXPECT_EQ(urdf->getJoint(kPrefix + "joint_1")->limits->upper, model.evaluate(294199.5, ws).joint_angle_rad[0]);
  // A value outside its range is refused, like a bad rosparam: the old value stays, and so does the model.
  now = reconfigure(*nh_, {{"chamber_gap_m", -1.0}});
  EXPECT_EQ(now["chamber_gap_m"], package.chamber_gap_m[0]);
  now = reconfigure(*nh_, {{"max_rate_hz", -5.0}});
  EXPECT_EQ(now["max_rate_hz"], 0.0);
  const ros::Time after = publishAndWait(120000.0);
  {
    std::lock_guard<std::mutex> lock(listener_->mutex);
    ASSERT_TRUE(listener_->joint_states.count(after));
    EXPECT_EQ(listener_->joint_states[after].position[3], model.evaluate(120000.0, ws).joint_angle_rad[3]);
  }
  // Back to the package's actuator for the other tests.
  reconfigure(*nh_, {{"shear_modulus_pa", package.shear_modulus_pa[0]}});
}

TEST_F(FingerNodeTest, InverseServiceRoundTrips) {
  ros::ServiceClient client = nh_->serviceClient<pf::PressureForTipAngle>("pressure_for_tip_angle");
  ASSERT_TRUE(client.waitForExistence(ros::Duration(10)));
  pf::FingerModel model(packageParameters());
  pf::FingerWorkspace ws(model);
  pf::PressureForTipAngle srv;
  srv.request.tip_angle_rad = model.evaluate(123456.0, ws).tip_angle_rad;
  ASSERT_TRUE(client.call(srv));
  EXPECT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_NEAR(srv.response.gauge_pa, 123456.0, 1e-6);
  EXPECT_NEAR(srv.response.absolute_pa, 123456.0 + 101325.0, 1e-6);
  srv.request.tip_angle_rad = 2.5;  // needs more than max_gauge_pa
  ASSERT_TRUE(client.call(srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("needs more than"), std::string::npos) << srv.response.message;
  // A refusal names what was wrong and nothing else, with the number as the user wrote it (not the double's 17
  // digits, "-0.10000000000000001"); a NaN reads as "nan" (printf's "-nan" reads like a number).
  srv.request.tip_angle_rad = -0.1;
  ASSERT_TRUE(client.call(srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_EQ(srv.response.message, "tip angle -0.1 rad is not a finite angle >= 0 (flexion is positive)");
  srv.request.tip_angle_rad = -std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(client.call(srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_EQ(srv.response.message, "tip angle nan rad is not a finite angle >= 0 (flexion is positive)");
}

// The grasp object: out of reach it changes nothing (the free finger, bit for bit); in reach the node's joints are
// the contact rule's (against the core's ContactSolver on the same section); an empty id clears it. The object is
// given in the mount's parent frame, which the node resolves through its own mount.
TEST_F(FingerNodeTest, GraspObjectConstrainsTheFingerAndOutOfReachChangesNothing) {
  const pf::FingerParameters params = packageParameters();
  pf::FingerModel model(params);
  pf::FingerWorkspace ws(model);
  ros::Publisher object_pub = nh_->advertise<pf::GraspObject>("grasp_object", 1, true);
  // rviz's force arrows: the last array the node sent (it sends them only to a subscriber, and only in contact).
  std::mutex arrows_mutex;
  visualization_msgs::MarkerArray arrows;
  ros::Subscriber arrows_sub = nh_->subscribe<visualization_msgs::MarkerArray>(
      "contact_force_markers", 10, [&](const visualization_msgs::MarkerArray::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(arrows_mutex);
        arrows = *m;
      });
  const Eigen::Isometry3d parent_from_finger =
      Eigen::Translation3d(kMountXyz[0], kMountXyz[1], kMountXyz[2]) *
      Eigen::AngleAxisd(kMountRpy[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(kMountRpy[1], Eigen::Vector3d::UnitY()) *
      Eigen::AngleAxisd(kMountRpy[0], Eigen::Vector3d::UnitX());
  auto publishSphere = [&](const std::string& id, const Eigen::Vector3d& in_finger, double radius) {
    const Eigen::Vector3d c = parent_from_finger * in_finger;
    pf::GraspObject o = pf_test::sphereObject("tool0", id, radius, c.x(), c.y(), c.z());
    const Eigen::Quaterniond q(parent_from_finger.rotation());
    o.pose.orientation.x = q.x(), o.pose.orientation.y = q.y(), o.pose.orientation.z = q.z(), o.pose.orientation.w = q.w();
    object_pub.publish(o);
  };
  auto waitForStatus = [&](uint8_t status, const std::string& id) {
    const ros::Time deadline = ros::Time::now() + ros::Duration(10);
    while (ros::Time::now() < deadline) {
      const ros::Time stamp = publishAndWait(196133.0);
      std::lock_guard<std::mutex> lock(listener_->mutex);
      const auto& s = listener_->finger_states[stamp];
      if (s.object_status == status && s.object_id == id) return stamp;
      ros::Duration(0.05).sleep();
    }
    ADD_FAILURE() << "object status " << int(status) << " for '" << id << "' never seen";
    return ros::Time();
  };

  // Half a metre away: out of reach, the free finger.
  publishSphere("far", Eigen::Vector3d(0.5, 0.0, 0.0), 0.01);
  ros::Time stamp = waitForStatus(pf::FingerModelState::OBJECT_OUT_OF_REACH, "far");
  {
    std::lock_guard<std::mutex> lock(listener_->mutex);
    const pf::FingerState& free = model.evaluate(196133.0, ws);
    const auto& s = listener_->finger_states[stamp];
    for (int i = 0; i < 7; ++i) EXPECT_EQ(listener_->joint_states[stamp].position[static_cast<std::size_t>(i)], free.joint_angle_rad[i]);
    EXPECT_TRUE(std::isnan(s.touch_gauge_pa));
    EXPECT_TRUE(s.contact_points.empty());
    // No contact, no force: the free joints carry no moment, and joint_states.effort says so.
    EXPECT_TRUE(s.contact_normal_forces_n.empty());
    ASSERT_EQ(s.joint_moment_nm.size(), 7u);
    for (std::size_t k = 0; k < 7; ++k) {
      EXPECT_EQ(s.joint_moment_nm[k], 0.0);
      EXPECT_EQ(listener_->joint_states[stamp].effort.at(k), 0.0);
    }
  }

  // A 12 mm ball 2 mm off the finger's plane: its section is a disk of radius sqrt(12^2 - 2^2) mm.
  publishSphere("ball", Eigen::Vector3d(0.06, 0.03, 0.002), 0.012);
  stamp = waitForStatus(pf::FingerModelState::OBJECT_TOUCHING, "ball");
  const pf::ContactState want =
      pf::ContactSolver(model).solve(196133.0, pf::Obstacle::disk(0.06, 0.03, std::sqrt(0.012 * 0.012 - 0.002 * 0.002)));
  ASSERT_EQ(want.status, pf::ContactState::Status::kInContact);
  std::size_t want_force_count = 0;
  double want_first_force = 0.0;
  {
    std::lock_guard<std::mutex> lock(listener_->mutex);
    const auto& s = listener_->finger_states[stamp];
    const auto& js = listener_->joint_states[stamp];
    for (int i = 0; i < 7; ++i) {
      const auto k = static_cast<std::size_t>(i);
      // The object's pose goes through the mount and back: equal to rounding, not to the bit.
      EXPECT_NEAR(js.position[k], want.joint_angle_rad[i], 1e-12) << "joint " << i + 1;
      EXPECT_EQ(s.joint_angle_rad[k], js.position[k]);
      EXPECT_EQ(static_cast<bool>(s.held_by_contact[k]), static_cast<bool>(want.held[k])) << "joint " << i + 1;
    }
    EXPECT_NEAR(s.first_touch_gauge_pa, want.first_touch_gauge_pa, 1e-9 * want.first_touch_gauge_pa);
    EXPECT_NEAR(s.touch_gauge_pa, want.first_touch_gauge_pa, 1e-9 * want.first_touch_gauge_pa);
    ASSERT_EQ(s.contact_points.size(), want.contact_points_m.size());
    EXPECT_NEAR(s.contact_points[0].x, want.contact_points_m[0].x(), 1e-9);
    EXPECT_NEAR(s.tip_angle_rad, want.joint_angle_rad.sum(), 1e-12);
    // The force model at the contact (the core's, on the same section): the held joints' moments in finger_state and
    // joint_states.effort, the normal force at each contact point.
    std::vector<double> want_force, want_moment(7);
    pf::contactNormalForcesN(model, 196133.0, want, want_force);
    want_force_count = want_force.size();
    want_first_force = want_force.at(0);
    model.heldJointMomentsNm(196133.0, want.held_since_gauge_pa.data(), want_moment.data());
    ASSERT_EQ(s.contact_normal_forces_n.size(), want_force.size());
    for (std::size_t k = 0; k < want_force.size(); ++k) {
      EXPECT_GT(want_force[k], 0.0);
      EXPECT_NEAR(s.contact_normal_forces_n[k], want_force[k], 1e-9 * want_force[k]) << "contact " << k;
    }
    for (std::size_t k = 0; k < 7; ++k) {
      EXPECT_NEAR(s.joint_moment_nm[k], want_moment[k], 1e-9 * std::fabs(want_moment[k])) << "joint " << k + 1;
      EXPECT_EQ(js.effort.at(k), s.joint_moment_nm[k]);
      EXPECT_EQ(s.joint_moment_nm[k] > 0, static_cast<bool>(want.held[k])) << "joint " << k + 1;
    }
  }
  {
    // An arrow per contact, ending at the contact point (beside the finger), 20 cm per newton (~force_arrow_m_per_n's
    // default).
    publishAndWait(196133.0);
    ros::Duration(0.1).sleep();
    std::lock_guard<std::mutex> lock(arrows_mutex);
    ASSERT_EQ(arrows.markers.size(), want_force_count + 1) << "a DELETEALL, then one arrow per contact";
    EXPECT_EQ(arrows.markers[0].action, visualization_msgs::Marker::DELETEALL);
    const visualization_msgs::Marker& a = arrows.markers[1];
    EXPECT_EQ(a.type, visualization_msgs::Marker::ARROW);
    EXPECT_EQ(a.header.frame_id, kPrefix + "segment_0");
    ASSERT_EQ(a.points.size(), 2u);
    EXPECT_NEAR(a.points[1].x, want.contact_points_m[0].x(), 1e-9);
    EXPECT_NEAR(a.points[1].y, want.contact_points_m[0].y(), 1e-9);
    const double length = std::hypot(a.points[1].x - a.points[0].x, a.points[1].y - a.points[0].y);
    EXPECT_NEAR(length, 0.2 * want_first_force, 1e-9);
  }

  // Cleared: the free finger again.
  pf::GraspObject none;
  object_pub.publish(none);
  stamp = waitForStatus(pf::FingerModelState::OBJECT_NONE, "");
  std::lock_guard<std::mutex> lock(listener_->mutex);
  const pf::FingerState& free = model.evaluate(196133.0, ws);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(listener_->joint_states[stamp].position[static_cast<std::size_t>(i)], free.joint_angle_rad[i]);
}

// A list parameter (as rosparam loads it from a file) reads as a list in the message, each number as written: it printed
// as "0.100000000000000010.20000000000000001" before.
namespace {
// Runs finger_node with @p args (stdout and stderr together) and returns its exit status, -1 if it did not exit.
int runNode(const std::string& args, std::string& out) {
  const std::string cmd = std::string("timeout 30 ") + FINGER_NODE_EXE + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  const int raw = pclose(pipe);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}
}  // namespace

// The physics cell sends its object at 50 Hz as it moves; the node says so once per change of id
// or frame (before: on every message, most of a run's log). The reference is the node's own log, read on /rosout.
TEST_F(FingerNodeTest, AMovingGraspObjectIsLoggedOncePerChange) {
  std::mutex log_mutex;
  int said = 0;
  ros::Subscriber rosout = nh_->subscribe<rosgraph_msgs::Log>("/rosout", 1000, [&](const rosgraph_msgs::Log::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(log_mutex);
    if (m->msg.find("grasp object 'logged_once' in 'tool0'") != std::string::npos) ++said;
  });
  ros::Publisher object_pub = nh_->advertise<pf::GraspObject>("grasp_object", 10, true);
  const ros::Time deadline = ros::Time::now() + ros::Duration(10);
  while ((object_pub.getNumSubscribers() == 0 || rosout.getNumPublishers() == 0) && ros::Time::now() < deadline) {
    ros::Duration(0.02).sleep();
  }
  pf::GraspObject o = pf_test::sphereObject("tool0", "logged_once", 0.01, 0.5, 0.0);
  for (int k = 0; k < 10; ++k) {
    o.pose.position.x = 0.5 + 0.001 * k;  // it moves, as a carried part does
    object_pub.publish(o);
    ros::Duration(0.05).sleep();
  }
  ros::Duration(1.0).sleep();
  {
    std::lock_guard<std::mutex> lock(log_mutex);
    EXPECT_EQ(said, 1);
  }
  o.id.clear();  // the finger free again for the tests after
  object_pub.publish(o);
  ros::Duration(0.2).sleep();
}

// One parameter file serves every interface. The core's readers (finger_model, finger_calibrate,
// Python) skip finger_node's own keys and read the range keys; both lists are held here to the node's own table, so a
// key added to the node is a key the tools accept. Before, volume_topic in a file made the tools fail.
TEST(FingerNodeParameters, TheCoreKnowsEveryKeyOfTheNodeSoThatOneFileServesEveryInterface) {
  std::set<std::string> node, core;
  for (const pf::NodeParameterSpec& spec : pf::nodeParameterSpecs()) node.insert(spec.key);
  for (const std::string& key : pf::nodeInterfaceKeys()) core.insert(key);
  for (const pf::ParameterSpec& spec : pf::rangeParameterSpecs()) core.insert(spec.key);
  EXPECT_EQ(node, core);
  pf::RawParameterMap raw;
  EXPECT_NO_THROW(pf::loadRawParametersFromYamlText("volume_topic: volume\nframe_prefix: a_\n", "f.yaml", raw));
  EXPECT_TRUE(raw.empty()) << "the node's keys are the node's, not the actuator's";
}

TEST(FingerNodeParameters, AListInAMessageReadsAsAList) {
  ros::param::set("/bad_list_node/mount_xyz_m", std::vector<double>{0.1, 0.2});
  std::string out;
  EXPECT_EQ(runNode("__name:=bad_list_node", out), 2) << out;
  EXPECT_NE(out.find("finger_node: error: parameter 'mount_xyz_m' = [0.1, 0.2] must "
                     "be a list of 3 numbers"),
            std::string::npos)
      << out;
  ros::param::del("/bad_list_node/mount_xyz_m");
}

TEST(FingerNodeParameters, EveryBadParameterStopsTheNodeNamingTheKey) {
  std::vector<std::pair<std::string, std::string>> cases = {
      {"_chamber_gap_m:=-1", "chamber_gap_m"},
      {"_chamber_gap_m:=wide", "chamber_gap_m"},
      {"_chamber_count:=2.5", "chamber_count"},
      {"_chamber_gap_m:=[1e-5,2e-5]", "chamber_gap_m"},
      {"_wall_critical_height_m:=0.02", "wall_critical_height_m"},
      {"_frame_prefix:=9fingers", "frame_prefix"},
      {"_frame_prefix:=a-b", "frame_prefix"},
      {"_parent_frame:=/tool0", "parent_frame"},
      {"_mount_xyz_m:=[1,2]", "mount_xyz_m"},
      {"_solver:=quick", "solver"},
      {"_max_rate_hz:=-5", "max_rate_hz"},
      {"_stale_timeout_s:=0", "stale_timeout_s"},
      {"_chamber_gapp_m:=1", "chamber_gapp_m"},
      {"_stamp_tolerance_s:=-1", "stamp_tolerance_s"},
      {"_max_gauge_pa:=0", "max_gauge_pa"},
      {"_validated_max_gauge_pa:=1e9", "validated_max_gauge_pa"},
      {"_frame_prefix:=5", "frame_prefix"},           // an int where a string is due
      {"_parent_frame:=3.5", "parent_frame"},
      {"_mount_rpy_rad:=[0,0,99]", "mount_rpy_rad"},
      {"_mount_xyz_m:=near", "mount_xyz_m"},
      {"_max_rate_hz:=fast", "max_rate_hz"},
      {"_description_param:='bad name'", "description_param"},
      {"_pressure_topic:='a b'", "pressure_topic"},
      {"_joint_states_topic:=7", "joint_states_topic"},
      {"_finger_state_topic:='x y'", "finger_state_topic"},
      // The calibration's error bar, as `rosparam load` of a parameter file puts it under ~tip_uncertainty/ (the
      // command line gives a string, not a list; the lists' own rules are the core's, test_tip_uncertainty.cpp).
      {"_tip_uncertainty/gauge_pa:=[100000.0]", "tip_uncertainty: 'gauge_pa' must be a list of numbers"},
      {"_tip_uncertainty/gauges:=1", "tip_uncertainty: unknown key 'gauges'"},
  };
  // Every actuator key out of its range, as a rosparam (the node's other path in).
  for (const auto& spec : pf::parameterSpecs()) {
    cases.push_back({std::string("_") + spec.key + ":=-7", spec.key});
  }
  int k = 0;
  for (const auto& c : cases) {
    std::string out;
    EXPECT_EQ(runNode("__name:=bad_node_" + std::to_string(k++) + " " + c.first, out), 2) << c.first << ": " << out;
    EXPECT_NE(out.find("finger_node: error: "), std::string::npos) << c.first << ": " << out;
    EXPECT_NE(out.find(c.second), std::string::npos) << c.first << ": " << out;
  }
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "finger_node_test", 2); }
