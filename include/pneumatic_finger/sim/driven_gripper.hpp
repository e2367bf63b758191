// The gripper's fingers in a MuJoCo scene, driven by one pressure (docs/SIMULATION.md): a twin and its springs
// (PressureDrivenFinger) per finger, which body belongs to which finger, and what each finger's contacts with one geom
// (the part) are. What a grasp-and-lift trial and the cell share. ROS-free; needs libmujoco-dev.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/description/finger_urdf.hpp"
#include "pneumatic_finger/sim/mjcf_text.hpp"
#include "pneumatic_finger/sim/pressure_driven_finger.hpp"

namespace pneumatic_finger {

class DrivenGripper {
 public:
  /// The fingers of @p fingers in @p model (each found by its mount's prefix), against the geom @p part_geom.
  /// @throws ParameterError as PressureDrivenFinger
  DrivenGripper(const std::vector<GripperFinger>& fingers, mjModel* model, int part_geom);

  /// Every finger's springs at @p gauge_pa: with the twin's held moments at @p data's angles (applyPressureWithHeld
  /// Moments), or, with @p held_moments false, applyPressure's linear springs. false, with @p why, where the twin has
  /// no shape at the pressure.
  bool apply(double gauge_pa, const mjData& data, bool held_moments, std::string& why);

  /// Per finger: how many contacts it has with the part now, and their normal forces on it, summed (N).
  std::vector<int> partContacts(const mjData& data) const;
  std::vector<double> partNormalForcesN(const mjData& data) const;

  const std::vector<PressureDrivenFinger>& fingers() const { return driven_; }

 private:
  // Calls @p each(finger, contact index) for every contact of the part with a finger.
  template <class Each>
  void forEachPartContact(const mjData& data, Each&& each) const;

  const mjModel* model_;
  std::vector<std::unique_ptr<FingerModel>> twins_;
  std::vector<PressureDrivenFinger> driven_;
  std::vector<int> finger_of_body_;  // per body: the finger it belongs to, or -1
  int part_geom_ = -1;
};

/// The number of warnings MuJoCo has raised on @p data so far.
int mujocoWarnings(const mjData& data);

/// Whether every position in @p data is finite (a diverged step is not).
bool stateIsFinite(const mjModel& model, const mjData& data);

}  // namespace pneumatic_finger
