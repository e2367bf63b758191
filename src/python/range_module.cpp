// pf.range_check (range_module.hpp).
#include "range_module.hpp"

#include <string>

#include "pneumatic_finger/core/pressure_range.hpp"

namespace py = pybind11;
namespace pf = pneumatic_finger;

namespace pneumatic_finger_python {

void defineRangeCheck(py::module_& m) {
  m.def(
      "range_check",
      [](double gauge_pa, const py::object& max_gauge_pa) {
        const pf::PressureRange range =
            max_gauge_pa.is_none() ? pf::PressureRange() : pf::PressureRange::upTo(max_gauge_pa.cast<double>());
        const pf::RangeCheck c = pf::checkGaugeRange(gauge_pa, range);
        const std::string words = c.clamped         ? pf::clampedMessage(gauge_pa, range)
                                  : gauge_pa < 0    ? pf::vacuumMessage(gauge_pa)
                                  : c.above_validated ? pf::aboveValidatedMessage(gauge_pa, range)
                                                      : std::string();
        return py::make_tuple(c.gauge_pa, words);
      },
      py::arg("gauge_pa"), py::arg("max_gauge_pa") = py::none(),
      "The model's range rule, as finger_node, finger_model and evaluate() apply it: (the pressure to evaluate, the "
      "words to warn with, empty in range)");
}

}  // namespace pneumatic_finger_python
