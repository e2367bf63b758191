// rostest: finger_node under bad input (test/finger_node_faults.test). Each case: the defined behaviour (refuse and
// keep the last state, or a defined safe state), the report on diagnostics, and recovery when good input returns.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/JointState.h>

#include <cmath>
#include <limits>
#include <atomic>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "ros_test_support.hpp"

namespace pf = pneumatic_finger;

namespace {

using pf_test::kAtm;

using pf_test::packageParameters;

class FaultTest : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    nh_ = new ros::NodeHandle;
    subs_.push_back(nh_->subscribe("joint_states", 20000, &FaultTest::onJoints));
    subs_.push_back(nh_->subscribe("finger_state", 20000, &FaultTest::onState));
    subs_.push_back(nh_->subscribe("/diagnostics", 100, &FaultTest::onDiagnostics));
    advertise();
  }
  // Waits both ways: the node listens to our pressure, and we listen to its outputs (else its first answers can go
  // out before our subscriptions connect, on a loaded machine).
  static void advertise() {
    pub_ = nh_->advertise<sensor_msgs::FluidPressure>("pressure", 20000);
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30);
    auto connected = [] {
      return pub_.getNumSubscribers() > 0 && subs_[0].getNumPublishers() > 0 && subs_[1].getNumPublishers() > 0;
    };
    while (!connected() && ros::WallTime::now() < deadline) ros::WallDuration(0.02).sleep();
  }
  static void onJoints(const sensor_msgs::JointState::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    joints_.push_back(*m);
  }
  static void onState(const pf::FingerModelState::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    states_.push_back(*m);
  }
  static void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& s : m->status) {
      if (s.name.find("pressure input") != std::string::npos) diagnostics_.push_back(s);
    }
  }
  static void send(double absolute, ros::Time stamp = ros::Time::now()) {
    sensor_msgs::FluidPressure msg;
    msg.header.stamp = stamp;
    msg.fluid_pressure = absolute;
    pub_.publish(msg);
  }
  static std::size_t jointCount() {
    std::lock_guard<std::mutex> lock(mutex_);
    return joints_.size();
  }
  static sensor_msgs::JointState lastJoints() {
    std::lock_guard<std::mutex> lock(mutex_);
    return joints_.empty() ? sensor_msgs::JointState() : joints_.back();
  }
  static pf::FingerModelState lastState() {
    std::lock_guard<std::mutex> lock(mutex_);
    return states_.empty() ? pf::FingerModelState() : states_.back();
  }
  // Sends a good pressure and waits for its output: the node is alive and the state is the model's.
  static sensor_msgs::JointState sendGoodAndWait(double gauge) {
    const std::size_t before = jointCount();
    send(gauge + kAtm);
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(5);
    while (jointCount() == before && ros::WallTime::now() < deadline) ros::WallDuration(0.005).sleep();
    EXPECT_GT(jointCount(), before) << "no output for a good pressure " << gauge;
    return lastJoints();
  }
  // Sends bad input and checks that nothing is published for it.
  static void expectNothingPublished(const std::function<void()>& bad) {
    const std::size_t before = jointCount();
    bad();
    ros::WallDuration(0.3).sleep();
    EXPECT_EQ(jointCount(), before) << "bad input produced output";
  }
  // The newest diagnostics status that arrives after now and matches @p level, while a working regulator keeps
  // sending good pressures (else the input would go stale and the report would be the stale ERROR).
  static diagnostic_msgs::DiagnosticStatus waitForDiagnostics(unsigned char level, double seconds = 4) {
    std::atomic<bool> stop{false};
    std::thread feeder([&stop] {
      while (!stop) {
        send(100000 + kAtm);
        ros::WallDuration(0.05).sleep();
      }
    });
    const auto status = waitForDiagnosticsQuiet(level, seconds);
    stop = true;
    feeder.join();
    return status;
  }
  static diagnostic_msgs::DiagnosticStatus waitForDiagnosticsQuiet(unsigned char level, double seconds) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      diagnostics_.clear();
    }
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        for (auto it = diagnostics_.rbegin(); it != diagnostics_.rend(); ++it) {
          if (it->level == level) return *it;
        }
      }
      ros::WallDuration(0.05).sleep();
    }
    diagnostic_msgs::DiagnosticStatus none;
    none.message = "(no diagnostics at that level)";
    return none;
  }
  // A diagnostics counter as it stands now, from the next report (whatever its level); 0 before the first count.
  // Tests compare counters before and after, so they do not depend on the order the tests run in.
  static long counterNow(const std::string& key) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      diagnostics_.clear();
    }
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(4);
    while (ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!diagnostics_.empty()) {
          const std::string v = value(diagnostics_.back(), key);
          return v.empty() ? 0 : std::stol(v);
        }
      }
      ros::WallDuration(0.05).sleep();
    }
    ADD_FAILURE() << "no diagnostics within 4 s";
    return -1;
  }
  static std::string value(const diagnostic_msgs::DiagnosticStatus& s, const std::string& key) {
    for (const auto& kv : s.values) {
      if (kv.key == key) return kv.value;
    }
    return "";
  }
  static void expectFinite(const sensor_msgs::JointState& js) {
    for (double q : js.position) EXPECT_TRUE(std::isfinite(q));
  }

  static ros::NodeHandle* nh_;
  static ros::Publisher pub_;
  static std::vector<ros::Subscriber> subs_;
  static std::mutex mutex_;
  static std::vector<sensor_msgs::JointState> joints_;
  static std::vector<pf::FingerModelState> states_;
  static std::vector<diagnostic_msgs::DiagnosticStatus> diagnostics_;
};

ros::NodeHandle* FaultTest::nh_ = nullptr;
ros::Publisher FaultTest::pub_;
std::vector<ros::Subscriber> FaultTest::subs_;
std::mutex FaultTest::mutex_;
std::vector<sensor_msgs::JointState> FaultTest::joints_;
std::vector<pf::FingerModelState> FaultTest::states_;
std::vector<diagnostic_msgs::DiagnosticStatus> FaultTest::diagnostics_;

}  // namespace

TEST_F(FaultTest, NotFinitePressuresAreRefusedAndTheLastStateKept) {
  const auto good = sendGoodAndWait(120000);
  const long refused_before = counterNow("refused: not finite");
  expectNothingPublished([] {
    send(std::numeric_limits<double>::quiet_NaN());
    send(std::numeric_limits<double>::infinity());
    send(-std::numeric_limits<double>::infinity());
  });
  EXPECT_EQ(lastJoints().position, good.position);  // nothing replaced the last valid state
  const auto d = waitForDiagnostics(diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NE(d.message.find("not finite"), std::string::npos) << d.message;
  EXPECT_EQ(std::stol(value(d, "refused: not finite")) - refused_before, 3);
  sendGoodAndWait(130000);  // and good input is taken again
}

TEST_F(FaultTest, NegativeAbsolutePressureIsRefused) {
  sendGoodAndWait(110000);
  expectNothingPublished([] { send(-5.0); });
  const auto d = waitForDiagnostics(diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NE(d.message.find("negative"), std::string::npos) << d.message;
  sendGoodAndWait(110001);
}

TEST_F(FaultTest, VacuumPublishesTheStraightFinger) {
  sendGoodAndWait(150000);
  const auto js = sendGoodAndWait(-40000);  // gauge < 0: outside the model
  ASSERT_EQ(js.position.size(), 7u);
  for (double q : js.position) EXPECT_EQ(q, 0.0);
  EXPECT_EQ(lastState().status, pf::FingerModelState::STATUS_VACUUM);
  const auto d = waitForDiagnostics(diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NE(d.message.find("vacuum"), std::string::npos) << d.message;
  sendGoodAndWait(150000);
  EXPECT_EQ(lastState().status, pf::FingerModelState::STATUS_OK);
}

TEST_F(FaultTest, AbsurdPressureIsClampedToTheModelRange) {
  pf::FingerModel model(packageParameters());
  pf::FingerWorkspace ws(model);
  const pf::FingerState& at_max = model.evaluate(294199.5, ws);
  for (double absurd : {1e12, 1e300}) {
    const auto js = sendGoodAndWait(absurd);
    expectFinite(js);
    ASSERT_EQ(js.position.size(), 7u);
    for (int i = 0; i < 7; ++i) EXPECT_EQ(js.position[static_cast<std::size_t>(i)], at_max.joint_angle_rad[i]);
    EXPECT_EQ(lastState().status, pf::FingerModelState::STATUS_CLAMPED);
    EXPECT_FALSE(lastState().in_validated_range);
  }
  const auto d = waitForDiagnostics(diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NE(d.message.find("clamped"), std::string::npos) << d.message;
  sendGoodAndWait(100000);
  EXPECT_EQ(lastState().status, pf::FingerModelState::STATUS_OK);
}

TEST_F(FaultTest, ZeroAndFarStampsAreReplacedByTheReceiveTime) {
  for (const ros::Time& bad : {ros::Time(0), ros::Time::now() + ros::Duration(3600), ros::Time(1.0)}) {
    const std::size_t before = jointCount();
    const ros::Time sent_at = ros::Time::now();
    send(100000 + kAtm, bad);
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(5);
    while (jointCount() == before && ros::WallTime::now() < deadline) ros::WallDuration(0.005).sleep();
    ASSERT_GT(jointCount(), before);
    const ros::Time got = lastJoints().header.stamp;
    EXPECT_GE(got, sent_at);
    EXPECT_LT((got - sent_at).toSec(), 1.0);
  }
  const auto d = waitForDiagnostics(diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NE(d.message.find("replaced by the receive time"), std::string::npos) << d.message;
}

TEST_F(FaultTest, OutOfOrderAndRepeatedStampsAreRefused) {
  const ros::Time t = ros::Time::now();
  send(100000 + kAtm, t);
  ros::WallDuration(0.2).sleep();
  expectNothingPublished([&] {
    send(120000 + kAtm, t - ros::Duration(0.05));  // older
    send(120000 + kAtm, t);                        // the same instant again
  });
  const auto d = waitForDiagnostics(diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NE(d.message.find("not newer"), std::string::npos) << d.message;
  sendGoodAndWait(125000);  // a newer stamp is taken
}

TEST_F(FaultTest, BurstAtTenKilohertzEndsInTheLastPressureWithTimeOnlyMovingForward) {
  sendGoodAndWait(0);
  std::size_t first;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    first = joints_.size();
  }
  pf::FingerModel model(packageParameters());
  pf::FingerWorkspace ws(model);
  const ros::WallTime start = ros::WallTime::now();
  double last_gauge = 0;
  for (int i = 1; i <= 10000; ++i) {
    last_gauge = 196133.0 * i / 10000;
    send(last_gauge + kAtm);
    // 10 kHz: one message every 100 us of wall time.
    while ((ros::WallTime::now() - start).toSec() < i * 1e-4) {
    }
  }
  const double want = model.evaluate(last_gauge, ws).joint_angle_rad[6];
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(20);
  auto joint7 = [] {
    const auto js = lastJoints();
    return js.position.size() == 7 ? js.position[6] : NAN;
  };
  while (!(std::fabs(joint7() - want) <= 1e-12) && ros::WallTime::now() < deadline) {
    ros::WallDuration(0.01).sleep();
  }
  EXPECT_NEAR(joint7(), want, 1e-12) << "the burst's last pressure was not the final state";
  std::lock_guard<std::mutex> lock(mutex_);
  RecordProperty("burst_messages_published", std::to_string(joints_.size() - first));
  for (std::size_t i = first + 1; i < joints_.size(); ++i) {
    EXPECT_GT(joints_[i].header.stamp, joints_[i - 1].header.stamp);
    expectFinite(joints_[i]);
  }
}

TEST_F(FaultTest, StaleInputIsReportedAndRecovers) {
  sendGoodAndWait(90000);
  ros::WallDuration(1.2).sleep();  // longer than stale_timeout_s = 0.6
  const auto d = waitForDiagnosticsQuiet(diagnostic_msgs::DiagnosticStatus::ERROR, 4);
  EXPECT_NE(d.message.find("stale"), std::string::npos) << d.message;
  // Recovery: good input again, and the report goes back to OK once earlier warnings (held 5 s) have aged out.
  const auto ok = waitForDiagnostics(diagnostic_msgs::DiagnosticStatus::OK, 8);
  EXPECT_EQ(ok.message, "ok");
  // The grasp object's status by its name (it read as a bare number).
  EXPECT_EQ(value(ok, "grasp object status"), "none");
}

TEST_F(FaultTest, RegulatorPublisherRestartIsFollowed) {
  sendGoodAndWait(80000);
  pub_.shutdown();  // the regulator goes away ...
  ros::WallDuration(0.5).sleep();
  advertise();      // ... and comes back
  const auto js = sendGoodAndWait(160000);
  pf::FingerModel model(packageParameters());
  pf::FingerWorkspace ws(model);
  ASSERT_EQ(js.position.size(), 7u);
  EXPECT_NEAR(js.position[3], model.evaluate(160000, ws).joint_angle_rad[3], 1e-12);
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "finger_node_faults_test", 2); }
