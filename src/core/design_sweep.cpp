// sweepDesigns: one model per design, each evaluated once. The raw map of the base is built once and only the swept
// keys change in it, so a design costs the loader's validation, the model's construction and one evaluation.
#include "pneumatic_finger/core/design_sweep.hpp"

#include "pneumatic_finger/core/drawing.hpp"
#include "pneumatic_finger/core/evaluation_report.hpp"
#include "pneumatic_finger/core/self_contact.hpp"

#include <limits>
#include <optional>

namespace pneumatic_finger {

namespace {

void writeNan(const DesignOutputs& out, std::size_t d) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double* o : {out.tip_angle_rad, out.tip_x_m, out.tip_y_m, out.contact_gauge_pa, out.snap_gauge_pa,
                    out.limit_gauge_pa}) {
    if (o) o[d] = nan;
  }
  if (out.status) out.status[d] = static_cast<std::uint8_t>(EvaluationStatus::kNotFinite);
  if (out.status_flags) out.status_flags[d] = 0;
}

// One design's status and flags by the one rule, from its row (joint angles written) and the input's range check.
void writeReport(const FingerModel& model, const BatchBuffers& row, const RangeCheck& input, const DesignOutputs& out,
                 std::size_t d) {
  const bool meets = jointsMeetThemselves(model.parameters(), row.joint_angle_rad.data());  // NaN rows never do
  const EvaluationReport report = reportEvaluation(static_cast<EvaluationStatus>(row.status[0]), input, meets);
  if (out.status) out.status[d] = static_cast<std::uint8_t>(report.status);
  if (out.status_flags) out.status_flags[d] = report.flags;
}

}  // namespace

std::vector<DesignRefusal> sweepDesigns(const FingerParameters& base, const ModelOptions& options,
                                        const std::vector<std::string>& keys, const double* values,
                                        std::size_t designs, double gauge_pa, const DesignOutputs& out,
                                        const RangeCheck& input) {
  for (const std::string& key : keys) {
    if (!isDrawingKey(key) && findParameterSpec(key) == nullptr) {
      throw unknownParameterError(key);
    }
  }
  RawParameterMap raw = base.toRaw();
  ModelOptions design_options = options;
  design_options.wall_inverse = false;  // one pressure per design: the wall's inverse would cost more than it saves
  design_options.snap_point = out.snap_gauge_pa != nullptr;  // a scan and a golden section: only when asked
  std::vector<DesignRefusal> refused;
  const bool wants_report = out.status || out.status_flags;
  const bool wants_shape = out.tip_angle_rad || out.tip_x_m || out.tip_y_m || wants_report;
  const bool wants_points = out.tip_x_m || out.tip_y_m;
  std::optional<FingerWorkspace> workspace;
  std::optional<BatchBuffers> row;
  int layout_chambers = 0, layout_groups = 0;
  for (std::size_t d = 0; d < designs; ++d) {
    for (std::size_t j = 0; j < keys.size(); ++j) raw[keys[j]] = {{values[d * keys.size() + j]}, false};
    std::optional<FingerModel> model;
    try {
      model.emplace(FingerParameters::fromRaw(raw), design_options);
    } catch (const ParameterError& e) {
      refused.push_back({d, e.what()});
      writeNan(out, d);
      continue;
    }
    if (out.contact_gauge_pa) out.contact_gauge_pa[d] = model->contactGaugePa();
    if (out.snap_gauge_pa) out.snap_gauge_pa[d] = model->snapGaugePa();
    if (out.limit_gauge_pa) out.limit_gauge_pa[d] = model->limitGaugePa();
    if (!wants_shape) continue;
    const int n = model->chamberCount(), groups = model->distinctChamberCount();
    // The scratch is sized once per chamber layout: a sweep of one layout allocates nothing for it after its first
    // design. (The workspace's cache is never consulted: evaluateMany neither reads nor writes it.)
    if (!workspace || n != layout_chambers || groups != layout_groups) {
      row.emplace(1, n);
      workspace.emplace(*model);
      layout_chambers = n;
      layout_groups = groups;
    }
    BatchOutputs one;
    one.tip_angle_rad = row->tip_angle_rad.data();
    one.backbone_m = wants_points ? row->backbone_m.data() : nullptr;
    one.status = row->status.data();
    one.joint_angle_rad = wants_report ? row->joint_angle_rad.data() : nullptr;  // for the self-contact check
    model->startBranch(*workspace, false);  // from rest, as its own model: no branch from the design before
    model->evaluateMany(&gauge_pa, 1, one, *workspace, BatchPath::kScalar);
    if (out.tip_angle_rad) out.tip_angle_rad[d] = row->tip_angle_rad[0];
    if (out.tip_x_m) out.tip_x_m[d] = row->backbone_m[2 * static_cast<std::size_t>(n + 1)];
    if (out.tip_y_m) out.tip_y_m[d] = row->backbone_m[2 * static_cast<std::size_t>(n + 1) + 1];
    if (wants_report) writeReport(*model, *row, input, out, d);
  }
  return refused;
}

}  // namespace pneumatic_finger
