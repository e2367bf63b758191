// The normal force at each contact point of a finger the contact rule holds (docs/MODEL.md, "Force"). The held
// joints' moments (FingerModel::heldJointMomentsNm) are the load; the object answers at the contact points, along
// the normals of the touching backbone segments, frictionless. As for the blocked tip force, the chain is statically
// indeterminate and the joints' compliance shares the load: joint j turns by (M_j - sum_k r_jk F_k) w_j, and no
// contact point moves along its normal, sum_j r_jk (M_j - sum_l r_jl F_l) w_j = 0 for every contact k. r_jk is how
// far contact k moves into the object per radian of joint j: (z x (p_k - O_j)) . n_k, for the joints that move the
// touching segment (1..m for segment O_m -> O_{m+1}).
#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "pneumatic_finger/core/contact.hpp"

namespace pneumatic_finger {

namespace {

// The small normal equations, A F = b, with F >= 0: a contact that would pull (F_k < 0) is let go (the most negative
// first) and the rest solved again. A has at most one row per touch event.
void solveNonNegative(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, std::vector<double>& force_n) {
  const auto k = static_cast<int>(b.size());
  std::vector<bool> active(static_cast<std::size_t>(k), true);
  force_n.assign(static_cast<std::size_t>(k), 0.0);
  for (int round = 0; round < k; ++round) {
    std::vector<int> idx;
    for (int i = 0; i < k; ++i) {
      if (active[static_cast<std::size_t>(i)]) idx.push_back(i);
    }
    const auto m = static_cast<Eigen::Index>(idx.size());
    Eigen::MatrixXd sub(m, m);
    Eigen::VectorXd rhs(m);
    for (Eigen::Index r = 0; r < m; ++r) {
      rhs(r) = b(idx[static_cast<std::size_t>(r)]);
      for (Eigen::Index c = 0; c < m; ++c) sub(r, c) = a(idx[static_cast<std::size_t>(r)], idx[static_cast<std::size_t>(c)]);
    }
    // Two contacts on one segment give equal rows: the least-norm answer shares between them.
    const Eigen::VectorXd f = sub.completeOrthogonalDecomposition().solve(rhs);
    Eigen::Index worst = 0;
    if (m == 0 || f.minCoeff(&worst) >= 0) {
      for (Eigen::Index r = 0; r < m; ++r) force_n[static_cast<std::size_t>(idx[static_cast<std::size_t>(r)])] = f(r);
      return;
    }
    active[static_cast<std::size_t>(idx[static_cast<std::size_t>(worst)])] = false;
  }
}

// The flexion-side normal of backbone segment @p segment: into the object.
Eigen::Vector2d segmentNormal(const ContactState& contact, int segment) {
  const Eigen::Vector2d d = contact.backbone_m.col(segment + 1) - contact.backbone_m.col(segment);
  return Eigen::Vector2d(-d.y(), d.x()).normalized();
}

// How far @p point moves along @p normal per radian of joint j (0-based; joints 1..segment move its segment).
double lever(const ContactState& contact, const Eigen::Vector2d& normal, const Eigen::Vector2d& point, int j) {
  const Eigen::Vector2d arm = point - contact.backbone_m.col(j + 1);  // O_{j+1} is joint j + 1's axis
  return Eigen::Vector2d(-arm.y(), arm.x()).dot(normal);
}

// One contact (the usual grasp): F = sum_j w_j M_j r_j / sum_j w_j r_j^2, no matrix, no allocation; 0 if it would pull.
double singleContactForceN(const FingerModel& model, const ContactState& contact, const double* moment) {
  const int segment = contact.contact_segments[0];
  const Eigen::Vector2d normal = segmentNormal(contact, segment);
  double num = 0.0, den = 0.0;
  for (int j = 0; j < segment && j < model.chamberCount(); ++j) {
    const double r = lever(contact, normal, contact.contact_points_m[0], j), w = model.jointComplianceWeight(j);
    num += w * moment[j] * r;
    den += w * r * r;
  }
  const double f = num / den;
  return std::isnan(f) || f > 0 ? f : 0.0;
}

}  // namespace

void contactNormalForcesN(const FingerModel& model, double gauge_pa, const ContactState& contact,
                          std::vector<double>& force_n) {
  force_n.clear();
  if (contact.status != ContactState::Status::kInContact || contact.contact_points_m.empty()) return;
  const int n = model.chamberCount();
  const auto count = static_cast<Eigen::Index>(contact.contact_points_m.size());
  std::array<double, kMaxChamberCount> moment;
  model.heldJointMomentsNm(gauge_pa, contact.held_since_gauge_pa.data(), moment.data());
  if (count == 1) {
    force_n.push_back(singleContactForceN(model, contact, moment.data()));
    return;
  }
  // r (joints x contacts): the lever of each contact's normal force about each joint that moves it.
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(n, count);
  for (Eigen::Index k = 0; k < count; ++k) {
    const int segment = contact.contact_segments[static_cast<std::size_t>(k)];
    const Eigen::Vector2d& p = contact.contact_points_m[static_cast<std::size_t>(k)];
    const Eigen::Vector2d normal = segmentNormal(contact, segment);
    for (int j = 0; j < segment && j < n; ++j) r(j, k) = lever(contact, normal, p, j);
  }
  Eigen::VectorXd w(n), m(n);
  for (int j = 0; j < n; ++j) {
    w(j) = model.jointComplianceWeight(j);
    m(j) = moment[static_cast<std::size_t>(j)];
  }
  if (!m.allFinite()) {
    force_n.assign(static_cast<std::size_t>(count), std::numeric_limits<double>::quiet_NaN());
    return;
  }
  const Eigen::MatrixXd a = r.transpose() * w.asDiagonal() * r;
  const Eigen::VectorXd b = r.transpose() * w.asDiagonal() * m;
  solveNonNegative(a, b, force_n);
}

double totalContactForceN(const FingerModel& model, double gauge_pa, const ContactState& contact) {
  std::vector<double> force;
  contactNormalForcesN(model, gauge_pa, contact, force);
  double total = 0.0;
  for (double f : force) total += f;
  return total;
}

// The force is 0 up to the touch and does not fall beyond it (each held wall's strip grows with the pressure, and a new
// touch adds a contact): the pressure for a force is bracketed by [0, max] and halved until it is known to 1e-9 of
// the range, far below the regulator's resolution.
bool gaugeForContactForce(const FingerModel& model, const std::function<ContactState(double)>& contact_at,
                          double force_n, double max_gauge_pa, double& gauge_pa, std::string& why) {
  auto force_at = [&](double p) { return totalContactForceN(model, p, contact_at(p)); };
  std::ostringstream s;
  if (!(force_n > 0) || !std::isfinite(force_n)) {
    s << "force " << force_n << " N is not a finite force > 0";
    why = s.str();
    return false;
  }
  const double most = force_at(max_gauge_pa);
  if (!(most >= force_n)) {
    // The asked force as the caller wrote it (formatMessage: 12.80665, not 12.8066), the computed ones to six digits.
    s << "presses with at most " << most << " N, at " << formatMessage(max_gauge_pa)
      << " Pa (the top of its range), short of " << formatMessage(force_n) << " N";
    why = s.str();
    return false;
  }
  double lo = 0.0, hi = max_gauge_pa;
  while (hi - lo > 1e-9 * max_gauge_pa) {
    const double mid = 0.5 * (lo + hi);
    (force_at(mid) >= force_n ? hi : lo) = mid;
  }
  gauge_pa = hi;
  return true;
}

}  // namespace pneumatic_finger
