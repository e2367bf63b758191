// Stages 5-6 of docs/MODEL.md, written once for a plain double and for a pack of doubles: the backbone's step (eq 38),
// and for identical chambers joint 1's angle and direction and the backbone's points. The single evaluation (uniform_shape.hpp) and the batch
// kernel (batch_kernel.hpp) instantiate the same templates, so both round alike. Internal header of src/core; internal
// linkage as in simd_math.hpp.
#pragma once

#include "pneumatic_finger/core/stages.hpp"
#include "simd_math.hpp"

namespace pneumatic_finger {
namespace {  // NOLINT(build/namespaces): internal linkage per instruction set (simd_math.hpp)

/// Joint 1 of identical chambers (docs/MODEL.md stage 5): q_1 = theta_0 + theta with theta_0 = s0 theta (the passive
/// base segment's face); with s0 = 0, q_1 = theta exactly.
template <class T>
inline T firstJointAngle(double base_wall_share, T theta) {
  return base_wall_share == 0.0 ? theta : base_wall_share * theta + theta;
}

/// Eq 38, one segment of the backbone: the direction (dir_c, dir_s) turns by the joint's rotation (rot_c, rot_s) =
/// (cos q, sin q), and the point (x, y) advances by the segment's length z along it. The sequential form, for joints
/// that are not all alike: the general chain (finger_model.cpp), the contact rule's held joints (contact.cpp) and
/// measured joints (calibration.cpp). Identical free chambers take uniformPoints below (powers of one rotation).
template <class T>
inline void advanceBackbone(T rot_c, T rot_s, double z, T& dir_c, T& dir_s, T& x, T& y) {
  const T c = dir_c * rot_c - dir_s * rot_s;
  dir_s = dir_s * rot_c + dir_c * rot_s;
  dir_c = c;
  x += z * dir_c;
  y += z * dir_s;
}

/// Up to this tan(theta), joint 1's direction comes from its series (FirstJointSeries, stages.hpp).
constexpr double kFirstJointSeriesLimit = 0.125;

/// Joint 1 of identical chambers: q_1 (firstJointAngle) and the direction of segment 1, e^(i q_1) = e^(i (1 + s0)
/// theta). With s0 = 0 nothing is computed: the direction is theta's own, exactly. Up to tan(theta) = 1/8 (7 degrees:
/// the calibrated finger's validated range) it is @p series in t (stages.hpp); above, the base face's sine and cosine
/// rotate theta's
/// (a pack takes the form each lane needs, both only when its lanes straddle the limit).
/// @return q_1
template <class T>
inline T firstJoint(double base_wall_share, const FirstJointSeries& series, T theta, T tan_half, T cos_half,
                    T sin_half, T& first_c, T& first_s) {
  if (base_wall_share == 0.0) {
    first_c = cos_half;
    first_s = sin_half;
    return theta;
  }
  auto fromSeries = [&](T& c, T& s) {
    const T z = tan_half * tan_half;
    c = estrin(series.cos_c, z);
    s = tan_half * estrin(series.sin_c, z);
  };
  auto fromFace = [&](T& c, T& s) {
    T c0, s0;
    sinCosSmall(base_wall_share * theta, c0, s0);
    c = c0 * cos_half - s0 * sin_half;
    s = s0 * cos_half + c0 * sin_half;
  };
  bool all_series, any_series;
  if constexpr (lanesOf<T>() == 1) {
    all_series = any_series = tan_half <= kFirstJointSeriesLimit;
  } else {
    const auto lane = tan_half <= splat<T>(kFirstJointSeriesLimit);
    all_series = !anyOf(notOf(lane));
    any_series = anyOf(lane);
  }
  if (all_series) {
    fromSeries(first_c, first_s);
  } else if (!any_series) {
    fromFace(first_c, first_s);
  } else {
    T sc, ss, fc, fs;
    fromSeries(sc, ss);
    fromFace(fc, fs);
    const auto lane = tan_half <= splat<T>(kFirstJointSeriesLimit);
    first_c = lane ? sc : fc;
    first_s = lane ? ss : fs;
  }
  return firstJointAngle(base_wall_share, theta);
}

/// Stage 6 for identical chambers (docs/MODEL.md): the backbone's points 2..N+1 (point 0 is the mount, point 1 the end
/// of the base segment, (Z_0, 0)). Segment n points along q_1 + 2 (n - 1) theta, that is e^(i q_1) r^(n-1) with
/// r = e^(2 i theta), so point n + 1 is (Z_0, 0) + e^(i q_1) S_n with S_n = sum_(j < n) Z_(j+1) r^j: the backbone in
/// segment 1's frame, turned once. S needs only cos and sin of theta, which the solve has before theta itself (they
/// come from w, theta from the arctangent of t), so its complex products run beside the arctangent and joint 1's
/// direction, and one rotation per point is all that waits for those. The powers of r: r, r^2, r^3 = r r^2, and every
/// later one from the one four before it and r^4, a chain 2 + (N - 4)/4 products long instead of N - 1. Shared by the
/// single evaluation and the batch kernel, so that both round alike.
/// @tparam kChambers the chamber count when known at compile time (the loops then unroll into straight code), else 0
/// @param first_c, first_s e^(i q_1), from firstJoint (or the table's polynomials)
/// @param cos_half, sin_half cos and sin of theta
/// @param power_c, power_s scratch for N powers of r
/// @param[out] x, y the points' coordinates, point 2 + j at x[j * stride], y[j * stride] (no element reached through
/// both, nor through the scratch: hence __restrict)
template <int kChambers, class T>
inline void uniformPoints(T first_c, T first_s, T cos_half, T sin_half, int chamber_count,
                          double base_segment_length_m, const double* __restrict segment_length_m,
                          T* __restrict power_c, T* __restrict power_s, T* __restrict x, T* __restrict y, int stride) {
  const int n = kChambers > 0 ? kChambers : chamber_count;
  // r = e^(2 i theta): cos 2 theta as a product, which does not cancel near pi/4.
  const T r1_c = (cos_half - sin_half) * (cos_half + sin_half);
  const T r1_s = splat<T>(2.0) * sin_half * cos_half;
  const T r2_c = (r1_c - r1_s) * (r1_c + r1_s);
  const T r2_s = splat<T>(2.0) * r1_s * r1_c;
  const T r4_c = (r2_c - r2_s) * (r2_c + r2_s);
  const T r4_s = splat<T>(2.0) * r2_s * r2_c;
  const T head_c[4] = {splat<T>(1.0), r1_c, r2_c, r1_c * r2_c - r1_s * r2_s};
  const T head_s[4] = {splat<T>(0.0), r1_s, r2_s, r1_s * r2_c + r1_c * r2_s};
#pragma GCC unroll 4
  for (int j = 0; j < (n < 4 ? n : 4); ++j) {
    power_c[j] = head_c[j];
    power_s[j] = head_s[j];
  }
#pragma GCC unroll 64
  for (int j = 4; j < n; ++j) {
    power_c[j] = power_c[j - 4] * r4_c - power_s[j - 4] * r4_s;
    power_s[j] = power_s[j - 4] * r4_c + power_c[j - 4] * r4_s;
  }
  const T x0 = splat<T>(base_segment_length_m);
  T sx = splat<T>(0.0), sy = splat<T>(0.0);
#pragma GCC unroll 64
  for (int j = 0; j < n; ++j) {
    sx += segment_length_m[j] * power_c[j];
    sy += segment_length_m[j] * power_s[j];
    x[j * stride] = x0 + (first_c * sx - first_s * sy);
    y[j * stride] = first_s * sx + first_c * sy;
  }
}

}  // namespace
}  // namespace pneumatic_finger
