// Shading frames and the shading-normal rule (stated in materials/shading.h and docs/materials.md).
#include "materials/shading.h"

#include <cmath>

namespace lumis {

namespace {

/// Unit n, or `fallback` when n has no usable length.
Vec3 unit_or(Vec3 n, Vec3 fallback) {
  const float l2 = length_squared(n);
  if (!(l2 > 1e-20f) || !std::isfinite(l2)) return fallback;
  return n / std::sqrt(l2);
}

/// Whether normal n gives wo a valid mirror configuration: wo above n, reflection above the geometric surface.
bool reflection_valid(Vec3 n, Vec3 ng, Vec3 wo, float threshold) {
  return dot(wo, n) > 0 && dot(reflect(wo, n), ng) >= threshold;
}

}  // namespace

Vec4 sample_texture(const Texture& texture, const Hit& hit) {
  return texture.sample(hit.uv[std::clamp(texture.tex_coord, 0, 1)]);
}

/// World frame around hit.ns; its s axis follows the mesh tangent when there is one, so normal maps line up.
Frame base_shading_frame(const Hit& hit) {
  const float l2 = length_squared(hit.ns);  // the fallback is normalised only when needed
  // Geometry gives unit normals: used as they are (normalize_unless_unit), without a square root and a division on
  // every vertex's critical path. Anything else is normalised, or replaced when it has no length.
  Vec3 n = l2 > 1e-20f && std::isfinite(l2) ? normalize_unless_unit(hit.ns) : unit_or(hit.ng, {0, 0, 1});
  // Rule 1: on the front face's side. Vertex normals that disagree with the winding (which defines the front face
  // in glTF) are turned over; left as they were, rule 3 bent them through ng into a view-dependent tilt.
  if (dot(n, hit.ng) < 0) n = -n;
  const Vec3 tangent{hit.tangent.x, hit.tangent.y, hit.tangent.z};
  if (length_squared(tangent) > 0) return Frame::from_normal_tangent(n, tangent);
  return Frame::from_normal(n);
}

/// World frame around the normal-mapped normal (tangent-space texel decoded as glTF's normalTexture says).
Frame normal_mapped_frame(const Hit& hit, const Texture& normal_map, float scale) {
  const Frame base = base_shading_frame(hit);
  const Vec4 c = sample_texture(normal_map, hit);
  const Vec3 v{(2 * c.x - 1) * scale, (2 * c.y - 1) * scale, 2 * c.z - 1};
  // glTF: bitangent = cross(normal, tangent) * handedness; Frame::from_normal_tangent already gives t = n x s.
  const float handedness = hit.tangent.w < 0 ? -1.0f : 1.0f;
  const Vec3 n_world = base.s * v.x + base.t * (handedness * v.y) + base.n * v.z;
  const Vec3 ng = unit_or(hit.ng, base.n);
  const Vec3 n = bend_toward(unit_or(n_world, base.n), ng, kMinShadingCosine);
  return Frame::from_normal_tangent(n, base.s);
}

/// Closest unit vector to n on the great circle through n and ng with dot(., ng) >= min_cos.
Vec3 bend_toward(Vec3 n, Vec3 ng, float min_cos) {
  const float c = dot(n, ng);
  if (c >= min_cos) return n;
  Vec3 perp = n - ng * c;
  const float l2 = length_squared(perp);
  perp = l2 > 1e-20f ? perp / std::sqrt(l2) : Frame::from_normal(ng).s;  // n == -ng: any direction will do
  return ng * min_cos + perp * std::sqrt(std::max(0.0f, 1 - min_cos * min_cos));
}

/// Bisects along the arc from frame.n to ng for the least bend that makes the mirror configuration valid.
Frame adapt_shading_frame(const Frame& frame, Vec3 ng, Vec3 wo) {
  const float cos_og = dot(wo, ng);
  if (!(cos_og > 0)) return frame;  // contract violated: nothing sensible to bend toward
  // The reflection must clear the geometric surface by a margin, but a grazing wo cannot do better than itself.
  const float threshold = std::min(0.9f * cos_og, 0.01f);
  if (reflection_valid(frame.n, ng, wo, threshold)) return frame;
  // n(t) = normalize(lerp(n, ng, t)) is valid at t = 1 (n = ng), so bisect for the smallest valid t.
  float lo = 0, hi = 1;
  for (int i = 0; i < 24; ++i) {
    const float mid = 0.5f * (lo + hi);
    if (reflection_valid(unit_or(lerp(mid, frame.n, ng), ng), ng, wo, threshold))
      hi = mid;
    else
      lo = mid;
  }
  const Vec3 n = unit_or(lerp(hi, frame.n, ng), ng);
  return Frame::from_normal_tangent(n, frame.s);
}

}  // namespace lumis
