// One evaluation as every interface reports it (evaluation_report.hpp).
#include "pneumatic_finger/core/evaluation_report.hpp"

namespace pneumatic_finger {

const char* statusFlagName(int bit) {
  static const char* const kNames[kStatusFlagCount] = {"clamped", "far branch", "meets itself", "extrapolated"};
  return bit >= 0 && bit < kStatusFlagCount ? kNames[bit] : "unknown";
}

std::string statusFlagNames(std::uint8_t flags) {
  std::string out;
  for (int bit = 0; bit < kStatusFlagCount; ++bit) {
    if (flags & (1u << bit)) out += (out.empty() ? "" : ", ") + std::string(statusFlagName(bit));
  }
  return out.empty() ? "none" : out;
}

EvaluationReport reportEvaluation(EvaluationStatus model_status, const RangeCheck& range, bool meets_itself) {
  using S = EvaluationStatus;
  const bool refused = model_status == S::kVacuum || model_status == S::kNotFinite ||
                       model_status == S::kSolverFailure || model_status == S::kBeyondLimitPoint;
  EvaluationReport report;
  report.status = refused        ? model_status
                  : meets_itself ? S::kMeetsItself
                  : range.clamped ? S::kClamped
                                  : model_status;
  if (range.clamped) report.flags |= kFlagClamped;
  if (model_status == S::kSnappedThrough) report.flags |= kFlagFarBranch;
  if (meets_itself && !refused) report.flags |= kFlagMeetsItself;
  if (range.above_validated && model_status != S::kNotFinite) report.flags |= kFlagExtrapolated;
  return report;
}

}  // namespace pneumatic_finger
