// Helpers shared by the materials: texture lookups at a hit, the shading frame, normal mapping, and the
// shading-normal rule that keeps shading normals from leaking light or turning faces black.
//
// Shading-normal rule (see docs/materials.md):
//  1. Material::shade(hit) starts from hit.ns, turned to the front face's side (ng's) when the mesh's vertex
//     normals disagree with its winding. A normal map perturbs it in the tangent frame
//     (hit.tangent with w = handedness; without tangents, the arbitrary but deterministic Frame::from_normal(ns)).
//  2. View-independent clamp, inside shade(): the perturbed normal is bent toward the front geometric normal ng
//     along their great circle until dot(n, ng) >= kMinShadingCosine, so a normal map never points behind the
//     surface it decorates.
//  3. View-dependent clamp, for the integrator once it knows wo (adapt_shading_frame): when wo is below the shading
//     hemisphere, or its mirror reflection about n would go below the geometric surface, n is bent toward ng just
//     enough that the reflection stays above the geometric surface (the "normal map clamp" used by Cycles).
#pragma once

#include "core/frame.h"
#include "core/geometry.h"
#include "core/texture.h"

namespace lumis {

/// Smallest cosine allowed between a (normal-mapped) shading normal and the front geometric normal.
inline constexpr float kMinShadingCosine = 0.01f;

/// Texture lookup at the hit's TEXCOORD set named by the texture (RGBA).
Vec4 sample_texture(const Texture& texture, const Hit& hit);

/// World-space shading frame at the hit without normal map: n = hit.ns on ng's side, s follows hit.tangent if any.
Frame base_shading_frame(const Hit& hit);

/// Normal-mapped world frame: tangent-space normal (texel * 2 - 1, xy scaled by `scale`) expressed in the base
/// frame's (tangent, handedness-signed bitangent, ns) basis, then clamped by rule 2 above.
Frame normal_mapped_frame(const Hit& hit, const Texture& normal_map, float scale);

/// Bends unit n toward unit ng (same side) along their great circle until dot(n, ng) >= min_cos.
Vec3 bend_toward(Vec3 n, Vec3 ng, float min_cos);

/// Rule 3: world frame whose normal sees wo and reflects it above the geometric surface. ng is the geometric
/// normal on wo's side (dot(wo, ng) > 0) and frame.n is on the same side as ng; all vectors unit, world space.
Frame adapt_shading_frame(const Frame& frame, Vec3 ng, Vec3 wo);

}  // namespace lumis
