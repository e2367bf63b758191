// pf.range_check (range_module.hpp).
#include "range_module.hpp"

#include <algorithm>
#include <string>

#include "pneumatic_finger/core/pressure_range.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace py = pybind11;
namespace pf = pneumatic_finger;

namespace pneumatic_finger_python {

void defineRangeCheck(py::module_& m) {
  m.def(
      "range_check",
      [](double gauge_pa, const py::object& max_gauge_pa, const py::object& validated_max_gauge_pa) {
        pf::PressureRange range =
            max_gauge_pa.is_none() ? pf::PressureRange() : pf::PressureRange::upTo(max_gauge_pa.cast<double>());
        if (!validated_max_gauge_pa.is_none()) {  // a model's own range (FingerModel.validated_max_gauge_pa)
          const double validated = validated_max_gauge_pa.cast<double>();
          pf::checkParameterValue(pf::rangeParameterSpec("validated_max_gauge_pa"), validated);
          range.validated_max_gauge_pa = std::min(validated, range.max_gauge_pa);
        }
        const pf::RangeCheck c = pf::checkGaugeRange(gauge_pa, range);
        const std::string words = c.clamped         ? pf::clampedMessage(gauge_pa, range)
                                  : gauge_pa < 0    ? pf::vacuumMessage(gauge_pa)
                                  : c.above_validated ? pf::aboveValidatedMessage(gauge_pa, range)
                                                      : std::string();
        return py::make_tuple(c.gauge_pa, words);
      },
      py::arg("gauge_pa"), py::arg("max_gauge_pa") = py::none(), py::arg("validated_max_gauge_pa") = py::none(),
      "The model's range rule, as finger_node, finger_model and evaluate() apply it: (the pressure to evaluate, the "
      "words to warn with, empty in range). The range is the default's unless given: pass a model's "
      "max_gauge_pa and validated_max_gauge_pa to apply its file's range");
}

}  // namespace pneumatic_finger_python
