// Every key a parameter file may hold, and the one message for a key that is none of them (parameters.hpp).
#include <algorithm>
#include <string>
#include <vector>

#include "pneumatic_finger/core/drawing.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pneumatic_finger {

namespace {

// Levenshtein distance: a typo is a letter left out, added, swapped or changed.
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

std::vector<std::string> knownParameterFileKeys() {
  std::vector<std::string> keys;
  for (const ParameterSpec& spec : parameterSpecs()) keys.emplace_back(spec.key);
  for (const ParameterSpec& spec : drawingParameterSpecs()) keys.push_back(kDrawingPrefix + std::string(spec.key));
  for (const ParameterSpec& spec : rangeParameterSpecs()) keys.emplace_back(spec.key);
  for (const std::string& key : nodeInterfaceKeys()) keys.push_back(key);
  keys.emplace_back(kTipUncertaintyKey);
  return keys;
}

ParameterError unknownParameterError(const std::string& key, const std::string& origin) {
  std::string nearest;
  std::size_t best = std::max<std::size_t>(2, key.size() / 4) + 1;  // a typo, not another word
  for (const std::string& known : knownParameterFileKeys()) {
    const std::size_t d = editDistance(key, known);
    if (d < best) best = d, nearest = known;
  }
  const std::string hint = nearest.empty() ? " (`finger_model --parameters` lists the keys)"
                                           : " (did you mean '" + nearest + "'?)";
  return ParameterError((origin.empty() ? "" : origin + ": ") + "unknown parameter '" + key + "'" + hint);
}

}  // namespace pneumatic_finger
