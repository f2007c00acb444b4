// Hemisphere, sphere, cap, disk and triangle warps with their densities and inverses. The direction warps all use the
// lecture's azimuth phi = 2 pi u.x - pi (so u.x = 1/2 is the +x axis) and differ only in how u.y sets theta.
// GGX lives in core/microfacet.cpp, spherical polygons in core/spherical_polygons.cpp.
#include "core/warp.h"

#include <cmath>

namespace lumis {

namespace {

// Lecture: phi = 2 pi u.x - pi, omega = (cos(phi) sin(theta), sin(phi) sin(theta), cos(theta)).
Vec3 from_phi_u(float u_x, float sin_theta, float cos_theta) {
  const float phi = 2.0f * kPi * u_x - kPi;
  return {std::cos(phi) * sin_theta, std::sin(phi) * sin_theta, cos_theta};
}

// Inverse of phi = 2 pi u.x - pi; atan2 is in [-pi, pi], and u.x = 1 is folded back to 0 (the same direction).
float u_from_phi(Vec3 w) {
  const float u = (std::atan2(w.y, w.x) + kPi) * kInv2Pi;
  return u >= 1.0f ? 0.0f : clamp(u, 0.0f, kOneMinusEpsilon);
}

// sin(theta) from the x, y components: accurate near the pole, where sqrt(1 - z^2) would cancel.
float sin_theta_of(Vec3 w) { return std::sqrt(w.x * w.x + w.y * w.y); }

float clamp01(float v) { return clamp(v, 0.0f, kOneMinusEpsilon); }

}  // namespace

// ---- Uniform in (theta, phi): the lecture's naive baseline ----

Vec3 sample_uniform_theta_phi_hemisphere(Vec2 u) {
  // Lecture: p(theta) = 2 / pi, i.e. theta = (pi / 2) u.y; the solid-angle density is 1 / (pi^2 sin(theta)).
  const float theta = kPiOver2 * u.y;
  return from_phi_u(u.x, std::sin(theta), std::cos(theta));
}

float uniform_theta_phi_hemisphere_pdf(Vec3 w) {
  if (w.z <= 0) return 0.0f;
  // Infinite exactly at the pole: the map squeezes a whole row of u onto one direction.
  const float s = sin_theta_of(w);
  return s > 0 ? 1.0f / (kPi * kPi * s) : INFINITY;
}

Vec2 invert_uniform_theta_phi_hemisphere(Vec3 w) {
  return {u_from_phi(w), clamp01(std::atan2(sin_theta_of(w), w.z) / kPiOver2)};
}

// ---- Uniform hemisphere: the lecture's cap with z_min = 0 ----

Vec3 sample_uniform_hemisphere(Vec2 u) {
  // Lecture (spherical cap, z_min = 0): omega_z = 1 - u.y; sin(theta) = sqrt(1 - z^2) = sqrt(u.y (2 - u.y)).
  const float z = 1.0f - u.y;
  return from_phi_u(u.x, std::sqrt(u.y * (2.0f - u.y)), z);
}

float uniform_hemisphere_pdf(Vec3 w) { return w.z > 0 ? kInv2Pi : 0.0f; }

Vec2 invert_uniform_hemisphere(Vec3 w) { return {u_from_phi(w), clamp01(1.0f - w.z)}; }

// ---- Cosine-weighted hemisphere (projected solid angle) ----

Vec3 sample_cosine_hemisphere(Vec2 u) { return sample_cosine_hemisphere(u, turn_azimuth(u.x)); }

Vec3 sample_cosine_hemisphere(Vec2 u, Vec2 azimuth) {
  // Lecture: p(theta) = 2 cos(theta) sin(theta), CDF 1 - cos^2(theta), so sin(theta) = sqrt(u.y) and
  // cos(theta) = sqrt(1 - u.y); omega = (cos(2 pi u.x - pi) sqrt(u.y), sin(2 pi u.x - pi) sqrt(u.y), sqrt(1 - u.y)),
  // where cos(2 pi u.x - pi) = -cos(2 pi u.x) and likewise for sin: the given azimuth, negated.
  const float sin_theta = std::sqrt(u.y);
  return {-azimuth.x * sin_theta, -azimuth.y * sin_theta, std::sqrt(1.0f - u.y)};
}

float cosine_hemisphere_pdf(Vec3 w) { return w.z > 0 ? w.z * kInvPi : 0.0f; }

Vec2 invert_cosine_hemisphere(Vec3 w) {
  // u.y = sin^2(theta), taken from x and y so that directions near the normal keep their precision.
  return {u_from_phi(w), clamp01(w.x * w.x + w.y * w.y)};
}

// ---- Uniform sphere: the lecture's cap with z_min = -1 ----

Vec3 sample_uniform_sphere(Vec2 u) {
  const float z = 1.0f - 2.0f * u.y;
  // 1 - z^2 = 4 u.y (1 - u.y), without the cancellation near the poles.
  return from_phi_u(u.x, 2.0f * std::sqrt(u.y * (1.0f - u.y)), z);
}

float uniform_sphere_pdf() { return kInv4Pi; }

Vec2 invert_uniform_sphere(Vec3 w) { return {u_from_phi(w), clamp01(0.5f * (1.0f - w.z))}; }

// ---- Spherical cap around +z ----

Vec3 sample_spherical_cap(Vec2 u, float cos_max) {
  // Lecture: p(theta) = w sin(theta) on [0, alpha), CDF w (1 - cos(theta)), so
  // omega_z = 1 - (1 - z_min) u.y and sin(theta) = sqrt(1 - omega_z^2). With d = 1 - z, 1 - z^2 = d (2 - d), which
  // stays accurate for the tiny caps of distant lights.
  const float d = (1.0f - cos_max) * u.y;
  return from_phi_u(u.x, std::sqrt(std::max(d * (2.0f - d), 0.0f)), 1.0f - d);
}

float spherical_cap_pdf(Vec3 w, float cos_max) {
  // Lecture: 2 pi (1 - z_min) is the solid angle of the cap.
  return w.z >= cos_max ? 1.0f / (2.0f * kPi * (1.0f - cos_max)) : 0.0f;
}

Vec2 invert_spherical_cap(Vec3 w, float cos_max) {
  // 1 - z from x and y (sin^2 / (1 + cos)) keeps small caps invertible.
  const float s2 = w.x * w.x + w.y * w.y;
  const float one_minus_z = w.z > 0 ? s2 / (1.0f + w.z) : 1.0f - w.z;
  return {u_from_phi(w), clamp01(one_minus_z / (1.0f - cos_max))};
}

// ---- Disk and triangle ----

Vec2 sample_uniform_disk(Vec2 u) {
  // Shirley & Chiu 1997: concentric squares to concentric circles, so strata stay compact and area is preserved.
  const float ox = 2.0f * u.x - 1.0f, oy = 2.0f * u.y - 1.0f;
  if (ox == 0 && oy == 0) return {0, 0};
  float r, theta;
  if (std::abs(ox) > std::abs(oy)) {
    r = ox;
    theta = 0.25f * kPi * (oy / ox);
  } else {
    r = oy;
    theta = kPiOver2 - 0.25f * kPi * (ox / oy);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

float uniform_disk_pdf(Vec2 p) { return p.x * p.x + p.y * p.y <= 1.0f ? kInvPi : 0.0f; }

Vec2 invert_uniform_disk(Vec2 p) {
  const float r = std::sqrt(p.x * p.x + p.y * p.y);
  if (r == 0) return {0.5f, 0.5f};
  const float phi = std::atan2(p.y, p.x), k = 4.0f / kPi;
  float ox, oy;
  if (std::abs(phi) <= 0.25f * kPi) {  // right wedge: r = ox > 0, phi = (pi/4) oy/ox
    ox = r;
    oy = ox * phi * k;
  } else if (std::abs(phi) >= 0.75f * kPi) {  // left wedge: r = ox < 0, phi - pi = (pi/4) oy/ox
    ox = -r;
    oy = ox * (phi > 0 ? phi - kPi : phi + kPi) * k;
  } else if (phi > 0) {  // top wedge: r = oy > 0, phi = pi/2 - (pi/4) ox/oy
    oy = r;
    ox = oy * (kPiOver2 - phi) * k;
  } else {  // bottom wedge: r = oy < 0, phi + pi = pi/2 - (pi/4) ox/oy
    oy = -r;
    ox = oy * (kPiOver2 - (phi + kPi)) * k;
  }
  return {clamp01(0.5f * (ox + 1.0f)), clamp01(0.5f * (oy + 1.0f))};
}

Vec2 sample_uniform_triangle(Vec2 u) {
  // Square-root parameterisation: the first barycentric's marginal is 2 (1 - b0), inverted as b0 = 1 - sqrt(u.x);
  // b1 is then uniform on the remaining segment.
  const float su = std::sqrt(u.x);
  return {1.0f - su, u.y * su};
}

Vec2 invert_uniform_triangle(Vec2 b) {
  const float su = 1.0f - b.x;
  return {clamp01(su * su), su > 0 ? clamp01(b.y / su) : 0.0f};
}

}  // namespace lumis
