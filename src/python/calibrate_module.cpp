// pf.calibrate (calibrate_module.hpp): the data as a file or as columns, the request as finger_calibrate's options,
// the answer as numpy arrays, one per quantity, with a row per measurement.
#include "calibrate_module.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/coupon.hpp"
#include "pneumatic_finger/calibration/calibration_run.hpp"
#include "python_parameters.hpp"

namespace pneumatic_finger_python {

namespace {

using Array = py::array_t<double>;

// A (rows, width) array filled by @p value(row, k).
template <typename F>
Array table(std::size_t rows, std::size_t width, F&& value) {
  Array a(std::vector<py::ssize_t>{static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(width)});
  auto w = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t k = 0; k < width; ++k) w(i, k) = value(i, k);
  }
  return a;
}

// A (rows,) array filled by @p value(row).
template <typename F>
Array column(std::size_t rows, F&& value) {
  Array a(static_cast<py::ssize_t>(rows));
  for (std::size_t i = 0; i < rows; ++i) a.mutable_data()[i] = value(i);
  return a;
}

// Residual rows as one array per quantity: (R,) or (R, N) or (R, 2); NaN where the data measured nothing.
py::dict residualArrays(const std::vector<pf::Residual>& rows, std::size_t n) {
  const std::size_t r = rows.size();
  auto joints = [&](bool measured) {
    return table(r, n, [&](std::size_t i, std::size_t k) {
      const std::vector<double>& q = measured ? rows[i].measured_joint_rad : rows[i].model_joint_rad;
      return k < q.size() ? q[k] : NAN;
    });
  };
  py::dict d;
  d["gauge_pa"] = column(r, [&](std::size_t i) { return rows[i].gauge_pa; });
  d["supplied_volume_m3"] = column(r, [&](std::size_t i) { return rows[i].supplied_volume_m3; });
  d["measured_gauge_pa"] = column(r, [&](std::size_t i) { return rows[i].measured_gauge_pa; });
  d["model_gauge_pa"] = column(r, [&](std::size_t i) { return rows[i].model_gauge_pa; });
  d["model_gauge_at_tip_angle_pa"] = column(r, [&](std::size_t i) { return rows[i].model_gauge_at_tip_angle_pa; });
  d["measured_joint_rad"] = joints(true);
  d["model_joint_rad"] = joints(false);
  d["measured_avg_rad"] = column(r, [&](std::size_t i) { return rows[i].measured_avg_rad; });
  d["model_avg_rad"] = column(r, [&](std::size_t i) { return rows[i].model_avg_rad; });
  d["measured_joint1_rad"] = column(r, [&](std::size_t i) { return rows[i].measured_joint1_rad; });
  d["model_joint1_rad"] = column(r, [&](std::size_t i) { return rows[i].model_joint1_rad; });
  d["measured_tip_angle_rad"] = column(r, [&](std::size_t i) { return rows[i].measured_tip_angle_rad; });
  d["model_tip_angle_rad"] = column(r, [&](std::size_t i) { return rows[i].model_tip_angle_rad; });
  d["measured_chord_angle_rad"] = column(r, [&](std::size_t i) { return rows[i].measured_chord_angle_rad; });
  d["measured_blocked_tip_force_n"] = column(r, [&](std::size_t i) { return rows[i].measured_blocked_force_n; });
  d["model_blocked_tip_force_n"] = column(r, [&](std::size_t i) { return rows[i].model_blocked_force_n; });
  d["model_chord_angle_rad"] = column(r, [&](std::size_t i) { return rows[i].model_chord_angle_rad; });
  d["measured_tip_m"] = table(r, 2, [&](std::size_t i, std::size_t k) {
    return k == 0 ? rows[i].measured_tip_x_m : rows[i].measured_tip_y_m;
  });
  d["model_tip_m"] = table(r, 2, [&](std::size_t i, std::size_t k) {
    return k == 0 ? rows[i].model_tip_x_m : rows[i].model_tip_y_m;
  });
  return d;
}

// The data: a CSV path, or names and columns (pneumatic_finger.core turns a dict of arrays into them).
pf::MeasurementSet measurements(const py::object& path, const std::vector<std::string>& names,
                                const std::vector<std::vector<double>>& columns, const std::string& average_column) {
  if (py::isinstance<py::list>(path)) {  // several files of one actuator
    return pf::readMeasurementSets(path.cast<std::vector<std::string>>(), 1, average_column);
  }
  if (!path.is_none()) return pf::readMeasurementSet(path.cast<std::string>(), 1, average_column);
  return pf::measurementSetFromColumns(names, columns, "data", 1, average_column);
}

py::dict uncertaintyOf(const pf::CalibrationResult& fit) {
  py::dict uncertainty;
  for (std::size_t i = 0; i < fit.keys.size(); ++i) uncertainty[py::str(fit.keys[i])] = fit.uncertainty[i];
  return uncertainty;
}

// How well the fit followed its data (None without leave-one-out), as the written file records it.
py::object calibrationErrorDict(const pf::CalibrationError& e) {
  if (e.empty()) return py::none();
  py::dict d;
  d["compared"] = e.compared;
  d["held_out_rms_rad"] = e.held_out_rms_rad;
  d["held_out_largest_rad"] = e.held_out_largest_rad;
  d["largest_at_gauge_pa"] = e.largest_at_gauge_pa;
  d["missed_rows"] = e.missed_rows;
  d["follows_data"] = e.follows_data;
  return std::move(d);
}

// --wall-law auto's candidates, each a dict (empty where nothing was chosen among candidates).
py::list candidateList(const pf::CalibrationRun& run) {
  py::list out;
  for (std::size_t i = 0; i < run.candidates.size(); ++i) {
    const pf::CandidateFit& c = run.candidates[i];
    py::dict d;
    d["wall_law"] = pf::wallLawName(c.law);
    d["compared"] = pf::quantityName(c.quantity);
    d["keys"] = py::cast(c.keys);
    d["held_out_bend_rad"] = c.skipped.empty() ? c.held_out.bend_rad : NAN;
    d["held_out_pressure"] = c.skipped.empty() ? c.held_out.pressure : NAN;
    // The largest blocked force held out, as a share of the largest measured (0 where no force is data).
    d["held_out_force"] = c.skipped.empty() ? c.held_out.force : NAN;
    d["score"] = c.skipped.empty() ? c.held_out.score : NAN;
    // The chosen's score widened by the choice's optimism (selectionOptimism): what its error bar takes.
    if (i == run.chosen_candidate) {
      d["corrected_score"] = pf::correctedScore(run.candidates, i);
    }
    d["rows_without_shape"] = c.held_out.unshaped;
    d["seconds"] = c.seconds;
    d["skipped"] = c.skipped;
    d["selected"] = c.selected;
    d["chosen"] = i == run.chosen_candidate;
    out.append(d);
  }
  return out;
}

py::dict calibrate(const py::object& path, const std::vector<std::string>& names,
                   const std::vector<std::vector<double>>& columns, const pf::CalibrationRequest& request,
                   const std::string& config, const py::dict& overrides) {
  pf::PressureRange file_range;  // the base file's, which the calibrated range starts from
  const pf::FingerParameters base = pf::calibrationBase(loadRaw(config, overrides, &file_range), request.wall_law);
  const pf::MeasurementSet data = measurements(path, names, columns, request.average_column);
  pf::CalibrationRun run;
  {
    py::gil_scoped_release release;
    run = pf::runCalibration(base, data, request);
  }
  const pf::WallLawFit& best = run.best();
  const auto n = static_cast<std::size_t>(base.chamber_count);
  py::dict fitted;
  for (std::size_t i = 0; i < best.fit.keys.size(); ++i) fitted[py::str(best.fit.keys[i])] = best.fit.values[i];
  py::dict d;
  d["fitted"] = fitted;
  d["wall_law"] = pf::wallLawName(best.law);
  d["compared"] = pf::quantityName(run.quantity);
  d["objective_value"] = best.fit.objective_value;
  d["residuals"] = residualArrays(best.fit.residuals, n);
  d["leave_one_out"] = request.leave_one_out ? py::object(residualArrays(best.leave_one_out, n)) : py::none();
  d["model_evaluations"] = best.fit.model_evaluations;
  d["uncertainty"] = uncertaintyOf(best.fit);
  const std::size_t k = best.fit.keys.size();
  d["correlation"] = table(k, k, [&](std::size_t a, std::size_t b) { return best.fit.correlation[a * k + b]; });
  d["warnings"] = py::cast(run.warnings);
  d["candidates"] = candidateList(run);
  d["calibration_error"] = calibrationErrorDict(run.calibration_error);
  // The file finger_calibrate --output writes (its keys; the Python wrapper adds the header): calibrate(output=).
  d["parameter_file"] = pf::calibratedParameterYaml(run, file_range);
  return d;
}

// finger_calibrate --coupon: the coupon from a file (@p path) or columns, the fit, and the file's text.
py::dict fitCoupon(const py::object& path, const std::vector<double>& strain, const std::vector<double>& stress,
                   const std::string& law, const std::string& config, const py::dict& overrides) {
  const bool gent = pf::parseCouponLaw(law);
  pf::PressureRange file_range;
  const pf::RawParameterMap raw = loadRaw(config, overrides, &file_range);
  const pf::CouponTest test =
      path.is_none() ? pf::couponFromColumns(strain, stress, "data") : pf::loadCouponCsv(py::cast<std::string>(path));
  pf::CouponFit fit;
  {
    py::gil_scoped_release release;
    fit = pf::fitCoupon(test, gent);
  }
  const std::string report = pf::couponFitReport(fit, test);
  py::dict d, sd;
  d["shear_modulus_pa"] = fit.shear_modulus_pa, sd["shear_modulus_pa"] = fit.shear_modulus_sd_pa;
  d["wall_locking_jm"] = fit.wall_locking_jm, sd["wall_locking_jm"] = fit.wall_locking_jm_sd;
  d["preload_strain"] = fit.preload_strain, sd["preload_strain"] = fit.preload_strain_sd;
  d["uncertainty"] = sd;
  d["rms_relative_error"] = fit.rms_relative_error;
  d["max_relative_error"] = fit.max_relative_error;
  const std::size_t r = test.rows.size();
  d["engineering_strain"] = column(r, [&](std::size_t i) { return test.rows[i].engineering_strain; });
  d["nominal_stress_pa"] = column(r, [&](std::size_t i) { return test.rows[i].nominal_stress_pa; });
  d["model_stress_pa"] = column(r, [&](std::size_t i) { return fit.model_stress_pa[i]; });
  d["report"] = report;
  d["parameter_file"] = pf::couponParameterYaml(raw, fit, file_range);
  return d;
}

}  // namespace

void defineCalibrate(py::module_& m) {
  defineDesign(m);
  m.def("fit_coupon", &fitCoupon, py::arg("path"), py::arg("strain"), py::arg("stress"), py::arg("law"),
        py::arg("config"), py::arg("overrides"),
        "finger_calibrate --coupon (use pneumatic_finger.core.fit_coupon): a CSV path, or strain and stress");
  m.def(
      "calibrate",
      [](const py::object& path, const std::vector<std::string>& names, const std::vector<std::vector<double>>& columns,
         const std::vector<std::string>& keys, const std::string& objective, const std::string& config,
         const py::dict& overrides, const std::string& average_column, const std::string& compare,
         const std::string& wall_law, bool leave_one_out, const std::string& drive) {
        pf::CalibrationRequest request;
        request.keys = keys;
        request.objective = objective;
        request.average_column = average_column;
        request.compare = compare;
        request.wall_law = wall_law;
        request.leave_one_out = leave_one_out;
        request.drive = drive;
        request.progress = pf::CalibrationProgressPrinter(std::cerr, "pf.calibrate");  // quiet for the first 2 s
        return calibrate(path, names, columns, request, config, overrides);
      },
      py::arg("path"), py::arg("names"), py::arg("columns"), py::arg("keys"), py::arg("objective"),
      py::arg("config"), py::arg("overrides"), py::arg("average_column"), py::arg("compare"), py::arg("wall_law"),
      py::arg("leave_one_out"), py::arg("drive"),
      "finger_calibrate's calibration (use pneumatic_finger.core.calibrate): a CSV path, or names and columns");
}

}  // namespace pneumatic_finger_python
