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
/// centre and u; and the angle beta at the sphere's point between -wi and its normal (law of sines:
/// sin(beta) = d sin(theta) / r), from u and the cap alone, so that tiny spheres keep their normals.
struct Setup {
  float d, inv_d;              ///< distance to the centre and its reciprocal
  float one_minus_cos_max;     ///< of the cap the sphere subtends; the density is 1 / (2 pi one_minus_cos_max)
  float z, sin_theta;          ///< polar angle
  float cos_phi, sin_phi;      ///< azimuth
  float cos_beta, sin_beta;    ///< cos(beta) = n . -wi >= 0: every cap sample's point faces the receiver
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
  // sin^2(beta) = sin^2(theta) / sin^2(theta_max) = u.y (2 - one_minus_z) / (2 - one_minus_cos_max), and
  // cos^2(beta) = (1 - u.y) (2 - one_minus_cos_max - one_minus_z) / (2 - one_minus_cos_max): no cancellation, where
  // r^2 - d^2 sin^2(theta) lost all its digits for a sphere far smaller than its distance.
  const float inv_den = 1 / (2 - s.one_minus_cos_max);
  s.sin_beta = std::sqrt(std::min(u.y * (2 - one_minus_z) * inv_den, 1.0f));
  s.cos_beta = std::sqrt(std::min((1 - u.y) * (2 - s.one_minus_cos_max - one_minus_z) * inv_den, 1.0f));
  sincos_turns(u.x - 0.5f, s.sin_phi, s.cos_phi);  // phi in turns: no library call, so the batch vectorises
  return s;
}

/// Then the world direction, the distance to its nearest intersection with the sphere (centre c, radius r), the
/// point there and the outward normal, from the receiver p and to_c = c - p.
struct Point {
  Vec3 wi;
  float t;
  Vec3 p, n;
};
inline Point finish(Vec3 p, Vec3 to_c, float r, const Setup& s) {
  // Unit up to rounding: z^2 + sin_theta^2 = 1 and the frame is orthonormal.
  const Frame frame = Frame::from_normal(to_c * s.inv_d);
  const Vec3 wi = frame.to_world({s.cos_phi * s.sin_theta, s.sin_phi * s.sin_theta, s.z});
  // Along wi: d cos(theta) = t + r cos(beta).
  const float t = std::max(0.0f, s.d * s.z - r * s.cos_beta);
  // The normal turns from -z by the angle at the centre, alpha = beta - theta, toward the sample's azimuth (pbrt-v4
  // computes it so too): (p + t wi - c) / r lost all its digits for a sphere far smaller than its distance, and the
  // shadow rays' ends, offset along normals of any length and direction, went astray (tiny lights were dark).
  const float sin_alpha = s.sin_beta * s.z - s.cos_beta * s.sin_theta;
  const float cos_alpha = s.cos_beta * s.z + s.sin_beta * s.sin_theta;
  const Vec3 n = frame.to_world({s.cos_phi * sin_alpha, s.sin_phi * sin_alpha, -cos_alpha});
  return {wi, t, p + wi * t, n};
}

/// Cap samples of one sphere for up to kChunk receivers, by column. Receivers inside the sphere (d2 <= r^2) get
/// meaningless numbers: SphereLight samples those by area itself.
struct Batch {
  static constexpr int kChunk = 64;
  Vec3 c;
  float r = 0;
  float px[kChunk], py[kChunk], pz[kChunk], ux[kChunk], uy[kChunk];  // in: receivers, 2D samples
  float wx[kChunk], wy[kChunk], wz[kChunk], t[kChunk];               // out: direction, distance
  float lx[kChunk], ly[kChunk], lz[kChunk];                          //      point on the sphere
  float nx[kChunk], ny[kChunk], nz[kChunk];                          //      its normal
  float one_minus_cos_max[kChunk];                                   //      the cap (density)
};

/// Fill the outputs of b's first n lanes with the kernel at `level` (simd_level() or below; tests try each).
void run(Batch& b, int n, int level);

}  // namespace lumis::sphere_cap
