// finger_model's warnings about its rows, each said once on stderr, in the words every interface uses. Internal header
// of finger_model (src/tools).
#pragma once

#include <iostream>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"
#include "pneumatic_finger/core/self_contact.hpp"

namespace pneumatic_finger_tools {

namespace pf = pneumatic_finger;

// The warnings of finger_model's rows, each said once (on stderr), in the words every interface uses.
struct RowWarnings {
  bool vacuum = false, failure = false, limit = false, clamp = false, extrapolated = false, snap = false, meets = false;

  // The backbone crossing itself, said once, as every interface says it (self_contact.hpp).
  void noteShape(const pf::FingerState& s) {
    const bool shaped = s.status != pf::EvaluationStatus::kNotFinite && s.status != pf::EvaluationStatus::kSolverFailure &&
                        s.status != pf::EvaluationStatus::kBeyondLimitPoint;
    if (shaped && !meets && pf::backboneMeetsItself(s.backbone_m, s.joint_angle_rad.data())) {
      std::cerr << "finger_model: warning: at " << pf::formatMessage(s.gauge_pa) << " Pa gauge "
                << pf::selfContactMessage(s.tip_angle_rad) << "\n";
      meets = true;
    }
  }

  void note(const pf::FingerModel& model, const pf::FingerState& s, const pf::RangeCheck& range, double requested,
            const pf::PressureRange& limits) {
    const double p = range.gauge_pa;
    if (s.status == pf::EvaluationStatus::kVacuum && !once(vacuum)) {
      std::cerr << "finger_model: warning: " << pf::vacuumMessage(p) << " is printed\n";
    }
    if (range.clamped && !once(clamp)) {
      std::cerr << "finger_model: warning: " << pf::clampedMessage(requested, limits) << " (gauge_pa "
                << pf::formatMessage(p) << " is printed)\n";
    } else if (range.above_validated && !range.clamped && !once(extrapolated)) {
      std::cerr << "finger_model: warning: " << pf::aboveValidatedMessage(p, limits) << "\n";
    }
    noteShape(s);
    if (s.status == pf::EvaluationStatus::kSnappedThrough && !once(snap)) {
      std::cerr << "finger_model: note: at " << pf::formatMessage(p) << " Pa the walls are on their far branch "
                << "(snapped through past the limit point, " << pf::formatMessage(model.limitGaugePa())
                << " Pa; back at or below " << pf::formatMessage(model.farTurningGaugePa())
                << " Pa): the rows follow the path, in order\n";
    }
    if (s.status == pf::EvaluationStatus::kBeyondLimitPoint && !once(limit)) {
      std::cerr << "finger_model: warning: gauge pressure " << pf::formatExact(p) << " Pa is at or beyond the "
                << "membrane wall's limit point, " << pf::formatExact(model.limitGaugePa())
                << " Pa, where the pressure does not determine the shape: the wall has no far branch and balloons "
                << "without bound (a risk of bursting); such rows are nan\n";
    } else if (s.status == pf::EvaluationStatus::kSolverFailure && !once(failure)) {
      std::cerr << "finger_model: warning: solver '" << pf::solverName(model.options().solver)
                << "' found no finite answer at " << pf::formatExact(p) << " Pa gauge; such rows are nan\n";
    }
  }

  // false the first time (and marks it said), true after.
  static bool once(bool& said) {
    const bool before = said;
    said = true;
    return before;
  }
};

}  // namespace pneumatic_finger_tools
