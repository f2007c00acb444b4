// Orthonormal frame (s, t, n) for moving directions between world space and a local shading frame (z = n).
#pragma once

#include "core/math.h"

namespace lumis {

struct Frame {
  Vec3 s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};

  Frame() = default;
  Frame(Vec3 s_, Vec3 t_, Vec3 n_) : s(s_), t(t_), n(n_) {}

  /// Frame around unit normal n (branchless construction of Duff et al. 2017).
  static Frame from_normal(Vec3 n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {{1 + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
  }
  /// Frame around unit normal n whose s axis follows tangent (Gram-Schmidt); falls back to from_normal.
  static Frame from_normal_tangent(Vec3 n, Vec3 tangent) {
    Vec3 s = tangent - n * dot(n, tangent);
    const float l2 = length_squared(s);
    if (!(l2 > 1e-12f)) return from_normal(n);
    s = s / std::sqrt(l2);
    return {s, cross(n, s), n};
  }

  /// World direction -> local (z along n).
  Vec3 to_local(Vec3 v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  /// Local direction -> world.
  Vec3 to_world(Vec3 v) const { return s * v.x + t * v.y + n * v.z; }
};

/// Spherical-coordinate helpers in a local frame (z = normal).
inline float cos_theta(Vec3 w) { return w.z; }
inline float abs_cos_theta(Vec3 w) { return std::abs(w.z); }
inline bool same_hemisphere(Vec3 a, Vec3 b) { return a.z * b.z > 0; }

}  // namespace lumis
