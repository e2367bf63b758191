// The gripper's fingers in a MuJoCo scene (driven_gripper.hpp).
#include "pneumatic_finger/sim/driven_gripper.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace pneumatic_finger {

DrivenGripper::DrivenGripper(const std::vector<GripperFinger>& fingers, mjModel* model, int part_geom)
    : model_(model), part_geom_(part_geom) {
  driven_.reserve(fingers.size());
  finger_of_body_.assign(static_cast<std::size_t>(model->nbody), -1);
  for (std::size_t f = 0; f < fingers.size(); ++f) {
    twins_.push_back(std::make_unique<FingerModel>(fingers[f].parameters));
    driven_.emplace_back(*twins_.back(), model, fingers[f].mount.prefix);
    for (int b = 0; b < model->nbody; ++b) {
      const char* name = mj_id2name(model, mjOBJ_BODY, b);
      if (name && std::string(name).rfind(fingers[f].mount.prefix, 0) == 0) finger_of_body_[b] = static_cast<int>(f);
    }
  }
}

bool DrivenGripper::apply(double gauge_pa, const mjData& data, bool held_moments, std::string& why) {
  for (PressureDrivenFinger& finger : driven_) {
    const bool ok = held_moments ? finger.applyPressureWithHeldMoments(gauge_pa, data, why)
                                 : finger.applyPressure(gauge_pa, why);
    if (!ok) return false;
  }
  return true;
}

template <class Each>
void DrivenGripper::forEachPartContact(const mjData& data, Each&& each) const {
  for (int c = 0; c < data.ncon; ++c) {
    const mjContact& contact = data.contact[c];
    const int other = contact.geom1 == part_geom_ ? contact.geom2 : contact.geom2 == part_geom_ ? contact.geom1 : -1;
    const int finger = other < 0 ? -1 : finger_of_body_[static_cast<std::size_t>(model_->geom_bodyid[other])];
    if (finger >= 0) each(static_cast<std::size_t>(finger), c);
  }
}

std::vector<int> DrivenGripper::partContacts(const mjData& data) const {
  std::vector<int> count(driven_.size(), 0);
  forEachPartContact(data, [&count](std::size_t finger, int) { ++count[finger]; });
  return count;
}

std::vector<double> DrivenGripper::partNormalForcesN(const mjData& data) const {
  std::vector<double> force_n(driven_.size(), 0.0);
  forEachPartContact(data, [&](std::size_t finger, int c) {
    mjtNum wrench[6];
    mj_contactForce(model_, &data, c, wrench);
    force_n[finger] += wrench[0];  // the contact frame's first axis is the normal
  });
  return force_n;
}

int mujocoWarnings(const mjData& data) {
  int n = 0;
  for (int w = 0; w < mjNWARNING; ++w) n += data.warning[w].number;
  return n;
}

bool stateIsFinite(const mjModel& model, const mjData& data) {
  for (int k = 0; k < model.nq; ++k) {
    if (!std::isfinite(data.qpos[k])) return false;
  }
  return true;
}

}  // namespace pneumatic_finger
