// pneumatic_finger._core: the model library for Python (pybind11). Thin: every number comes from the C++ core
// (FingerModel::evaluateMany, gaugeForTipAngle, ContactTracker); every parameter goes through the same loader and
// validation as the tools, so a bad key raises ValueError with the tools' message. Python users import
// pneumatic_finger.core, which adds the package's default parameter file.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/design_sweep.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "calibrate_module.hpp"
#include "range_module.hpp"
#include "range_warnings.hpp"
#include "python_parameters.hpp"
#include "contact_rows.hpp"
#include "output_arrays.hpp"
#include "status_codes.hpp"

namespace py = pybind11;
namespace pf = pneumatic_finger;

namespace {

using namespace pneumatic_finger_python;  // NOLINT(build/namespaces): the module's own helpers
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The pressures of a call: a number (scalar: the results drop the pressure axis) or a 1-D sequence.
// A number or a 1-D array of them (@p name says what, in the message, and @p unit its unit: pressures in Pa by
// default).
Array pressures(const py::object& gauge_pa, bool& scalar, const char* name = "gauge_pa", const char* unit = "Pa") {
  scalar = !py::isinstance<py::array>(gauge_pa) && !py::isinstance<py::list>(gauge_pa) &&
           !py::isinstance<py::tuple>(gauge_pa);
  // Numbers only: forcecast would read None as NaN and '100000' as a pressure, so the natural dtype is checked first.
  const py::array natural = py::array::ensure(gauge_pa);
  const char kind = natural ? natural.dtype().kind() : 'O';
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::value_error(std::string(name) + " = " + std::string(py::repr(gauge_pa)) +
                          " is not a number: give a number or a 1-D array of numbers (" + unit + ")");
  }
  Array p = Array::ensure(gauge_pa);
  if (!p || p.ndim() > 1) {
    throw py::value_error(std::string(name) + " must be a number or a 1-D array of them (" + unit + ")");
  }
  return p;
}

// One output a call can write: its name, its element type and its shape after the leading axis (-1: the chamber
// count N, -2: N + 2).
using E = Element;
const std::vector<OutputField> kStateFields = {
    {"stretch", E::kFloat64, {-1}},         {"bulge_m", E::kFloat64, {-1}},      {"half_angle_rad", E::kFloat64, {-1}},
    {"joint_angle_rad", E::kFloat64, {-1}}, {"backbone_m", E::kFloat64, {-2, 2}}, {"tip_angle_rad", E::kFloat64, {}},
    {"status", E::kCode, {}},               {"supplied_volume_m3", E::kFloat64, {}}, {"status_flags", E::kCode, {}},
    {"gauge_pa", E::kFloat64, {}},  // evaluate: the pressure evaluated (a clamped one's top); by volume: it makes
    {"chord_angle_rad", E::kFloat64, {}}};
const std::vector<OutputField>& kVolumeFields = kStateFields;
const std::vector<OutputField> kDesignFields = {
    {"tip_angle_rad", E::kFloat64, {}},    {"tip_x_m", E::kFloat64, {}},       {"tip_y_m", E::kFloat64, {}},
    {"contact_gauge_pa", E::kFloat64, {}}, {"snap_gauge_pa", E::kFloat64, {}}, {"limit_gauge_pa", E::kFloat64, {}},
    {"status", E::kCode, {}},              {"status_flags", E::kCode, {}}};

class PyFingerModel {
 public:
  PyFingerModel(const std::string& config, const py::dict& overrides, const std::string& solver,
                const py::object& max_gauge_pa) {
    pf::ModelOptions options;
    options.solver = pf::parseSolverName(solver);
    // The file's range (max_gauge_pa, validated_max_gauge_pa), as every interface reads it; max_gauge_pa= on top.
    model_ = std::make_unique<pf::FingerModel>(pf::FingerParameters::fromRaw(loadRaw(config, overrides, &range_)),
                                               options);
    if (!max_gauge_pa.is_none()) range_ = range_.withTop(max_gauge_pa.cast<double>());
    max_volume_m3_ = pf::maxSuppliedVolumeM3(*model_, range_);
  }

  // A scalar gives arrays without the leading pressure axis; an array of P pressures gives (P, ...). Only the outputs
  // asked for are allocated, written and, where the batch kernel can leave them out, computed.
  // @p path: a FingerPath's workspace, which carries the walls' branch from call to call; nullptr: this call's own,
  // starting on @p start_branch.
  py::dict evaluate(const py::object& gauge_pa, const py::object& outputs, const py::object& out,
                    const std::string& start_branch, pf::FingerWorkspace* path = nullptr) const {
    const bool far = startOnFar(start_branch);
    bool scalar = false;
    const Array p = pressures(gauge_pa, scalar);
    if (scalar && !out.is_none()) throw py::value_error("out= needs gauge_pa as a 1-D array");
    const auto count = static_cast<std::size_t>(p.size());
    refuseNegativeAbsolute(p.data(), count, scalar, model_->parameters().atmospheric_pressure_pa);
    OutputArrays arrays(kStateFields, outputs, out, p.size(), model_->chamberCount());
    arrays.refuseOverlap(p.data(), count * sizeof(double));
    pf::BatchOutputs rows = stateRows(arrays);  // (bulge_m may get a scratch array below, for the supplied volume)
    std::size_t clamped = 0;
    double meets = NAN;  // the first tip angle whose backbone crosses itself
    {
      // The loop runs in C++ without the GIL. The model is const; each call has its own workspace, so calls from
      // several Python threads run at once.
      py::gil_scoped_release release;
      std::optional<pf::FingerWorkspace> own;
      pf::FingerWorkspace& workspace = path ? *path : own.emplace(*model_);
      if (!path) model_->startBranch(workspace, far);  // the walls' branch the sequence starts from
      // The range rule of every interface (pressure_range.hpp); a copy only when some pressure is above the range.
      std::vector<double> in_range;
      const double* evaluated = p.data();
      if (std::any_of(p.data(), p.data() + count, [this](double x) { return pf::checkGaugeRange(x, range_).clamped; })) {
        in_range.resize(count);
        clamped = pf::clampToRange(p.data(), in_range.data(), count, range_);
        evaluated = in_range.data();
      }
      // The supplied volume, only when asked for, from each row's bulges (any branch): the batch writes them, into
      // a scratch array when the bulges were not asked for themselves.
      double* volume = arrays.data<double>("supplied_volume_m3");
      std::vector<double> bulge_scratch, joint_scratch;
      if (volume && !rows.bulge_m) rows.bulge_m = scratch(bulge_scratch, count);
      if (!rows.joint_angle_rad) rows.joint_angle_rad = scratch(joint_scratch, count);  // for the self-contact check
      std::uint8_t* flags = arrays.data<std::uint8_t>("status_flags");
      std::vector<std::uint8_t> status_scratch = statusForFlags(rows, flags, count);  // rows.status, maybe
      const ChordScratch chord(arrays, rows, count, model_->chamberCount());
      model_->evaluateMany(evaluated, count, rows, workspace);
      writeChord(arrays, rows, count, model_->chamberCount());
      const auto n = static_cast<std::size_t>(model_->chamberCount());
      for (std::size_t i = 0; volume && i < count; ++i) {
        volume[i] = model_->suppliedVolumeForBulges(rows.bulge_m + i * n, evaluated[i]);  // NaN rows stay NaN
      }
      if (double* g = arrays.data<double>("gauge_pa")) std::copy(evaluated, evaluated + count, g);  // as finger_model
      meets = reportRows(model_->parameters(), rows, flags, count,
                         [&](std::size_t i) { return pf::checkGaugeRange(p.data()[i], range_); });
    }
    if (clamped > 0) warnClamped(p.data(), count, clamped, range_);
    warnOutsideValidated(p.data(), count, range_);
    warnSelfContact(meets);
    return arrays.result(scalar);
  }

  // Volume as the input (docs/MODEL.md, Volume): the state each supplied volume gives, and the pressure it makes.
  // Numpy-shaped as evaluate; a volume the model does not follow gives NaN and its status.
  py::dict evaluateVolume(const py::object& volume_m3, const py::object& outputs, const py::object& out) const {
    bool scalar = false;
    const Array v = pressures(volume_m3, scalar, "supplied_volume_m3", "m^3");
    if (scalar && !out.is_none()) throw py::value_error("out= needs supplied_volume_m3 as a 1-D array");
    const auto count = static_cast<std::size_t>(v.size());
    OutputArrays arrays(kVolumeFields, outputs, out, v.size(), model_->chamberCount());
    arrays.refuseOverlap(v.data(), count * sizeof(double));
    std::size_t clamped = 0;
    double meets = NAN;  // the first tip angle whose backbone crosses itself
    double first_above_validated = NAN;  // the first pressure a volume made above the validated range (not clamped)
    {
      py::gil_scoped_release release;
      pf::FingerWorkspace workspace(*model_);
      // The range rule of every interface, for a volume (pressure_range.hpp): above the volume that makes
      // max_gauge_pa, the finger at that volume, status clamped.
      std::vector<double> in_range(v.data(), v.data() + count);
      clamped = pf::clampVolumesToRange(v.data(), in_range.data(), count, max_volume_m3_);
      pf::BatchOutputs rows = stateRows(arrays);
      std::vector<double> joint_scratch, gauge_scratch;
      if (!rows.joint_angle_rad) rows.joint_angle_rad = scratch(joint_scratch, count);  // for the self-contact check
      std::uint8_t* flags = arrays.data<std::uint8_t>("status_flags");
      std::vector<std::uint8_t> status_scratch = statusForFlags(rows, flags, count);  // rows.status, maybe
      double* gauge = arrays.data<double>("gauge_pa");
      if (!gauge) gauge_scratch.resize(count), gauge = gauge_scratch.data();  // the validated range is in pressure
      const ChordScratch chord(arrays, rows, count, model_->chamberCount());
      model_->evaluateVolumeMany(in_range.data(), count, rows, gauge, workspace);
      writeChord(arrays, rows, count, model_->chamberCount());
      meets = reportRows(model_->parameters(), rows, flags, count, [&](std::size_t i) {
        pf::RangeCheck check;  // a clamped volume is a clamped pressure: the finger at max_gauge_pa's volume
        check.clamped = pf::checkVolumeRange(v.data()[i], max_volume_m3_).clamped;
        check.above_validated = check.clamped || gauge[i] > range_.validated_max_gauge_pa;
        const bool extrapolated = check.above_validated && !check.clamped;
        if (extrapolated && std::isnan(first_above_validated)) first_above_validated = gauge[i];
        return check;
      });
      if (double* d = arrays.data<double>("supplied_volume_m3")) std::copy(in_range.begin(), in_range.end(), d);
    }
    warnVolumeNotFollowed(v.data(), arrays.data<std::uint8_t>("status"), count, model_->volumeLimitM3());
    if (std::isfinite(first_above_validated)) warnRuntime(pf::aboveValidatedMessage(first_above_validated, range_));
    if (clamped > 0) {
      const double* first = std::find_if(v.data(), v.data() + count, [this](double x) { return x > max_volume_m3_; });
      warnRuntime(pf::volumeClampedMessage(*first, max_volume_m3_, range_) +
                  (clamped > 1 ? " (and " + std::to_string(clamped - 1) + " more)" : std::string()));
    }
    warnSelfContact(meets);
    return arrays.result(scalar);
  }


  // A scratch array of count x N, for an output the caller did not ask for but a check needs.
  double* scratch(std::vector<double>& storage, std::size_t count) const {
    storage.resize(count * static_cast<std::size_t>(model_->chamberCount()));
    return storage.data();
  }

  // The blocked tip force (N) at a pressure or an array of them (docs/MODEL.md "Force"). A pressure that is not a
  // finite number is refused by its index: a force is an answer to a real pressure.
  py::object blockedTipForce(const py::object& gauge_pa) const {
    bool scalar = false;
    const Array p = pressures(gauge_pa, scalar);
    Array force(p.size());
    for (py::ssize_t i = 0; i < p.size(); ++i) {
      if (!std::isfinite(p.data()[i])) {
        throw py::value_error("gauge_pa" + (scalar ? std::string() : "[" + std::to_string(i) + "]") + ": " +
                              pf::notFinitePressureMessage(p.data()[i]));
      }
      // The range rule of every interface: above max_gauge_pa, the force there (as finger_model prints it).
      force.mutable_data()[i] = model_->blockedTipForceN(pf::checkGaugeRange(p.data()[i], range_).gauge_pa);
    }
    const std::size_t clamped = static_cast<std::size_t>(std::count_if(
        p.data(), p.data() + p.size(), [this](double x) { return pf::checkGaugeRange(x, range_).clamped; }));
    if (clamped > 0) warnClamped(p.data(), static_cast<std::size_t>(p.size()), clamped, range_);
    if (scalar) return py::float_(force.data()[0]);
    return std::move(force);
  }

  // The inverse at one tip angle or an array of them (numpy-shaped as evaluate). A tip angle no pressure up to the
  // limit reaches is refused, by its index in an array.
  py::object gaugeForTipAngle(const py::object& tip_angle_rad, const py::object& max_gauge_pa) const {
    // A cap is a pressure range's top: refused by the one rule unless finite and > 0 (PressureRange::upTo).
    return inverse(tip_angle_rad,
                   max_gauge_pa.is_none() ? range_.max_gauge_pa
                                          : pf::PressureRange::upTo(max_gauge_pa.cast<double>()).max_gauge_pa,
                   &pf::FingerModel::gaugeForTipAngle);
  }

  // The supplied volume (m^3) for a tip angle: the inverse of a finger filled by volume (volumeForTipAngle).
  py::object volumeForTipAngle(const py::object& tip_angle_rad, const py::object& max_volume_m3) const {
    return inverse(tip_angle_rad, max_volume_m3.is_none() ? INFINITY : max_volume_m3.cast<double>(),
                   &pf::FingerModel::volumeForTipAngle);
  }

  // An inverse of the model (@p solve: gaugeForTipAngle, volumeForTipAngle) over a tip angle or an array of them;
  // ValueError naming the angle it cannot reach and why.
  template <class Solve>
  py::object inverse(const py::object& tip_angle_rad, double limit, Solve solve) const {
    bool scalar = false;
    const Array angles = pressures(tip_angle_rad, scalar, "tip_angle_rad");
    Array answer(angles.size());
    for (py::ssize_t i = 0; i < angles.size(); ++i) {
      std::string why;
      if (!((*model_).*solve)(angles.data()[i], limit, answer.mutable_data()[i], why)) {
        throw py::value_error((scalar ? std::string() : "tip_angle_rad[" + std::to_string(i) + "]: ") + why);
      }
    }
    if (scalar) return py::float_(answer.data()[0]);
    return std::move(answer);
  }

  // The finger closing on a disk of the finger's plane (docs/GRASP.md), at one pressure or an array of them, or at
  // supplied volumes (@p by_volume: the pressure each makes on the disk is found first); one disk (3,) for all, or one
  // per input (P, 3). Consecutive inputs on the same disk share its tracker (its touch events).
  py::dict contact(const py::object& input, const py::object& disk, const py::object& outputs, const py::object& out,
                   bool by_volume) const {
    bool scalar = false;
    const char* name = by_volume ? "supplied_volume_m3" : "gauge_pa";
    const Array x = pressures(input, scalar, name, by_volume ? "m^3" : "Pa");
    if (scalar && !out.is_none()) throw py::value_error(std::string("out= needs ") + name + " as a 1-D array");
    const std::vector<pf::Obstacle> obstacles = disksOf(disk, x.size(), scalar);
    const auto count = static_cast<std::size_t>(x.size());
    OutputArrays arrays(kContactFields, outputs, out, x.size(), model_->chamberCount());
    arrays.refuseOverlap(x.data(), count * sizeof(double));
    const ContactRows rows = contactRows(arrays);
    std::vector<double> gauge(x.data(), x.data() + count);
    std::string why;
    {
      py::gil_scoped_release release;
      if (by_volume) why = gaugesForVolumes(*model_, x.data(), count, obstacles, range_.max_gauge_pa, gauge.data());
      if (why.empty()) solveContacts(*model_, gauge.data(), count, obstacles, rows);
    }
    if (!why.empty()) throw py::value_error(why);
    return arrays.result(scalar);
  }

  py::dict parameters() const { return parametersDict(model_->parameters()); }

  int chamberCount() const { return model_->chamberCount(); }

  // Many designs at one pressure (pf.sweep_designs): this model's parameters with @p keys set per row of @p values.
  py::dict sweepDesigns(const std::vector<std::string>& keys, const py::object& values, double gauge_pa,
                        const py::object& outputs) const {
    const Array v = Array::ensure(values);
    if (keys.empty() || !v || v.ndim() != 2 || v.shape(1) != static_cast<py::ssize_t>(keys.size())) {
      throw py::value_error("values must be an array of shape (designs, len(keys)), and keys not empty");
    }
    refuseNegativeAbsolute(&gauge_pa, 1, true, model_->parameters().atmospheric_pressure_pa);
    OutputArrays arrays(kDesignFields, outputs, py::none(), v.shape(0), 0);
    const pf::DesignOutputs rows{arrays.data<double>("tip_angle_rad"),    arrays.data<double>("tip_x_m"),
                                 arrays.data<double>("tip_y_m"),          arrays.data<double>("contact_gauge_pa"),
                                 arrays.data<std::uint8_t>("status"),     arrays.data<double>("snap_gauge_pa"),
                                 arrays.data<double>("limit_gauge_pa"),   arrays.data<std::uint8_t>("status_flags")};
    std::vector<pf::DesignRefusal> refused;
    {
      py::gil_scoped_release release;
      const pf::RangeCheck input = pf::checkGaugeRange(gauge_pa, range_);  // the range rule of every interface
      refused = pf::sweepDesigns(model_->parameters(), model_->options(), keys, v.data(),
                                 static_cast<std::size_t>(v.shape(0)), input.gauge_pa, rows, input);
    }
    py::dict d = arrays.result(false);
    py::list refusals;
    for (const pf::DesignRefusal& r : refused) refusals.append(py::make_tuple(r.design, r.message));
    d["refused"] = refusals;
    return d;
  }
  double contactGaugePa() const { return model_->contactGaugePa(); }
  double maxGaugePa() const { return range_.max_gauge_pa; }
  double validatedMaxGaugePa() const { return range_.validated_max_gauge_pa; }
  double limitGaugePa() const { return model_->limitGaugePa(); }
  double snapGaugePa() const { return model_->snapGaugePa(); }
  double volumeLimitM3() const { return model_->volumeLimitM3(); }
  double farTurning() const { return model_->farTurningGaugePa(); }
  py::object suppliedVolume(const py::object& gauge_pa) const {
    bool scalar = false;
    const Array p = pressures(gauge_pa, scalar);
    Array v(p.size());
    for (py::ssize_t i = 0; i < p.size(); ++i) v.mutable_data()[i] = model_->suppliedVolumeAt(p.data()[i]);
    if (scalar) return py::float_(v.data()[0]);
    return std::move(v);
  }
  double maxSuppliedVolumeM3() const { return max_volume_m3_; }
  const pf::FingerModel& core() const { return *model_; }
  static bool startOnFar(const std::string& branch) {
    if (branch == "near" || branch == "far") return branch == "far";
    throw py::value_error("start_branch = '" + branch + "' is not one of near, far");
  }
  std::string solver() const { return pf::solverName(model_->options().solver); }

 private:
  std::unique_ptr<const pf::FingerModel> model_;
  pf::PressureRange range_;  // what evaluate() clamps to, as finger_node's ~max_gauge_pa
  double max_volume_m3_ = 0.0;  // what evaluate_volume() clamps to: the volume that makes range_.max_gauge_pa
};

// A path through the model's states (model.path()): its workspace, and so the walls' branch, carries over from one
// evaluate() to the next, as finger_node's does from message to message. One path per thread.
class PyFingerPath {
 public:
  PyFingerPath(const py::object& model, const std::string& start_branch)
      : owner_(model), model_(model.cast<const PyFingerModel*>()),
        workspace_(std::make_unique<pf::FingerWorkspace>(model_->core())) {
    model_->core().startBranch(*workspace_, PyFingerModel::startOnFar(start_branch));
  }
  py::dict evaluate(const py::object& gauge_pa, const py::object& outputs, const py::object& out) {
    return model_->evaluate(gauge_pa, outputs, out, "near", workspace_.get());
  }
 private:
  py::object owner_;  // keeps the model alive as long as the path
  const PyFingerModel* model_;
  std::unique_ptr<pf::FingerWorkspace> workspace_;
};

}  // namespace

// The finger closing on a disk, by pressure or by volume (docs/GRASP.md; docs/MODEL.md, Volume).
void defineContact(py::class_<PyFingerModel>& c) {
  // One method body for both inputs: @p by_volume says which the first argument is.
  auto contact_by = [](bool by_volume) {
    return [by_volume](const PyFingerModel& m, const py::object& input, const py::object& disk,
                       const py::object& outputs, const py::object& out) {
      return m.contact(input, disk, outputs, out, by_volume);
    };
  };
  c.def(
          "contact", contact_by(false),
          py::arg("gauge_pa"), py::arg("disk"), py::arg("outputs") = py::none(), py::arg("out") = py::none(),
          "The finger closing on a disk (x_m, y_m, radius_m) of its plane, or one disk per pressure (P, 3): "
          "joint_angle_rad (P, N), backbone_m (P, N+2, 2), held (P, N) bool, first_touch_gauge_pa (P,), status (P,) "
          "uint8 codes (CONTACT_STATUS names them), contact_point_m (P, N, 2) and normal_force_n (P, N): each touch's "
          "point and the normal force (N) the finger presses with there, in touch order, NaN after the last; "
          "supplied_volume_m3 (P,): the volume the finger on the disk has taken (the held walls keep theirs), and "
          "gauge_pa (P,); outputs and out as for evaluate")
      .def(
          "contact_volume", contact_by(true),
          py::arg("supplied_volume_m3"), py::arg("disk"), py::arg("outputs") = py::none(), py::arg("out") = py::none(),
          "contact() driven by volume: the finger closing on the disk at each supplied volume (m^3), gauge_pa the "
          "pressure it makes there (up to max_gauge_pa and the limit point; ValueError naming a volume it cannot "
          "take); the same outputs");
}

void defineVolume(py::class_<PyFingerModel>& c) {
  c.def("evaluate_volume", &PyFingerModel::evaluateVolume, py::arg("supplied_volume_m3"),
           py::arg("outputs") = py::none(), py::arg("out") = py::none(),
           "Volume as the input (docs/MODEL.md, Volume): the finger into which a supply has pushed a volume (m^3: the "
           "chambers' growth plus the compression of dead_volume_m3 of gas) or a 1-D array of them, in order. The "
           "outputs of evaluate and gauge_pa (P,), the pressure the volume makes; under the membrane law with "
           "identical chambers the volume sets the shape past the limit point too. NaN and status 'beyond limit "
           "point' above the most the model follows (volume_limit_m3); clamped above max_supplied_volume_m3; 'vacuum' "
           "for a negative volume (the straight finger, gauge_pa the dead gas's vacuum)")
      .def("supplied_volume", &PyFingerModel::suppliedVolume, py::arg("gauge_pa"),
           "The supplied volume (m^3) at a gauge pressure (Pa) or a 1-D array of them: the chambers' growth and the "
           "dead gas's compression; NaN at or beyond the limit point")
      .def_property_readonly("max_supplied_volume_m3", &PyFingerModel::maxSuppliedVolumeM3,
                             "the top of evaluate_volume's range (m^3): the volume that makes max_gauge_pa; a larger "
                             "volume is clamped to it (status 'clamped to max_gauge_pa', a RuntimeWarning), as "
                             "evaluate clamps a pressure; inf where the pressure never reaches max_gauge_pa")
      .def_property_readonly("volume_limit_m3", &PyFingerModel::volumeLimitM3,
                             "the largest supplied volume (m^3) evaluate_volume follows: inf where the volume sets the "
                             "shape without end; finite with a large dead gas volume (the gas snaps the finger) or a "
                             "Gent wall's lock")
      .def("volume_for_tip_angle", &PyFingerModel::volumeForTipAngle, py::arg("tip_angle_rad"),
           py::arg("max_volume_m3") = py::none(),
           "The supplied volume (m^3) for a tip angle (rad) or a 1-D array of them, for a finger filled by volume: past "
           "the limit point too; ValueError beyond what volume control follows or above max_volume_m3 (None: no cap)");
}

void defineProperties(py::class_<PyFingerModel>& c) {
  c.def_property_readonly("parameters", &PyFingerModel::parameters)
      .def_property_readonly("chamber_count", &PyFingerModel::chamberCount)
      .def_property_readonly("contact_gauge_pa", &PyFingerModel::contactGaugePa)
      .def_property_readonly("limit_gauge_pa", &PyFingerModel::limitGaugePa,
                             "the limit point (Pa gauge), where a wall folds: at or above it the status is 'beyond "
                             "limit point' (or 'snapped through' onto a far branch); inf under the paper law and where "
                             "no wall folds (a Gent wall that locks first): snap_gauge_pa is where the finger snaps "
                             "either way")
      .def_property_readonly("snap_gauge_pa", &PyFingerModel::snapGaugePa,
                             "where a rising pressure bends the finger fastest (Pa gauge): the limit point where a wall "
                             "folds, else where a Gent wall that locks first is softest (its bend rises steeply but "
                             "continuously); inf under the paper law or where every wall only stiffens")
      .def_property_readonly("far_turning_gauge_pa", [](const PyFingerModel& self) { return self.farTurning(); },
                             "the pressure (Pa gauge) at or below which a wall on its far branch snaps back to the near "
                             "one (the largest over the chamber groups); inf where no wall has a far branch")
      .def_property_readonly("solver", &PyFingerModel::solver)
      .def_property_readonly("max_gauge_pa", &PyFingerModel::maxGaugePa,
                             "the top of the model's range (Pa gauge): evaluate() clamps a pressure above it to it, "
                             "with status 'clamped to max_gauge_pa' and a RuntimeWarning, as finger_node does; the "
                             "parameter file's max_gauge_pa unless max_gauge_pa= was given")
      .def_property_readonly("validated_max_gauge_pa", &PyFingerModel::validatedMaxGaugePa,
                             "the top of the validated range (Pa gauge): the parameter file's validated_max_gauge_pa "
                             "(finger_calibrate writes the highest pressure it calibrated on), no higher than "
                             "max_gauge_pa");
}

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
  defineStatusNames(m);
  defineCalibrate(m);
  defineRangeCheck(m);
  py::class_<PyFingerPath>(m, "FingerPath",
                           "The model along one path of pressures (FingerModel.path()): the walls' branch carries over")
      .def("evaluate", &PyFingerPath::evaluate, py::arg("gauge_pa"), py::arg("outputs") = py::none(),
           py::arg("out") = py::none(), "FingerModel.evaluate's outputs, from where the last call on this path left");
  py::class_<PyFingerModel> finger_model(m, "FingerModel");
  defineVolume(finger_model);
  defineContact(finger_model);
  defineProperties(finger_model);
  finger_model
      .def(py::init<const std::string&, const py::dict&, const std::string&, const py::object&>(), py::arg("config"),
           py::arg("overrides") = py::dict(), py::arg("solver") = "robust", py::arg("max_gauge_pa") = py::none())
      .def("path", [](const py::object& self, const std::string& start_branch) { return PyFingerPath(self, start_branch); },
           py::arg("start_branch") = "near",
           "A FingerPath: evaluate() on it follows the pressures across calls, as finger_node does from message to "
           "message (a Gent wall that snapped stays on its far branch until the pressure falls to its turning point); "
           "model.evaluate() starts each call afresh from start_branch. One path per thread")
      .def("evaluate",
           [](const PyFingerModel& m, const py::object& p, const py::object& outputs, const py::object& out,
              const std::string& start_branch) { return m.evaluate(p, outputs, out, start_branch); },
           py::arg("gauge_pa"), py::arg("outputs") = py::none(), py::arg("out") = py::none(),
           py::arg("start_branch") = "near",
           "The free finger at a gauge pressure (Pa) or a 1-D array of them: a dict of numpy arrays stretch, bulge_m, "
           "half_angle_rad, joint_angle_rad (P, N), backbone_m (P, N+2, 2), tip_angle_rad (P,) and status (P,) uint8 "
           "codes (STATUS names them; a scalar call gives one code), status_flags what else holds at once (bits: "
           "STATUS_FLAGS, status_flag_names()), gauge_pa the pressure evaluated. A pressure above max_gauge_pa is clamped to it "
           "(status 'clamped to max_gauge_pa', flag 'clamped', a RuntimeWarning). The pressures are a path: under the membrane law a Gent "
           "wall snaps through at its limit pressure to its far branch (status 'snapped through') and back at that "
           "branch's turning point, in order, starting from start_branch ('near' or 'far'). outputs: the names to "
           "compute (None: all); out: a dict of arrays to fill (float64, uint8 for status, C-contiguous, of the "
           "shapes above)")
      .def("blocked_tip_force", &PyFingerModel::blockedTipForce, py::arg("gauge_pa"),
           "The blocked tip force (N) at a gauge pressure (Pa) or a 1-D array of them: the finger held straight by a "
           "plate at its tip (docs/MODEL.md, Force); 0 before the walls touch and for a vacuum; at and beyond the "
           "limit point (a rising pressure) the whole wall presses: the force jumps where the free bend snaps; "
           "ValueError for a pressure that is not finite")
      .def("gauge_for_tip_angle", &PyFingerModel::gaugeForTipAngle, py::arg("tip_angle_rad"),
           py::arg("max_gauge_pa") = py::none(),
           "The gauge pressure (Pa) for a tip angle (rad) or a 1-D array of them; ValueError when none up to "
           "max_gauge_pa (None: the model's)")

      .def("sweep_designs", &PyFingerModel::sweepDesigns, py::arg("keys"), py::arg("values"), py::arg("gauge_pa"),
           py::arg("outputs") = py::none(),
           "Many designs at one pressure: this model with keys set to each row of values (designs, len(keys)): "
           "tip_angle_rad, tip_x_m, tip_y_m, contact_gauge_pa, snap_gauge_pa, limit_gauge_pa (designs,) and status "
           "(snap_gauge_pa, a scan per design, only when asked for or with outputs=None); refused: [(design, message)] "
           "for designs the parameters refuse (NaN in every output)");
}
