// Sampling warps: maps from uniform numbers in [0,1)^n to shapes and directions, each paired with its density
// (and its inverse where one exists). Directions are in a local frame with z as the pole unless stated.
// Formulas follow ../shared/reference/importance-sampling-lecture.txt where the lecture derives them.
#pragma once

#include <optional>

#include "core/math.h"

namespace lumis {

// ---- Hemispheres and spheres (local frame, z up) ----

/// Lecture's "uniform" baseline: theta = (pi/2) u.y, phi = 2 pi u.x - pi. Solid-angle density 1/(pi^2 sin theta).
Vec3 sample_uniform_theta_phi_hemisphere(Vec2 u);
/// Solid-angle density of sample_uniform_theta_phi_hemisphere: 1/(pi^2 sin theta) for z > 0, else 0.
float uniform_theta_phi_hemisphere_pdf(Vec3 w);
/// Inverse of sample_uniform_theta_phi_hemisphere.
Vec2 invert_uniform_theta_phi_hemisphere(Vec3 w);

/// Uniform by solid angle on the upper hemisphere. Solid-angle density 1/(2 pi).
Vec3 sample_uniform_hemisphere(Vec2 u);
/// Solid-angle density: 1/(2 pi) for z > 0, else 0.
float uniform_hemisphere_pdf(Vec3 w);
Vec2 invert_uniform_hemisphere(Vec3 w);

/// Lecture's projected-solid-angle sampling: (cos(2 pi u.x - pi) sqrt(u.y), sin(..) sqrt(u.y), sqrt(1 - u.y)).
Vec3 sample_cosine_hemisphere(Vec2 u);
/// The same with azimuth = turn_azimuth(u.x) = (cos, sin) of 2 pi u.x given (computed for many lanes at once).
Vec3 sample_cosine_hemisphere(Vec2 u, Vec2 azimuth);
/// Solid-angle density cos(theta)/pi for z > 0, else 0.
float cosine_hemisphere_pdf(Vec3 w);
Vec2 invert_cosine_hemisphere(Vec3 w);

/// Uniform on the unit sphere. Solid-angle density 1/(4 pi).
Vec3 sample_uniform_sphere(Vec2 u);
float uniform_sphere_pdf();
Vec2 invert_uniform_sphere(Vec3 w);

/// Lecture's spherical cap around +z: z = 1 - (1 - cos_max) u.y, phi = 2 pi u.x - pi.
Vec3 sample_spherical_cap(Vec2 u, float cos_max);
/// Solid-angle density 1/(2 pi (1 - cos_max)) inside the cap (z >= cos_max), else 0.
float spherical_cap_pdf(Vec3 w, float cos_max);
Vec2 invert_spherical_cap(Vec3 w, float cos_max);
/// 1 - cos(alpha) for sin^2(alpha) = sin2_max in [0, 1], stable for tiny caps: 1 - sqrt(1 - s^2) written as
/// s^2 / (1 + sqrt(1 - s^2)), no subtraction of nearly equal numbers. A cap of radius r seen from distance d has
/// sin2_max = r^2 / d^2 (no square root needed for it).
inline float one_minus_cos_from_sin2(float sin2_max) {
  return sin2_max / (1.0f + std::sqrt(std::max(1.0f - sin2_max, 0.0f)));
}
/// The same for sin(alpha) = sin_max.
inline float one_minus_cos_from_sin(float sin_max) { return one_minus_cos_from_sin2(sin_max * sin_max); }

// ---- Planar shapes ----

/// Uniform point on the unit disk (concentric map, Shirley-Chiu). Area density 1/pi.
Vec2 sample_uniform_disk(Vec2 u);
float uniform_disk_pdf(Vec2 p);
Vec2 invert_uniform_disk(Vec2 p);

/// Uniform point on a triangle, returned as barycentrics (b0, b1) with b2 = 1 - b0 - b1. Area density 1/area.
Vec2 sample_uniform_triangle(Vec2 u);
Vec2 invert_uniform_triangle(Vec2 b);

// ---- Solid-angle sampling of polygons as seen from a point ----

/// Solid angle of the triangle (a, b, c) seen from p (Van Oosterom & Strackee 1983).
float triangle_solid_angle(Vec3 p, Vec3 a, Vec3 b, Vec3 c);
/// Solid angle of the parallelogram origin + s ex + t ey (s, t in [0,1]) seen from p, its corners taken relative to
/// p in double (edges far below an ulp of the origin keep their size); area |cos| / d^2 for edges below 1e-3 of d.
float parallelogram_solid_angle(Vec3 p, Vec3 origin, Vec3 ex, Vec3 ey);
struct SphericalSample {
  Vec3 w;       ///< unit world direction from p
  float pdf;    ///< solid-angle density (1 / solid angle)
};
/// Arvo 1995: uniform direction inside the spherical triangle subtended by (a, b, c) from p. Fails (nullopt)
/// when the solid angle is too small or too large to sample stably; callers fall back to area sampling.
std::optional<SphericalSample> sample_spherical_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c, Vec2 u);
/// The density sample_spherical_triangle reports from p (solid angle), nullopt exactly when it fails; without
/// drawing a sample.
std::optional<float> spherical_triangle_pdf(Vec3 p, Vec3 a, Vec3 b, Vec3 c);
/// Inverse of sample_spherical_triangle for a direction w inside the triangle.
Vec2 invert_spherical_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c, Vec3 w);

/// Solid angle of the parallelogram-free rectangle origin + s ex + t ey (s, t in [0,1], ex orthogonal to ey)
/// seen from p, by the four-angle formula (sum of interior angles - 2 pi): rounding noise (of order 1e-6 sr) for
/// rectangles far smaller than their distance, which sample_spherical_rectangle therefore refuses.
float rectangle_solid_angle(Vec3 p, Vec3 origin, Vec3 ex, Vec3 ey);
/// Urena et al. 2013: uniform direction in the solid angle of rectangle (origin, ex, ey) seen from p.
/// Fails (nullopt) when the solid angle is below 1e-6 sr or above 2 pi - 1e-3 sr (too small or too close to a
/// hemisphere to sample stably), and for p in the rectangle's plane.
std::optional<SphericalSample> sample_spherical_rectangle(Vec3 p, Vec3 origin, Vec3 ex, Vec3 ey, Vec2 u);
/// The density sample_spherical_rectangle reports from p (solid angle), nullopt exactly when it fails.
std::optional<float> spherical_rectangle_pdf(Vec3 p, Vec3 origin, Vec3 ex, Vec3 ey);

// ---- GGX (Trowbridge-Reitz) microfacet distribution, local frame, anisotropic roughness (ax, ay) ----

/// Normal distribution D(wm), per unit solid angle of microfacet normals (projected-area normalised).
float ggx_d(Vec3 wm, float ax, float ay);
/// Smith Lambda for direction w.
float ggx_lambda(Vec3 w, float ax, float ay);
/// Smith masking G1(w) = 1 / (1 + Lambda(w)).
float ggx_g1(Vec3 w, float ax, float ay);
/// Height-correlated masking-shadowing G2(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi)).
float ggx_g2(Vec3 wo, Vec3 wi, float ax, float ay);
/// Density of visible normals D_wo(wm) = G1(wo) max(0, wo.wm) D(wm) / wo.z, per solid angle of wm.
float ggx_vndf_pdf(Vec3 wo, Vec3 wm, float ax, float ay);

enum class VndfMethod { Heitz2018, SphericalCap2023 };
/// Visible normal for wo (wo.z > 0) by Heitz 2018 ("Sampling the GGX Distribution of Visible Normals").
Vec3 sample_ggx_vndf_heitz(Vec3 wo, float ax, float ay, Vec2 u);
/// Visible normal for wo by Dupuy & Benyoub 2023 ("Sampling Visible GGX Normals with Spherical Caps").
Vec3 sample_ggx_vndf_spherical_cap(Vec3 wo, float ax, float ay, Vec2 u);
/// The same with azimuth = turn_azimuth(u.x) given.
Vec3 sample_ggx_vndf_spherical_cap(Vec3 wo, float ax, float ay, Vec2 u, Vec2 azimuth);
/// Dispatch on method.
Vec3 sample_ggx_vndf(Vec3 wo, float ax, float ay, Vec2 u, VndfMethod method);
/// Dispatch on method, with azimuth = turn_azimuth(u.x) given (Heitz 2018 draws its azimuth from u.y: unused there).
Vec3 sample_ggx_vndf(Vec3 wo, float ax, float ay, Vec2 u, VndfMethod method, Vec2 azimuth);

}  // namespace lumis
