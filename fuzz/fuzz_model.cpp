// libFuzzer target over the YAML parameter loader and the model evaluation (scripts/fuzz.sh builds and runs it).
//
// Input layout: the bytes up to the first NUL are YAML text for the loader (the same path finger_model,
// finger_calibrate and the node's config take); the bytes after it are read as doubles: pressures (any bit pattern,
// so NaN, infinities and subnormals too) and tip angles for the inverse model.
// A refused parameter set must be refused with ParameterError and nothing else. For an accepted one, every solver
// except `paper` must give finite joint angles and backbone for every finite pressure; the paper solver must not
// crash (its NaN on hard cases is documented behaviour).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const uint8_t* nul = static_cast<const uint8_t*>(std::memchr(data, 0, size));
  const std::size_t text_size = nul ? static_cast<std::size_t>(nul - data) : size;
  const std::string yaml(reinterpret_cast<const char*>(data), text_size);
  std::vector<double> numbers;
  for (std::size_t i = text_size + 1; i + sizeof(double) <= size; i += sizeof(double)) {
    double v;
    std::memcpy(&v, data + i, sizeof v);
    numbers.push_back(v);
  }
  pf::FingerParameters params;
  try {
    pf::RawParameterMap raw;
    pf::loadRawParametersFromYamlText(yaml, "fuzz", raw);
    params = pf::FingerParameters::fromRaw(raw);
  } catch (const pf::ParameterError&) {
    return 0;  // refused with a message: the defined behaviour
  }
  if (numbers.empty()) numbers = {0.0, 1e5, 2e5};
  for (pf::SolverKind solver : {pf::SolverKind::kRobust, pf::SolverKind::kTable, pf::SolverKind::kPaper}) {
    pf::ModelOptions options;
    options.solver = solver;
    options.table_max_gauge_pa = 3e5;
    pf::FingerModel model(params, options);
    pf::FingerWorkspace ws(model);
    for (double p : numbers) {
      const pf::FingerState& s = model.evaluate(p, ws);
      if (!std::isfinite(p)) {
        if (s.status != pf::EvaluationStatus::kNotFinite) __builtin_trap();
        continue;
      }
      const bool finite = s.joint_angle_rad.allFinite() && s.backbone_m.allFinite() && std::isfinite(s.tip_angle_rad);
      if (!finite && solver != pf::SolverKind::kPaper) __builtin_trap();  // NaN output for accepted parameters
    }
    if (solver == pf::SolverKind::kRobust) {
      for (double angle : numbers) {
        double gauge = 0;
        std::string why;
        if (model.gaugeForTipAngle(angle, 1e7, gauge, why) && !(gauge >= 0 && gauge <= 1e7)) __builtin_trap();
      }
    }
  }
  return 0;
}
