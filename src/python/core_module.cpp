// pneumatic_finger._core: the model library for Python (pybind11). Thin: every number comes from the C++ core
// (FingerModel::evaluateMany, gaugeForTipAngle, ContactTracker); every parameter goes through the same loader and
// validation as the tools, so a bad key raises ValueError with the tools' message. Python users import
// pneumatic_finger.core, which adds the package's default parameter file.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "pneumatic_finger/core/calibration.hpp"
#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace py = pybind11;
namespace pf = pneumatic_finger;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

const char* statusName(int status) {
  switch (static_cast<pf::EvaluationStatus>(status)) {
    case pf::EvaluationStatus::kOk: return "ok";
    case pf::EvaluationStatus::kVacuum: return "vacuum";
    case pf::EvaluationStatus::kNotFinite: return "not finite";
    case pf::EvaluationStatus::kSolverFailure: return "solver failure";
  }
  return "?";
}

// Python's value of an override: a number, or a list of numbers (one per chamber).
pf::RawParameterValue rawValue(const std::string& key, const py::handle& value) {
  pf::RawParameterValue raw;
  try {
    if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
      raw.values.push_back(value.cast<double>());
    } else {
      raw.is_list = true;
      for (const py::handle& v : value) raw.values.push_back(v.cast<double>());
    }
  } catch (const py::cast_error&) {
    throw pf::ParameterError("parameter '" + key + "' must be a number or a list of numbers");
  } catch (const py::type_error&) {
    throw pf::ParameterError("parameter '" + key + "' must be a number or a list of numbers");
  }
  return raw;
}

// A parameter file with Python overrides on top: the raw map every reader validates the same way.
pf::RawParameterMap loadRaw(const std::string& config, const py::dict& overrides) {
  pf::RawParameterMap raw;
  if (!config.empty()) pf::loadRawParametersFromYamlFile(config, raw);
  for (const auto& item : overrides) {
    const std::string key = py::str(item.first);
    raw[key] = rawValue(key, item.second);
  }
  return raw;
}

// The pressures of a call: a number (scalar: the results drop the pressure axis) or a 1-D sequence.
Array pressures(const py::object& gauge_pa, bool& scalar) {
  scalar = !py::isinstance<py::array>(gauge_pa) && !py::isinstance<py::list>(gauge_pa) &&
           !py::isinstance<py::tuple>(gauge_pa);
  Array p = Array::ensure(gauge_pa);
  if (!p || p.ndim() > 1) throw py::value_error("gauge_pa must be a number or a 1-D array of pressures (Pa)");
  return p;
}

class PyFingerModel {
 public:
  PyFingerModel(const std::string& config, const py::dict& overrides, const std::string& solver) {
    pf::ModelOptions options;
    options.solver = pf::parseSolverName(solver);
    model_ = std::make_unique<pf::FingerModel>(pf::FingerParameters::fromRaw(loadRaw(config, overrides)), options);
  }

  // A scalar gives arrays without the leading pressure axis; an array of P pressures gives (P, ...).
  py::dict evaluate(const py::object& gauge_pa) {
    bool scalar = false;
    const Array p = pressures(gauge_pa, scalar);
    const auto count = static_cast<py::ssize_t>(p.size());
    const py::ssize_t n = model_->chamberCount();
    // The batch's arrays are the core's BatchBuffers (one definition of their shapes); numpy views them, and a capsule
    // keeps them alive as long as any view does.
    auto* rows = new pf::BatchBuffers(static_cast<std::size_t>(count), static_cast<int>(n));
    const py::capsule owner(rows, [](void* r) { delete static_cast<pf::BatchBuffers*>(r); });
    const double* gauges = p.data();
    {
      // The loop runs in C++ without the GIL. The model is const; each call has its own workspace, so calls from
      // several Python threads run at once.
      py::gil_scoped_release release;
      pf::FingerWorkspace workspace(*model_);
      model_->evaluateMany(gauges, static_cast<std::size_t>(count), rows->outputs(), workspace);
    }
    auto view = [&owner](std::vector<double>& v, std::vector<py::ssize_t> shape) {
      return Array(std::move(shape), v.data(), owner);
    };
    const Array stretch = view(rows->stretch, {count, n}), bulge = view(rows->bulge_m, {count, n}),
                half = view(rows->half_angle_rad, {count, n}), joints = view(rows->joint_angle_rad, {count, n}),
                backbone = view(rows->backbone_m, {count, n + 2, py::ssize_t(2)}), tip = view(rows->tip_angle_rad, {count});
    py::list names;
    for (py::ssize_t i = 0; i < count; ++i) names.append(statusName(rows->status[static_cast<std::size_t>(i)]));
    py::dict d;
    auto put = [&](const char* key, const Array& a) {
      d[key] = scalar ? py::object(a[py::int_(0)]) : py::object(a);
    };
    put("stretch", stretch);
    put("bulge_m", bulge);
    put("half_angle_rad", half);
    put("joint_angle_rad", joints);
    put("backbone_m", backbone);
    put("tip_angle_rad", tip);
    d["status"] = scalar ? py::object(names[0]) : py::object(names);
    return d;
  }

  double gaugeForTipAngle(double tip_angle_rad, const py::object& max_gauge_pa) const {
    const double limit = max_gauge_pa.is_none() ? pf::kModelMaxGaugePa : max_gauge_pa.cast<double>();
    double gauge = 0.0;
    std::string why;
    if (!model_->gaugeForTipAngle(tip_angle_rad, limit, gauge, why)) throw py::value_error(why);
    return gauge;
  }

  // The finger closing on a disk of the finger's plane (docs/GRASP.md), at one pressure or an array of them.
  py::dict contact(const py::object& gauge_pa, const std::vector<double>& disk) const {
    if (disk.size() != 3) throw py::value_error("disk must be (x_m, y_m, radius_m)");
    const pf::Obstacle obstacle = pf::Obstacle::disk(disk[0], disk[1], disk[2]);
    const std::string problem = obstacle.problem();
    if (!problem.empty()) throw py::value_error(problem);
    bool scalar = false;
    const Array p = pressures(gauge_pa, scalar);
    const auto count = static_cast<py::ssize_t>(p.size());
    const py::ssize_t n = model_->chamberCount();
    Array joints({count, n}), backbone({count, n + 2, py::ssize_t(2)}), first({count});
    py::array_t<bool> held({count, n});
    std::vector<std::string> status(static_cast<std::size_t>(count));
    {
      py::gil_scoped_release release;
      pf::ContactTracker tracker(*model_, obstacle);  // const methods of the model only: thread-safe
      for (py::ssize_t i = 0; i < count; ++i) {
        const pf::ContactState s = tracker.solve(p.data()[i]);
        std::copy(s.joint_angle_rad.data(), s.joint_angle_rad.data() + n, joints.mutable_data() + i * n);
        std::copy(s.backbone_m.data(), s.backbone_m.data() + 2 * (n + 2), backbone.mutable_data() + i * 2 * (n + 2));
        for (py::ssize_t k = 0; k < n; ++k) held.mutable_data()[i * n + k] = s.held[static_cast<std::size_t>(k)];
        first.mutable_data()[i] = s.first_touch_gauge_pa;
        using S = pf::ContactState::Status;
        status[static_cast<std::size_t>(i)] = s.status == S::kFree             ? "free"
                                              : s.status == S::kInContact      ? "in contact"
                                              : s.status == S::kOverlapsAtRest ? "overlaps at rest"
                                                                               : "solver failure";
      }
    }
    py::dict d;
    auto pick = [&](const py::array& a) { return scalar ? py::object(a[py::int_(0)]) : py::object(a); };
    d["joint_angle_rad"] = pick(joints);
    d["backbone_m"] = pick(backbone);
    d["held"] = pick(held);
    d["first_touch_gauge_pa"] = pick(first);
    d["status"] = scalar ? py::object(py::str(status[0])) : py::object(py::cast(status));
    return d;
  }

  py::dict parameters() const {
    py::dict d;
    for (const auto& kv : model_->parameters().toRaw()) {
      d[py::str(kv.first)] = kv.second.is_list ? py::object(py::cast(kv.second.values)) : py::object(py::float_(kv.second.values[0]));
    }
    return d;
  }

  int chamberCount() const { return model_->chamberCount(); }
  double contactGaugePa() const { return model_->contactGaugePa(); }
  std::string solver() const { return pf::solverName(model_->options().solver); }


 private:
  std::unique_ptr<const pf::FingerModel> model_;
};

// The calibration of finger_calibrate: fit keys of a parameter file to measured joint angles, tip angles or tip
// positions; the same defaults (what to compare, which keys) as the tool.
// Residual rows as dicts (measured and model, per row).
py::list residualRows(const std::vector<pf::Residual>& rows) {
  py::list out;
  for (const pf::Residual& r : rows) {
    py::dict row;
    row["gauge_pa"] = r.gauge_pa;
    row["measured_avg_rad"] = r.measured_avg_rad;
    row["model_avg_rad"] = r.model_avg_rad;
    row["measured_joint1_rad"] = r.measured_joint1_rad;
    row["model_joint1_rad"] = r.model_joint1_rad;
    row["measured_joint_rad"] = r.measured_joint_rad;
    row["model_joint_rad"] = r.model_joint_rad;
    row["measured_tip_angle_rad"] = r.measured_tip_angle_rad;
    row["model_tip_angle_rad"] = r.model_tip_angle_rad;
    row["measured_tip_m"] = py::make_tuple(r.measured_tip_x_m, r.measured_tip_y_m);
    row["model_tip_m"] = py::make_tuple(r.model_tip_x_m, r.model_tip_y_m);
    out.append(row);
  }
  return out;
}

py::dict calibrate(const std::string& data, const std::vector<std::string>& keys, const std::string& objective,
                   const std::string& config, const py::dict& overrides, const std::string& average_column,
                   const std::string& compare, bool with_leave_one_out) {
  const pf::FingerParameters base = pf::FingerParameters::fromRaw(loadRaw(config, overrides));
  const pf::CalibrationObjective goal = pf::parseObjective(objective);
  const std::vector<pf::Measurement> rows = pf::readMeasurementsCsv(data, 1, average_column);
  const pf::CalibrationQuantity quantity = !compare.empty()          ? pf::parseQuantity(compare)
                                           : !average_column.empty() ? pf::CalibrationQuantity::kOuterAverage
                                                                     : pf::defaultQuantity(rows);
  const std::vector<std::string> fit_keys = keys.empty() ? pf::defaultFitKeys(quantity) : keys;
  pf::CalibrationResult fit;
  {
    py::gil_scoped_release release;
    fit = pf::calibrate(base, fit_keys, rows, goal, quantity);
  }
  py::dict fitted;
  for (std::size_t i = 0; i < fit.keys.size(); ++i) fitted[py::str(fit.keys[i])] = fit.values[i];
  py::list residuals = residualRows(fit.residuals);
  py::object leave_one_out = py::none();
  if (with_leave_one_out) {
    std::vector<pf::Residual> loo;
    {
      py::gil_scoped_release release;
      loo = pf::leaveOneOut(base, fit_keys, rows, goal, quantity);
    }
    leave_one_out = residualRows(loo);
  }
  py::dict d;
  d["fitted"] = fitted;
  d["compared"] = pf::quantityName(quantity);
  d["objective_value"] = fit.objective_value;
  d["residuals"] = residuals;
  d["leave_one_out"] = leave_one_out;
  d["model_evaluations"] = fit.model_evaluations;
  return d;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "The pneumatic finger model (C++ core). Use pneumatic_finger.core, which adds the default parameter file.";
  // The core's refusals (a bad key, value or file) are Python's ValueError, with the tools' message.
  py::register_exception_translator([](std::exception_ptr e) {
    try {
      if (e) std::rethrow_exception(e);
    } catch (const pf::ParameterError& error) {
      PyErr_SetString(PyExc_ValueError, error.what());
    }
  });
  m.def("calibrate", &calibrate, py::arg("data"), py::arg("keys"), py::arg("objective"), py::arg("config"),
        py::arg("overrides") = py::dict(), py::arg("average_column") = "", py::arg("compare") = "",
        py::arg("leave_one_out") = false,
        "Fits keys of a parameter file to measured joint angles, tip angles or tip positions, as finger_calibrate "
        "does; with leave_one_out, also each row as a fit to the others predicts it");
  py::class_<PyFingerModel>(m, "FingerModel")
      .def(py::init<const std::string&, const py::dict&, const std::string&>(), py::arg("config"),
           py::arg("overrides") = py::dict(), py::arg("solver") = "robust")
      .def("evaluate", &PyFingerModel::evaluate, py::arg("gauge_pa"),
           "The free finger at a gauge pressure (Pa) or a 1-D array of them: a dict of numpy arrays stretch, bulge_m, "
           "half_angle_rad, joint_angle_rad (P, N), backbone_m (P, N+2, 2), tip_angle_rad (P,), and status")
      .def("gauge_for_tip_angle", &PyFingerModel::gaugeForTipAngle, py::arg("tip_angle_rad"),
           py::arg("max_gauge_pa") = py::none(), "The gauge pressure (Pa) for a tip angle; ValueError when none up to max")
      .def("contact", &PyFingerModel::contact, py::arg("gauge_pa"), py::arg("disk"),
           "The finger closing on a disk (x_m, y_m, radius_m) of its plane: joint_angle_rad, backbone_m, held, "
           "first_touch_gauge_pa, status")
      .def_property_readonly("parameters", &PyFingerModel::parameters)
      .def_property_readonly("chamber_count", &PyFingerModel::chamberCount)
      .def_property_readonly("contact_gauge_pa", &PyFingerModel::contactGaugePa)
      .def_property_readonly("solver", &PyFingerModel::solver);
}
