// A grasp and a lift in MuJoCo (docs/SIMULATION.md, "Does the grasp rule hold?"): the regulator fills the fingers of a
// grasp scene (grasp_scene.hpp) while the object floats where the cell holds it, gravity comes on, the lift carries
// the fingers up on the cell's smoothstep path, and physics says whether the object came along. ROS-free; needs
// libmujoco-dev.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/regulator.hpp"
#include "pneumatic_finger/sim/driven_gripper.hpp"
#include "pneumatic_finger/sim/grasp_scene.hpp"
#include "pneumatic_finger/sim/mjcf_text.hpp"
#include "pneumatic_finger/sim/pressure_driven_finger.hpp"

namespace pneumatic_finger {

/// The lift: the cell's path (core/smoothstep.hpp), at rest at both ends.
struct LiftMotion {
  double height_m = 0.05;               ///< how far the carriage rises (m)
  double peak_acceleration_mps2 = 1.0;  ///< the path's largest acceleration at both ends (m/s^2)
  /// The path's duration T (s), which gives that peak: smoothstepPeakAcceleration(h, T) = a.
  double durationS() const;
  /// Height, velocity and acceleration at @p t_s from the start (clamped to the path).
  void at(double t_s, double& z_m, double& v_mps, double& a_mps2) const;
};

struct GraspTrialSettings {
  double flow_m3_per_s = kCellRegulatorFlowM3PerS;  ///< the regulator's flow into all the fingers (m^3/s)
  double settle_s = 0.3;         ///< after the fill, gravity still off: the grasp settles (s)
  double hang_s = 0.5;           ///< gravity on, the carriage still: the forces are read at the end (s)
  double after_s = 0.5;          ///< after the lift, the carriage still (s)
  double carried_slip_m = 0.005; ///< an object that fell less than this in the grasp was carried (m)
  bool held_moments = true;      ///< the springs press with the twin's held moments (applyPressureWithHeldMoments);
                                 ///< false: applyPressure's linear springs (for comparison)
};

struct GraspTrialOutcome {
  std::vector<double> finger_normal_force_n;  ///< per finger: MuJoCo's normal forces on the object, summed, at the
                                              ///< end of the hang (N)
  double slip_m = 0.0;     ///< how far the object fell relative to the tool from the lift's start to the end (m)
  bool carried = false;    ///< slip_m < carried_slip_m
  std::string problem;     ///< not empty: the simulation went wrong (MuJoCo's warnings, a state not finite)
};

/// One scene, run as often as asked (each run from the scene's initial state).
class GraspLiftTrial {
 public:
  /// @throws ParameterError as graspSceneMjcf, and for fewer than one finger
  GraspLiftTrial(const std::vector<GripperFinger>& fingers, const GraspScene& scene, const MjcfOptions& mjcf);

  /// Fills the fingers to @p grasp_gauge_pa at the regulator's rate, settles, hangs, lifts by @p lift, holds.
  GraspTrialOutcome run(double grasp_gauge_pa, const LiftMotion& lift, const GraspTrialSettings& settings);

  /// The engine's model and its state at the end of the last run (for a look at the contacts).
  const mjModel& model() const { return *model_; }
  const mjData& data() const { return *data_; }

 private:
  // One step with the pressure's springs, the carriage on its path (z, v, a) and gravity on or off. false: a problem.
  bool step(double gauge_pa, double z_m, double v_mps, double a_mps2, bool gravity, std::string& problem);

  std::vector<GripperFinger> fingers_;
  MujocoModelPtr model_;
  MujocoDataPtr data_;
  std::unique_ptr<DrivenGripper> gripper_;
  int lift_dof_ = -1, lift_qpos_ = -1, lift_actuator_ = -1, object_body_ = -1, object_geom_ = -1;
  double gravity_z_ = 0.0;
  bool held_moments_ = true;  // the run's GraspTrialSettings::held_moments
};

}  // namespace pneumatic_finger
