// Rays, the surface record (Hit) that materials, lights and integrators consume, and rays that leave a surface
// without hitting it again: origins offset by the hit point's floating-point error bound (pbrt-v4's scheme).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "core/math.h"

namespace lumis {

/// Members laid out in 16-byte slots (o, tmin | d, tmax): a copy moves them 16 bytes at a time, and a Vec3 that
/// straddled two such moves would be read back through a failed store forward (docs/performance.md).
struct Ray {
  Ray() = default;
  Ray(Vec3 o_, Vec3 d_, float tmin_ = 0, float tmax_ = INFINITY) : o(o_), tmin(tmin_), d(d_), tmax(tmax_) {}
  Vec3 o;               ///< origin
  float tmin = 0;
  Vec3 d;               ///< direction (need not be unit; t is in units of |d|)
  float tmax = INFINITY;
};

/// What Embree accepts: origin and direction components no larger than its FLT_LARGE (1.844e18: Embree 3's
/// RayK::valid(), asserted in Debian's build, which aborted on a shadow ray toward a 1e-18 sphere light), 0 <= tmin
/// finite, tmax >= 0 and not NaN. Queries of other rays answer "no hit" (occluded() says occluded) without Embree.
inline bool ray_is_valid(const Ray& r) {
  constexpr float kLarge = 1.844e18f;
  const auto small = [](Vec3 v) {
    return std::fabs(v.x) <= kLarge && std::fabs(v.y) <= kLarge && std::fabs(v.z) <= kLarge;  // false for NaN
  };
  return small(r.o) && small(r.d) && std::isfinite(r.tmin) && r.tmin >= 0 && !std::isnan(r.tmax) && r.tmax >= 0;
}

/// What a ray hit. Normals are unit and world-space.
struct Hit {
  float t = INFINITY;
  Vec3 p;              ///< hit point
  Vec3 p_error;        ///< conservative absolute floating-point error bound of p, per axis
  Vec3 ng;             ///< geometric normal of the front face (not flipped toward the ray)
  Vec3 ns;             ///< interpolated shading normal (== ng when the mesh has none), front-face side
  Vec4 tangent;        ///< interpolated tangent (w = handedness), zero when absent
  Vec2 uv[2];          ///< TEXCOORD_0/1 (zero when absent)
  Vec4 color{1, 1, 1, 1};  ///< vertex colour
  bool front = true;   ///< the ray arrived on the front side (dot(d, ng) < 0)
  uint32_t geom_id = ~0u, prim_id = ~0u;
  int material = -1, light = -1;
};

/// The next float toward +infinity (std::nextafter without the library call); +infinity stays.
inline float next_float_up(float v) {
  if (std::isinf(v) && v > 0) return v;
  if (v == 0) return std::bit_cast<float>(1u);  // +0 and -0: the smallest positive denormal
  const uint32_t bits = std::bit_cast<uint32_t>(v);
  return std::bit_cast<float>(v > 0 ? bits + 1 : bits - 1);
}
/// The next float toward -infinity; -infinity stays.
inline float next_float_down(float v) { return -next_float_up(-v); }

/// v moved one float up when dir > 0, down when dir < 0, kept otherwise: next_float_up / next_float_down for every
/// non-NaN v (+0 and -0 alike), as selects instead of branches (the signs of a bounce's offsets are unpredictable).
inline float next_float_toward(float v, float dir) {
  const uint32_t bits = std::bit_cast<uint32_t>(v), magnitude = bits & 0x7fffffffu;
  const bool up = dir > 0, negative = bits >> 31;
  const uint32_t grown = magnitude == 0x7f800000u ? bits : bits + 1;  // away from zero; an infinity stays
  const uint32_t moved = magnitude == 0 ? (up ? 1u : 0x80000001u) : up != negative ? grown : bits - 1;
  return std::bit_cast<float>(dir > 0 || dir < 0 ? moved : bits);
}

/// Error bound of a computed point per unit of the largest coordinate involved in computing it: 8 units in the last
/// place, twice the smallest that kept every ray from the surface it left in Geometry.SpawnedRaysNeverMeetTheirSurface-
/// Again (4 passed 5.6 million rays at scales 1e-12 to 1e11; 2 let 14 of 557,021 through), about pbrt-v4's gamma_7.
/// It was 64 until stop 59: 0.38 units at 1e5 from the origin, where `mis` then rendered 38 % too bright.
inline constexpr float kErrorScale = 8 * 0x1p-24f;

/// Offset a point with error bound p_error off a surface along its geometric normal, to the side of direction w,
/// by the projected error bound (pbrt-v4's scheme): relative to the coordinates, so it works at any scene scale.
/// World space. Always inline (the three below are inline): called per ray (left out of line by GCC once shadow rays
/// offset both ends, it took 5 % of a render), and a returned Ray read back from memory stalls.
[[gnu::always_inline]] inline Vec3 offset_ray_origin(Vec3 p, Vec3 p_error, Vec3 ng, Vec3 w) {
  const float d = dot(abs(ng), p_error);
  Vec3 offset = ng * d;
  if (dot(w, ng) < 0) offset = -offset;
  const Vec3 po = p + offset;
  // Rounded away from p so that the offset is never lost to rounding.
  return {next_float_toward(po.x, offset.x), next_float_toward(po.y, offset.y), next_float_toward(po.z, offset.z)};
}
/// Ray from surface point `from` toward unit world direction w.
inline Ray spawn_ray(const Hit& from, Vec3 w) {
  return {offset_ray_origin(from.p, from.p_error, from.ng, w), w, 0, INFINITY};
}
/// spawn_ray_to from an origin already offset off its surface (offset_ray_origin's result toward the target). The
/// segment o -> target stops where it is the target's projected error bound (off) short of the target's surface: it
/// keeps its direction, so it stands for part of the true segment. Only when that would take half of it or more (a
/// segment nearly parallel to the surface, or an origin within a few bounds of it) does it end instead at the target
/// moved off the surface along its normal, toward o, by off (pbrt-v4's SpawnRayTo). That move used to be made for
/// every ray: it turns the segment, and far from the origin, where off is large, the turned segments met surfaces
/// the true ones miss (a ceiling above a light's outline) or missed ones they meet (the edge of a plate under it).
inline Ray shadow_ray(Vec3 o, Vec3 target, Vec3 target_n, float target_error) {
  const Vec3 d = target - o;
  const float along = std::abs(dot(d, target_n)), off = dot(abs(target_n), Vec3(target_error));
  // No rounding guard needed: every light's bound holds kErrorScale x dist, so off / along >= kErrorScale (8 ulps of
  // 1), and rounding 1 - off / along gives back at most a sixteenth of it.
  if (2 * off < along) [[likely]] return {o, d, 0, 1 - off / along};
  const Vec3 t = offset_ray_origin(target, Vec3(target_error), target_n, o - target);
  return {o, t - o, 0, 1};
}
/// Shadow ray from surface point `from` to a world point on a light with surface normal target_n and error bound
/// target_error (per axis): both ends stop off their surfaces by their error bounds (shadow_ray). Without the
/// target's margin, a light point rounded into its own surface (far from the origin, where floats are coarse) was
/// shadowed by the light itself; with it, no further margin is needed: the segment used to stop 1e-4 of its length
/// short (pbrt-v4's ShadowEpsilon), which hid an occluder that close to a light (a ceiling 1e-4 below a light 2
/// units away).
inline Ray spawn_ray_to(const Hit& from, Vec3 target, Vec3 target_n, float target_error) {
  return shadow_ray(offset_ray_origin(from.p, from.p_error, from.ng, target - from.p), target, target_n, target_error);
}

}  // namespace lumis
