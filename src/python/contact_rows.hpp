// What Python's contact() and contact_volume() write, row by row: the contact rule's state of the finger closing on a
// disk at each pressure (ContactTracker), its touches' points and forces, and its supplied volume. Internal header of
// the Python module (src/python).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pneumatic_finger/core/contact.hpp"
#include "output_arrays.hpp"
#include "status_codes.hpp"

namespace pneumatic_finger_python {

namespace pf = pneumatic_finger;

inline const std::vector<OutputField> kContactFields = {
    {"joint_angle_rad", Element::kFloat64, {-1}},  {"backbone_m", Element::kFloat64, {-2, 2}},
    {"held", Element::kFlag, {-1}},                {"first_touch_gauge_pa", Element::kFloat64, {}},
    {"status", Element::kCode, {}},                {"contact_point_m", Element::kFloat64, {-1, 2}},
    {"normal_force_n", Element::kFloat64, {-1}},   {"supplied_volume_m3", Element::kFloat64, {}},
    {"gauge_pa", Element::kFloat64, {}}};

// Where contact() writes (null: not asked for).
struct ContactRows {
  double* joint_angle_rad;
  double* backbone_m;
  bool* held;
  double* first_touch_gauge_pa;
  std::uint8_t* status;
  double* contact_point_m;     // (N, 2) per pressure: the touches in order, NaN after the last
  double* normal_force_n;      // (N,) per pressure: the normal force at each, NaN after the last (computed only if asked)
  double* supplied_volume_m3;  // suppliedVolumeInContact (computed only if asked)
  double* gauge_pa;
};

inline ContactRows contactRows(OutputArrays& a) {
  return {a.data<double>("joint_angle_rad"),      a.data<double>("backbone_m"),     a.data<bool>("held"),
          a.data<double>("first_touch_gauge_pa"), a.data<std::uint8_t>("status"),   a.data<double>("contact_point_m"),
          a.data<double>("normal_force_n"),       a.data<double>("supplied_volume_m3"), a.data<double>("gauge_pa")};
}

// The disks of a call: one (3,) for every input, or one per input (P, 3). @throws py::value_error naming the problem
inline std::vector<pf::Obstacle> disksOf(const py::object& disk, py::ssize_t count, bool scalar) {
  using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
  const Array disks = Array::ensure(disk);
  const bool per_input = disks && disks.ndim() == 2;
  if (!disks || !((disks.ndim() == 1 && disks.shape(0) == 3) ||
                  (per_input && disks.shape(0) == count && disks.shape(1) == 3 && !scalar))) {
    throw py::value_error("disk must be (x_m, y_m, radius_m), or an array of shape (P, 3): one per pressure");
  }
  std::vector<pf::Obstacle> obstacles;
  for (py::ssize_t i = 0; i < (per_input ? disks.shape(0) : 1); ++i) {
    const double* d = disks.data() + 3 * i;
    obstacles.push_back(pf::Obstacle::disk(d[0], d[1], d[2]));
    const std::string problem = obstacles.back().problem();
    if (!problem.empty()) throw py::value_error((per_input ? "disk " + std::to_string(i) + ": " : "") + problem);
  }
  return obstacles;
}

inline bool sameDisk(const pf::Obstacle& a, const pf::Obstacle& b) {
  Eigen::Vector2d ca, cb;
  double ra = 0, rb = 0;
  return a.asDisk(ca, ra) && b.asDisk(cb, rb) && ca == cb && ra == rb;
}

// Calls @p each(i, tracker) for every input, with one tracker per run of the same disk.
template <class F>
void forEachOnItsDisk(const pf::FingerModel& model, std::size_t count, const std::vector<pf::Obstacle>& obstacles,
                      F&& each) {
  std::unique_ptr<pf::ContactTracker> tracker;  // const methods of the model only: thread-safe
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t which = obstacles.size() == 1 ? 0 : i;
    if (!tracker || (which > 0 && !sameDisk(obstacles[which], obstacles[which - 1]))) {
      tracker = std::make_unique<pf::ContactTracker>(model, obstacles[which]);
    }
    each(i, *tracker);
  }
}

// The pressure at which the finger on each disk has taken each volume (gaugeForVolumeInContact, up to
// @p max_gauge_pa), into @p gauge_pa. The first volume it cannot take: its message (empty: all taken).
inline std::string gaugesForVolumes(const pf::FingerModel& model, const double* volume_m3, std::size_t count,
                                    const std::vector<pf::Obstacle>& obstacles, double max_gauge_pa, double* gauge_pa) {
  std::string why;
  forEachOnItsDisk(model, count, obstacles, [&](std::size_t i, pf::ContactTracker& tracker) {
    std::string problem;
    if (!why.empty()) return;
    if (!pf::gaugeForVolumeInContact(model, [&tracker](double p) { return tracker.solve(p); }, volume_m3[i],
                                     max_gauge_pa, gauge_pa[i], problem)) {
      why = "supplied_volume_m3[" + std::to_string(i) + "]: " + problem;
    }
  });
  return why;
}

// The contact points and, only when asked for, their normal forces (contactNormalForcesN), NaN-padded to N.
inline void writeTouches(const pf::FingerModel& model, const pf::ContactState& s, double gauge_pa,
                         const ContactRows& rows, std::size_t i) {
  const auto n = static_cast<std::size_t>(model.chamberCount());
  if (rows.contact_point_m) {
    double* row = rows.contact_point_m + i * 2 * n;
    std::fill(row, row + 2 * n, NAN);
    for (std::size_t k = 0; k < s.contact_points_m.size() && k < n; ++k) {
      row[2 * k] = s.contact_points_m[k].x();
      row[2 * k + 1] = s.contact_points_m[k].y();
    }
  }
  if (rows.normal_force_n) {
    std::vector<double> force;
    pf::contactNormalForcesN(model, gauge_pa, s, force);
    double* row = rows.normal_force_n + i * n;
    std::fill(row, row + n, NAN);
    std::copy(force.begin(), force.begin() + static_cast<std::ptrdiff_t>(std::min(force.size(), n)), row);
  }
}

// The contact rule's state at each pressure into @p rows.
inline void solveContacts(const pf::FingerModel& model, const double* gauge_pa, std::size_t count,
                          const std::vector<pf::Obstacle>& obstacles, const ContactRows& rows) {
  const auto n = static_cast<std::size_t>(model.chamberCount());
  forEachOnItsDisk(model, count, obstacles, [&](std::size_t i, pf::ContactTracker& tracker) {
    const pf::ContactState s = tracker.solve(gauge_pa[i]);
    if (rows.joint_angle_rad) std::copy(s.joint_angle_rad.data(), s.joint_angle_rad.data() + n, rows.joint_angle_rad + i * n);
    if (rows.backbone_m) std::copy(s.backbone_m.data(), s.backbone_m.data() + 2 * (n + 2), rows.backbone_m + i * 2 * (n + 2));
    for (std::size_t k = 0; rows.held && k < n; ++k) rows.held[i * n + k] = s.held[k];
    if (rows.first_touch_gauge_pa) rows.first_touch_gauge_pa[i] = s.first_touch_gauge_pa;
    if (rows.status) rows.status[i] = contactStatusCode(s.status);
    if (rows.supplied_volume_m3) rows.supplied_volume_m3[i] = pf::suppliedVolumeInContact(model, s, gauge_pa[i]);
    if (rows.gauge_pa) rows.gauge_pa[i] = gauge_pa[i];
    writeTouches(model, s, gauge_pa[i], rows, i);
  });
}

}  // namespace pneumatic_finger_python
