// The lecture's spherical-cap sampling of a sphere light seen from outside, in two steps, so that SphereLight::sample
// (one receiver) and the batch kernel (lights/sphere_light_batch.cpp, many receivers side by side) run the same
// arithmetic in the same order and give the same numbers bit for bit. The batch kernel's header is here too.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/frame.h"
#include "lights/light.h"

namespace lumis::sphere_cap {

/// The direction in the frame around the centre's direction: the cap's 1 - cos(theta_max), the sample's polar angle
/// (z = cos, sin) and azimuth phi = 2 pi u.x - pi, from the squared radius r2, the squared distance d2 > r2 to the
/// centre and u.
struct Setup {
  float d, inv_d;              ///< distance to the centre and its reciprocal
  float one_minus_cos_max;     ///< of the cap the sphere subtends; the density is 1 / (2 pi one_minus_cos_max)
  float z, sin_theta;          ///< polar angle
  float cos_phi, sin_phi;      ///< azimuth
};
inline Setup setup(float r2, float d2, Vec2 u) {
  Setup s;
  s.d = std::sqrt(d2);
  s.inv_d = 1 / s.d;
  s.one_minus_cos_max = sphere_cap_one_minus_cos(r2, d2);
  // Written with 1 - cos(theta) so that tiny caps keep their precision.
  const float one_minus_z = s.one_minus_cos_max * u.y;
  s.z = 1 - one_minus_z;
  s.sin_theta = safe_sqrt(one_minus_z * (2 - one_minus_z));
  sincos_turns(u.x - 0.5f, s.sin_phi, s.cos_phi);  // phi in turns: no library call, so the batch vectorises
  return s;
}

/// Then the world direction, the distance to its nearest intersection with the sphere (centre c, radius r,
/// inv_r = 1 / r), the point there and the outward normal, from the receiver p and to_c = c - p (d2 = |to_c|^2).
struct Point {
  Vec3 wi;
  float t;
  Vec3 p, n;
};
inline Point finish(Vec3 c, float r, float inv_r, Vec3 p, Vec3 to_c, float d2, const Setup& s) {
  // Unit up to rounding: z^2 + sin_theta^2 = 1 and the frame is orthonormal.
  const Frame frame = Frame::from_normal(to_c * s.inv_d);
  const Vec3 wi = frame.to_world({s.cos_phi * s.sin_theta, s.sin_phi * s.sin_theta, s.z});
  // The discriminant is >= 0 up to rounding inside the cap.
  const float t = std::max(0.0f, s.d * s.z - safe_sqrt(r * r - d2 * s.sin_theta * s.sin_theta));
  const Vec3 p_light = p + wi * t;
  return {wi, t, p_light, (p_light - c) * inv_r};  // p_light is on the sphere: unit up to rounding, no square root
}

/// Cap samples of one sphere for up to kChunk receivers, by column. Receivers inside the sphere (d2 <= r^2) get
/// meaningless numbers: SphereLight samples those by area itself.
struct Batch {
  static constexpr int kChunk = 64;
  Vec3 c;
  float r = 0, inv_r = 0;
  float px[kChunk], py[kChunk], pz[kChunk], ux[kChunk], uy[kChunk];  // in: receivers, 2D samples
  float wx[kChunk], wy[kChunk], wz[kChunk], t[kChunk];               // out: direction, distance
  float lx[kChunk], ly[kChunk], lz[kChunk];                          //      point on the sphere
  float nx[kChunk], ny[kChunk], nz[kChunk];                          //      its normal
  float one_minus_cos_max[kChunk];                                   //      the cap (density)
  int emits[kChunk];                                                 //      the point faces the receiver
};

/// Fill the outputs of b's first n lanes with the kernel at `level` (simd_level() or below; tests try each).
void run(Batch& b, int n, int level);

}  // namespace lumis::sphere_cap
