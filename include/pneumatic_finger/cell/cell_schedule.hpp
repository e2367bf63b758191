// The pick-and-place cell's schedule: which phase the cell is in at a time, where the arm is, whether the gripper
// is to be closed and where the object is if the grasp succeeds. ROS-free, so that a unit test drives it with synthetic times; the
// cell_sequencer node only forwards its answers to topics.
#pragma once

#include <string>
#include <vector>

namespace pneumatic_finger {

using ArmJoints = std::vector<double>;

/// The phases of one pick-and-place cycle, in order.
enum class CellPhase { kApproach, kDescendToPick, kGrasp, kLift, kMove, kDescendToPlace, kPlace, kRetreat, kReturn };

/// A phase's human-readable name ("grasp (inflate)", ...).
const char* cellPhaseName(CellPhase phase);

/// The arm's waypoints (joint positions, rad, in the order of the arm's joint names).
struct CellWaypoints {
  ArmJoints home, above_pick, pick, above_place, place;
};

/// Where the object is.
enum class ObjectPlace { kOnPickTable, kHeld, kOnPlaceTable };

/// What the schedule says at one time.
struct CellStep {
  long cycle = 0;                 ///< completed cycles before this time
  CellPhase phase = CellPhase::kApproach;
  double phase_progress = 0.0;    ///< 0..1 within the phase
  ArmJoints arm;                  ///< arm joint positions (rad)
  bool gripper_closed = false;    ///< the gripper is to hold (grasp .. descend to place); the action plans the pressure
  ObjectPlace object = ObjectPlace::kOnPickTable;  ///< where the object is when the grasp succeeds
};

/// The cycle times a schedule runs (s): the phases need a few tenths of a second each, and a cycle longer than ten
/// minutes is a configuration mistake.
constexpr double kMinCycleTimeS = 2.0, kMaxCycleTimeS = 600.0;

class CellSchedule {
 public:
  /// @throws std::invalid_argument when a waypoint's size differs from the others or cycle_time_s is not in [2, 600]
  CellSchedule(CellWaypoints waypoints, double cycle_time_s);

  /// The step at @p t_s seconds since the start (t >= 0).
  CellStep at(double t_s) const;

  /// How long @p phase lasts in each cycle (s).
  double phaseDurationS(CellPhase phase) const;


 private:
  struct Segment {
    CellPhase phase;
    double fraction;          // of the cycle time
    const ArmJoints* from;    // arm motion (the same waypoint twice: hold)
    const ArmJoints* to;
    bool closed;              // the gripper holds
  };
  CellWaypoints waypoints_;
  double cycle_time_s_;
  std::vector<Segment> segments_;
};

}  // namespace pneumatic_finger
