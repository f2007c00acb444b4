// Test-only ray casts against light shapes, so that a test can evaluate a light's pdf() for an arbitrary direction
// by building the Hit a BSDF ray would have made (the lights themselves never intersect rays).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "core/geometry.h"
#include "core/math.h"
#include "core/rng.h"
#include "lights/light.h"

namespace lumis::test {

/// Monte Carlo estimate of the solid angle (steradians) over which `light` samples from ctx: the mean of 1/pdf over
/// n samples (an empty sample counts 0), with its standard error.
struct SolidAngleEstimate {
  double mean, se;
};
inline SolidAngleEstimate mc_solid_angle(const Light& light, const LightSampleContext& ctx, Pcg32 rng,
                                         int n = 100'000) {
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const auto s = light.sample(ctx, {rng.next_float(), rng.next_float()});
    const double inv = s ? 1.0 / s->pdf : 0.0;
    sum += inv;
    sum2 += inv * inv;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

/// Every crossing (t > 0) of the ray o + t d (d unit) with the sphere, nearest first, as Hits with outward ng.
inline std::vector<Hit> sphere_hits(Vec3 o, Vec3 d, Vec3 c, float r) {
  const double ox = double(o.x) - c.x, oy = double(o.y) - c.y, oz = double(o.z) - c.z;
  const double b = ox * d.x + oy * d.y + oz * d.z;
  const double cc = ox * ox + oy * oy + oz * oz - double(r) * r;
  const double disc = b * b - cc;
  std::vector<Hit> hits;
  if (disc < 0) return hits;
  const double sq = std::sqrt(disc);
  for (double t : {-b - sq, -b + sq}) {
    if (!(t > 0)) continue;
    Hit h;
    h.t = static_cast<float>(t);
    h.p = o + d * h.t;
    h.ng = h.ns = normalize(h.p - c);
    h.front = dot(d, h.ng) < 0;
    h.prim_id = 0;
    hits.push_back(h);
  }
  return hits;
}

/// Two-sided ray-triangle crossing (Moller-Trumbore in double); ng follows the counter-clockwise winding.
inline std::optional<Hit> triangle_hit(Vec3 o, Vec3 d, Vec3 a, Vec3 b, Vec3 c, uint32_t prim_id) {
  const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
  const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
  const double dd[3] = {d.x, d.y, d.z};
  const double pv[3] = {dd[1] * e2[2] - dd[2] * e2[1], dd[2] * e2[0] - dd[0] * e2[2], dd[0] * e2[1] - dd[1] * e2[0]};
  const double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
  if (det == 0) return std::nullopt;
  const double tv[3] = {double(o.x) - a.x, double(o.y) - a.y, double(o.z) - a.z};
  const double u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
  if (u < 0 || u > 1) return std::nullopt;
  const double qv[3] = {tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2], tv[0] * e1[1] - tv[1] * e1[0]};
  const double v = (dd[0] * qv[0] + dd[1] * qv[1] + dd[2] * qv[2]) / det;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double t = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
  if (!(t > 0)) return std::nullopt;
  Hit h;
  h.t = static_cast<float>(t);
  h.p = o + d * h.t;
  h.ng = h.ns = normalize(cross(b - a, c - a));
  h.front = dot(d, h.ng) < 0;
  h.prim_id = prim_id;
  return h;
}

/// Every crossing of the ray with the mesh's triangles (any order).
inline std::vector<Hit> mesh_hits(Vec3 o, Vec3 d, const TriangleMesh& mesh) {
  std::vector<Hit> hits;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
               c = mesh.positions[mesh.indices[3 * t + 2]];
    if (auto h = triangle_hit(o, d, a, b, c, static_cast<uint32_t>(t))) hits.push_back(*h);
  }
  return hits;
}

/// The two-triangle mesh the scene builds for a quad light: (o, o+u, o+u+v, o+v), triangles (0,1,2), (0,2,3).
inline TriangleMesh quad_mesh(Vec3 o, Vec3 u, Vec3 v) {
  TriangleMesh m;
  m.positions = {o, o + u, o + u + v, o + v};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

}  // namespace lumis::test
