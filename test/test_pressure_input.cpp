// The node's input rules (PressureInputPolicy), driven with synthetic times: no master, no sleeps.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "pneumatic_finger/core/pressure_input.hpp"
#include "pneumatic_finger/core/units.hpp"

namespace pf = pneumatic_finger;

namespace {

constexpr double kAtm = pf::kStandardAtmospherePa;

pf::PressureInputSettings settings() {
  pf::PressureInputSettings s;
  s.atmospheric_pa = kAtm;
  s.max_gauge_pa = 3e5;
  s.validated_max_gauge_pa = 2e5;
  s.stamp_tolerance_s = 1.0;
  s.time_jump_s = 1.0;
  s.stale_timeout_s = 1.0;
  return s;
}

}  // namespace

TEST(PressureInput, AcceptsAGoodMessageWithItsStampAndGauge) {
  pf::PressureInputPolicy p(settings());
  const auto d = p.onMessage(kAtm + 1e5, 100.0, 100.01);
  EXPECT_EQ(d.verdict, pf::InputVerdict::kAccept);
  EXPECT_EQ(d.gauge_pa, 1e5);
  EXPECT_EQ(d.stamp_s, 100.0);
  EXPECT_FALSE(d.stamp_replaced);
  EXPECT_TRUE(d.problem.empty());
  EXPECT_EQ(p.report(100.5).level, pf::InputHealth::kOk);
}

TEST(PressureInput, SteadyZeroStampsAreTheReceiveTimeCountedAndOk) {
  // What `rostopic pub -r 10` sends: no stamp. Normal input, not a fault: diagnostics stay OK.
  pf::PressureInputPolicy p(settings());
  for (int i = 0; i < 50; ++i) {
    const double t = 10.0 + 0.1 * i;
    const auto d = p.onMessage(kAtm + 5e4, 0.0, t);
    ASSERT_EQ(d.verdict, pf::InputVerdict::kAccept) << i;
    EXPECT_EQ(d.stamp_s, t);
    EXPECT_TRUE(d.stamp_replaced);
    EXPECT_TRUE(d.problem.empty());
  }
  EXPECT_EQ(p.counters().zero_stamps, 50);
  EXPECT_EQ(p.report(15.0).level, pf::InputHealth::kOk);
}

TEST(PressureInput, ZeroStampsWithinOneClockTickAreDroppedNotRefused) {
  // Simulated time advances in steps: two unstamped messages in one step would be the same instant twice.
  pf::PressureInputPolicy p(settings());
  EXPECT_EQ(p.onMessage(kAtm + 1e4, 0.0, 5.0).verdict, pf::InputVerdict::kAccept);
  EXPECT_EQ(p.onMessage(kAtm + 2e4, 0.0, 5.0).verdict, pf::InputVerdict::kThrottled);
  EXPECT_EQ(p.onMessage(kAtm + 3e4, 0.0, 5.01).verdict, pf::InputVerdict::kAccept);
  EXPECT_EQ(p.counters().refused_out_of_order, 0);
  EXPECT_EQ(p.report(5.02).level, pf::InputHealth::kOk);
}

TEST(PressureInput, FarStampsAreReplacedAndReported) {
  pf::PressureInputPolicy p(settings());
  const auto d = p.onMessage(kAtm + 1e5, 5000.0, 100.0);
  EXPECT_EQ(d.verdict, pf::InputVerdict::kAccept);
  EXPECT_EQ(d.stamp_s, 100.0);
  EXPECT_NE(d.problem.find("replaced by the receive time"), std::string::npos);
  EXPECT_EQ(p.counters().far_stamps, 1);
  const auto r = p.report(100.5);
  EXPECT_EQ(r.level, pf::InputHealth::kWarn);
  EXPECT_NE(r.message.find("replaced by the receive time"), std::string::npos);
  // The report holds the problem for kProblemHoldS, then recovers while input keeps coming.
  for (double t = 100.1; t < 106.0; t += 0.1) p.onMessage(kAtm + 1e5, t, t);
  EXPECT_EQ(p.report(106.0).level, pf::InputHealth::kOk);
}

TEST(PressureInput, SlightlyOlderStampsAreRefusedAsOutOfOrder) {
  pf::PressureInputPolicy p(settings());
  ASSERT_EQ(p.onMessage(kAtm + 1e5, 50.0, 50.0).verdict, pf::InputVerdict::kAccept);
  const auto older = p.onMessage(kAtm + 1.2e5, 49.95, 50.05);
  EXPECT_EQ(older.verdict, pf::InputVerdict::kRefusedOutOfOrder);
  EXPECT_NE(older.problem.find("not newer"), std::string::npos);
  EXPECT_EQ(p.onMessage(kAtm + 1.2e5, 50.0, 50.06).verdict, pf::InputVerdict::kRefusedOutOfOrder);  // same instant
  EXPECT_EQ(p.counters().refused_out_of_order, 2);
  EXPECT_EQ(p.counters().time_jumps, 0);
  EXPECT_EQ(p.onMessage(kAtm + 1.2e5, 50.1, 50.1).verdict, pf::InputVerdict::kAccept);
}

TEST(PressureInput, TheClockJumpingBackStartsANewTimeline) {
  // A bag played with --clock --loop, or a simulation reset: ROS time itself goes back.
  pf::PressureInputPolicy p(settings());
  for (double t = 20.0; t < 30.0; t += 0.1) ASSERT_EQ(p.onMessage(kAtm + 1e5, t, t).verdict, pf::InputVerdict::kAccept);
  const auto d = p.onMessage(kAtm + 1e5, 0.5, 0.5);
  EXPECT_EQ(d.verdict, pf::InputVerdict::kAccept);
  EXPECT_TRUE(d.time_jumped);
  EXPECT_NE(d.problem.find("jumped back"), std::string::npos);
  EXPECT_EQ(d.stamp_s, 0.5);
  EXPECT_EQ(p.counters().time_jumps, 1);
  // Said once: the next messages of the new timeline are ordinary, and diagnostics are not stuck.
  const auto next = p.onMessage(kAtm + 1e5, 0.6, 0.6);
  EXPECT_EQ(next.verdict, pf::InputVerdict::kAccept);
  EXPECT_FALSE(next.time_jumped);
  EXPECT_EQ(p.report(0.65).level, pf::InputHealth::kOk);
  EXPECT_EQ(p.counters().time_jumps, 1);
}

TEST(PressureInput, StampsJumpingBackFarOnASteadyClockStartANewTimeline) {
  // A bag replayed without --clock whose stamps are within stamp_tolerance of now (say, recorded minutes ago on
  // this clock): the stamps go back by more than time_jump_s.
  auto s = settings();
  s.stamp_tolerance_s = 100.0;
  pf::PressureInputPolicy p(s);
  ASSERT_EQ(p.onMessage(kAtm + 1e5, 90.0, 100.0).verdict, pf::InputVerdict::kAccept);
  const auto d = p.onMessage(kAtm + 1e5, 60.0, 100.1);
  EXPECT_EQ(d.verdict, pf::InputVerdict::kAccept);
  EXPECT_TRUE(d.time_jumped);
  EXPECT_EQ(d.stamp_s, 60.0);
}

TEST(PressureInput, BadValuesAreRefusedNamingThem) {
  pf::PressureInputPolicy p(settings());
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(p.onMessage(nan, 1.0, 1.0).verdict, pf::InputVerdict::kRefusedNotFinite);
  EXPECT_EQ(p.onMessage(inf, 1.1, 1.1).verdict, pf::InputVerdict::kRefusedNotFinite);
  const auto neg = p.onMessage(-5.0, 1.2, 1.2);
  EXPECT_EQ(neg.verdict, pf::InputVerdict::kRefusedNegativeAbsolute);
  EXPECT_NE(neg.problem.find("negative"), std::string::npos);
  EXPECT_EQ(p.counters().refused_not_finite, 2);
  EXPECT_EQ(p.counters().refused_negative_absolute, 1);
  EXPECT_EQ(p.report(1.3).level, pf::InputHealth::kWarn);
}

// Above the range: test_pressure_range.cpp (PressureRange.TheNodesInputPolicySaysTheSameWords), with the words.

TEST(PressureInput, ThrottlingKeepsOneMessagePerPeriod) {
  auto s = settings();
  s.max_rate_hz = 10.0;
  pf::PressureInputPolicy p(s);
  int accepted = 0;
  for (int i = 0; i < 100; ++i) {  // 1 kHz for 0.1 s
    const double t = 1.0 + 0.001 * i;
    accepted += p.onMessage(kAtm + 1e5 + i, t, t).verdict == pf::InputVerdict::kAccept;
  }
  EXPECT_EQ(accepted, 1);
  EXPECT_EQ(p.counters().throttled, 99);
  EXPECT_EQ(p.report(1.1).level, pf::InputHealth::kOk);  // throttling is not a problem
}

TEST(PressureInput, SilenceIsStaleThenRecovers) {
  pf::PressureInputPolicy p(settings());
  EXPECT_EQ(p.report(0.0).level, pf::InputHealth::kWarn);  // nothing received yet
  p.onMessage(kAtm + 1e5, 10.0, 10.0);
  EXPECT_EQ(p.report(10.9).level, pf::InputHealth::kOk);
  const auto stale = p.report(12.0);
  EXPECT_EQ(stale.level, pf::InputHealth::kError);
  EXPECT_NE(stale.message.find("stale"), std::string::npos);
  EXPECT_DOUBLE_EQ(stale.age_s, 2.0);
  p.onMessage(kAtm + 1e5, 12.5, 12.5);
  EXPECT_EQ(p.report(12.6).level, pf::InputHealth::kOk);
}

TEST(PressureInput, InputRateCountsTheLastSecond) {
  pf::PressureInputPolicy p(settings());
  for (int i = 0; i < 30; ++i) p.onMessage(kAtm + 1e5, 0.0, 5.0 + 0.0625 * i);  // 16 Hz, times exact in binary
  EXPECT_EQ(p.report(6.8125).rate_hz, 17.0);  // receive times 5.8125 .. 6.8125
}

TEST(PressureInput, SolverFailuresAndVacuumAreReported) {
  pf::PressureInputPolicy p(settings());
  p.onMessage(kAtm - 4e4, 1.0, 1.0);
  p.noteVacuum(-4e4, 1.0);
  EXPECT_NE(p.report(1.1).message.find("vacuum"), std::string::npos);
  p.noteSolverFailure("solver 'paper' found no finite answer", 1.2);
  EXPECT_EQ(p.counters().solver_failures, 1);
  EXPECT_EQ(p.counters().vacuum, 1);
  EXPECT_NE(p.report(1.3).message.find("no finite answer"), std::string::npos);
}

// Driven by volume, the reports name the supplied volume, and past the limit point (the pressure falling as the
// volume grows, a state volume control follows) they say so while it lasts.
TEST(PressureInput, VolumeInputReportsNameTheVolumeAndThePastLimitState) {
  pf::PressureInputSettings s = settings();
  s.volume_input = true;
  pf::PressureInputPolicy p(s);
  EXPECT_EQ(p.report(0.0).message, "no supplied volume received yet");
  ASSERT_EQ(p.onVolumeMessage(2e-6, 1.0).verdict, pf::InputVerdict::kAccept);
  p.noteGaugeFromVolume(3e4, false);
  EXPECT_EQ(p.report(1.5).level, pf::InputHealth::kOk);
  EXPECT_EQ(p.report(1.5).message, "ok");
  ASSERT_EQ(p.onVolumeMessage(5e-6, 1.6).verdict, pf::InputVerdict::kAccept);
  p.noteGaugeFromVolume(2.5e4, true);
  const pf::InputReport past = p.report(2.0);
  EXPECT_EQ(past.level, pf::InputHealth::kOk);
  EXPECT_NE(past.message.find("past the wall's limit point"), std::string::npos) << past.message;
  const pf::InputReport stale = p.report(4.0);
  EXPECT_EQ(stale.level, pf::InputHealth::kError);
  EXPECT_NE(stale.message.find("stale: no supplied volume for 2.4 s"), std::string::npos) << stale.message;
  pf::PressureInputPolicy pressure(settings());
  EXPECT_EQ(pressure.report(0.0).message, "no pressure received yet");
}
