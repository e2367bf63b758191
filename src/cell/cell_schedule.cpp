#include "pneumatic_finger/cell/cell_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "pneumatic_finger/core/smoothstep.hpp"

namespace pneumatic_finger {

const char* cellPhaseName(CellPhase phase) {
  switch (phase) {
    case CellPhase::kApproach: return "approach";
    case CellPhase::kDescendToPick: return "descend to pick";
    case CellPhase::kGrasp: return "grasp (inflate)";
    case CellPhase::kLift: return "lift";
    case CellPhase::kMove: return "move";
    case CellPhase::kDescendToPlace: return "descend to place";
    case CellPhase::kPlace: return "place (deflate)";
    case CellPhase::kRetreat: return "retreat";
    case CellPhase::kReturn: return "return";
  }
  return "?";
}

CellSchedule::CellSchedule(CellWaypoints waypoints, double cycle_time_s)
    : waypoints_(std::move(waypoints)), cycle_time_s_(cycle_time_s) {
  const auto& w = waypoints_;
  for (const ArmJoints* v : {&w.above_pick, &w.pick, &w.above_place, &w.place}) {
    if (v->size() != w.home.size()) throw std::invalid_argument("every waypoint needs as many joints as 'home'");
  }
  if (!(cycle_time_s >= kMinCycleTimeS && cycle_time_s <= kMaxCycleTimeS)) {
    throw std::invalid_argument("cycle_time_s must be in [" + std::to_string(int(kMinCycleTimeS)) + ", " +
                                std::to_string(int(kMaxCycleTimeS)) + "]");
  }
  // Fractions of the cycle: the grasp and release phases last 15 % (1.8 s of a 12 s cycle), long enough for the
  // regulator's fill to finish before the arm moves.
  segments_ = {
      {CellPhase::kApproach, 0.14, &w.home, &w.above_pick, false},
      {CellPhase::kDescendToPick, 0.10, &w.above_pick, &w.pick, false},
      {CellPhase::kGrasp, 0.15, &w.pick, &w.pick, true},
      {CellPhase::kLift, 0.10, &w.pick, &w.above_pick, true},
      {CellPhase::kMove, 0.14, &w.above_pick, &w.above_place, true},
      {CellPhase::kDescendToPlace, 0.10, &w.above_place, &w.place, true},
      {CellPhase::kPlace, 0.15, &w.place, &w.place, false},
      // Straight up first: a swing from the place pose would sweep the open fingers through the object just left.
      {CellPhase::kRetreat, 0.06, &w.place, &w.above_place, false},
      {CellPhase::kReturn, 0.06, &w.above_place, &w.home, false},
  };
}

CellStep CellSchedule::at(double t_s) const {
  CellStep step;
  const double t = std::max(0.0, t_s);
  step.cycle = static_cast<long>(t / cycle_time_s_);
  double s = std::fmod(t, cycle_time_s_) / cycle_time_s_;
  std::size_t k = 0;
  while (k + 1 < segments_.size() && s >= segments_[k].fraction) s -= segments_[k++].fraction;
  const Segment& seg = segments_[k];
  step.phase = seg.phase;
  step.phase_progress = std::min(1.0, s / seg.fraction);
  const double u = step.phase_progress;
  const double smooth = smoothstep(u);  // zero velocity at both ends of every motion
  step.arm.resize(seg.from->size());
  for (std::size_t i = 0; i < step.arm.size(); ++i) step.arm[i] = (*seg.from)[i] + smooth * ((*seg.to)[i] - (*seg.from)[i]);
  step.gripper_closed = seg.closed;
  // Held from the end of the grasp until the release starts; before that on the pick table, after it on the place one.
  const bool held = (seg.phase == CellPhase::kGrasp && u >= 1.0) || seg.phase == CellPhase::kLift ||
                    seg.phase == CellPhase::kMove || seg.phase == CellPhase::kDescendToPlace;
  if (held) {
    step.object = ObjectPlace::kHeld;
  } else if (seg.phase == CellPhase::kPlace || seg.phase == CellPhase::kRetreat || seg.phase == CellPhase::kReturn) {
    step.object = ObjectPlace::kOnPlaceTable;
  } else {
    step.object = ObjectPlace::kOnPickTable;
  }
  return step;
}

double CellSchedule::phaseDurationS(CellPhase phase) const {
  double fraction = 0.0;
  for (const Segment& s : segments_) fraction += s.phase == phase ? s.fraction : 0.0;
  return fraction * cycle_time_s_;
}

}  // namespace pneumatic_finger
