// pf.design_to_target: finger_design --target (calibration/design_target.hpp) from Python, with the same words.
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "calibrate_module.hpp"
#include "pneumatic_finger/calibration/design_target.hpp"
#include "python_parameters.hpp"

namespace pneumatic_finger_python {

namespace {

// The request from Python's arguments: targets as text, free keys as {key: (lo, hi)} (0: the default bound).
pf::DesignRequest designRequest(const std::vector<std::string>& targets, const py::dict& free,
                                const std::vector<int>& chamber_counts, double castable_m,
                                const std::vector<double>& max_body_m, const std::string& part, double max_gauge_pa,
                                double validated_max_gauge_pa) {
  pf::DesignRequest r;
  for (const std::string& t : targets) r.targets.push_back(pf::parseDesignTarget(t));
  pf::attachGripPart(r.targets, part, max_gauge_pa);
  r.validated_max_gauge_pa = validated_max_gauge_pa;
  for (const auto& item : free) {
    const auto bounds = item.second.cast<std::vector<double>>();
    if (bounds.size() != 2) throw pf::ParameterError("free: " + item.first.cast<std::string>() + " needs (lo, hi)");
    r.free.push_back({item.first.cast<std::string>(), bounds[0], bounds[1]});
  }
  r.chamber_counts = chamber_counts;
  r.castable_m = castable_m;
  if (max_body_m.size() != 3) throw pf::ParameterError("max_body_m: (length, width, height) in m, 0 for no limit");
  r.max_body_length_m = max_body_m[0], r.max_body_width_m = max_body_m[1], r.max_body_height_m = max_body_m[2];
  return r;
}

// One design of a Pareto front: its sizes, count, what it achieves and misses, and its reach.
py::dict frontDesign(const pf::DesignAnswer& a, const pf::DesignRequest& request) {
  py::dict values, achieved, misses;
  for (std::size_t k = 0; k < request.free.size(); ++k) values[py::str(request.free[k].key)] = a.values[k];
  for (std::size_t i = 0; i < request.targets.size(); ++i) {
    achieved[py::str(request.targets[i].text)] = a.achieved[i];
    misses[py::str(request.targets[i].text)] = a.misses[i];
  }
  py::dict d;
  d["values"] = values;
  d["chamber_count"] = a.chamber_count;
  d["achieved"] = achieved;
  d["misses"] = misses;
  d["reach"] = a.reach;
  return d;
}

py::dict designToTarget(const std::string& config, const py::dict& overrides, const std::vector<std::string>& targets,
                        const py::dict& free, const std::vector<int>& chamber_counts, double castable_m,
                        const std::vector<double>& max_body_m, int pareto, const std::string& part) {
  pf::PressureRange range;
  const pf::FingerParameters base = pf::FingerParameters::fromRaw(loadRaw(config, overrides, &range));
  const pf::DesignRequest request = designRequest(targets, free, chamber_counts, castable_m, max_body_m, part,
                                                          range.max_gauge_pa, range.validated_max_gauge_pa);
  pf::DesignAnswer a;
  std::vector<pf::DesignAnswer> front;
  {
    py::gil_scoped_release release;
    a = pf::designToTarget(base, request);
    if (pareto > 0) front = pf::designParetoFront(base, request, pareto);
  }
  py::dict values, drawn, achieved;
  for (std::size_t k = 0; k < request.free.size(); ++k) {
    values[py::str(request.free[k].key)] = a.values[k];
    drawn[py::str(request.free[k].key)] = a.drawn[k];
  }
  for (std::size_t i = 0; i < request.targets.size(); ++i) achieved[py::str(request.targets[i].text)] = a.achieved[i];
  py::dict d;
  d["values"] = values;
  d["drawn"] = drawn;
  d["chamber_count"] = a.chamber_count;
  d["achieved"] = achieved;
  d["miss"] = a.miss;
  d["met"] = a.met;
  d["at_bound"] = py::cast(a.at_bound);
  d["notes"] = py::cast(a.notes);
  d["reach"] = a.reach;
  d["seconds"] = a.seconds;
  d["parameter_file"] = pf::designParameterYaml(a, request, range.max_gauge_pa);
  py::list designs;
  for (const pf::DesignAnswer& f : front) designs.append(frontDesign(f, request));
  d["pareto"] = designs;
  return d;
}

// The lowest pressure at which the gripper holds a part (finger_model --pressures --grip-part): (Pa or NaN, why not).
py::tuple gripGaugePa(const std::string& config, const py::dict& overrides, const std::string& part,
                      const py::object& max_gauge_pa) {
  pf::PressureRange range;
  const pf::FingerModel model(pf::FingerParameters::fromRaw(loadRaw(config, overrides, &range)));
  pf::SideGripTask task = pf::parseSideGripTask(part);
  task.max_gauge_pa = max_gauge_pa.is_none() ? range.max_gauge_pa : max_gauge_pa.cast<double>();
  std::string why;
  double gauge_pa = 0.0;
  {
    py::gil_scoped_release release;
    gauge_pa = pf::holdingGaugePa(model, task, &why);
  }
  return py::make_tuple(gauge_pa, why);
}

}  // namespace

void defineDesign(py::module_& m) {
  m.def("grip_gauge_pa", &gripGaugePa, py::arg("config"), py::arg("overrides"), py::arg("part"),
        py::arg("max_gauge_pa"), "finger_model --pressures --grip-part (use pneumatic_finger.core.grip_gauge_pa)");
  m.def("design_to_target", &designToTarget, py::arg("config"), py::arg("overrides"), py::arg("targets"),
        py::arg("free"), py::arg("chamber_counts"), py::arg("castable_m"), py::arg("max_body_m"), py::arg("pareto"),
        py::arg("part"),
        "finger_design --target (use pneumatic_finger.core.design_to_target)");
}

}  // namespace pneumatic_finger_python
