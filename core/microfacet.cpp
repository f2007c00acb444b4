// GGX (Trowbridge-Reitz) microfacet distribution: D, Smith masking, and two samplers of the distribution of
// visible normals. Everything is in the local frame of the macro-surface (z = macro normal), with anisotropic
// roughness (ax, ay). Written for alphas down to kMinGgxAlpha = 1e-3 in float: squared terms are formed as
// ratios (m.x / ax)^2 rather than tan^2 theta, and Lambda avoids the cancellation in sqrt(1 + x) - 1.
#include <cmath>

#include "core/warp.h"

namespace lumis {

namespace {

/// Unit vector, or `fallback` when v has no usable length (zero, denormal or non-finite).
Vec3 normalize_or(Vec3 v, Vec3 fallback) {
  const float l2 = length_squared(v);
  if (!(l2 > 1e-30f) || !std::isfinite(l2)) return fallback;
  return v / std::sqrt(l2);
}

}  // namespace

/// Per unit solid angle of microfacet normals; integrates to 1 against m.z (projected area).
float ggx_d(Vec3 wm, float ax, float ay) {
  if (!(wm.z > 0)) return 0;
  // D = 1 / (pi ax ay (x^2/ax^2 + y^2/ay^2 + z^2)^2): the form cos^4 (1 + tan^2 ...)^2 multiplied out, so that no
  // tan^2 overflows near the horizon.
  const float sx = wm.x / ax, sy = wm.y / ay;
  const float q = sx * sx + sy * sy + wm.z * wm.z;
  return 1.0f / (kPi * ax * ay * q * q);
}

/// Smith Lambda for direction w (local frame; only w.z^2 matters, so it is even in w.z).
float ggx_lambda(Vec3 w, float ax, float ay) {
  const float z2 = w.z * w.z;
  const float t = sqr(w.x * ax) + sqr(w.y * ay);  // alpha^2 tan^2 theta, times cos^2 theta
  if (!(z2 > 0)) return t > 0 ? INFINITY : 0.0f;
  const float x = t / z2;
  if (std::isinf(x)) return INFINITY;
  // (sqrt(1 + x) - 1) / 2, written without cancellation for small x (smooth surfaces).
  return x / (2.0f * (1.0f + std::sqrt(1.0f + x)));
}

/// Smith masking G1(w) = 1 / (1 + Lambda(w)); 0 at grazing incidence.
float ggx_g1(Vec3 w, float ax, float ay) { return 1.0f / (1.0f + ggx_lambda(w, ax, ay)); }

/// Height-correlated Smith masking-shadowing G2(wo, wi) (Heitz 2014, eq. 99).
float ggx_g2(Vec3 wo, Vec3 wi, float ax, float ay) {
  return 1.0f / (1.0f + ggx_lambda(wo, ax, ay) + ggx_lambda(wi, ax, ay));
}

/// Solid-angle density (of wm) of the normals visible from wo: G1(wo) max(0, wo.wm) D(wm) / wo.z.
float ggx_vndf_pdf(Vec3 wo, Vec3 wm, float ax, float ay) {
  if (!(wo.z > 0)) return 0;
  const float cos_om = dot(wo, wm);
  if (!(cos_om > 0)) return 0;
  return ggx_g1(wo, ax, ay) * cos_om * ggx_d(wm, ax, ay) / wo.z;
}

/// Heitz 2018: stretch wo to the hemisphere configuration (alpha = 1), sample the projected area of the visible
/// half of the hemisphere as a disk whose far half is squashed by (1 + vh.z) / 2, lift to the hemisphere, unstretch.
Vec3 sample_ggx_vndf_heitz(Vec3 wo, float ax, float ay, Vec2 u) {
  const Vec3 vh = normalize_or({ax * wo.x, ay * wo.y, wo.z}, {0, 0, 1});
  // Orthonormal basis (t1, t2, vh); t1 is horizontal. At normal incidence any horizontal axis works.
  const float len2 = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = len2 > 0 ? Vec3{-vh.y, vh.x, 0} / std::sqrt(len2) : Vec3{1, 0, 0};
  const Vec3 t2 = cross(vh, t1);
  // Uniform point on the unit disk (polar), then the lower half is compressed to the projected visible area.
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * kPi * u.y;
  const float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  const float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * safe_sqrt(1.0f - p1 * p1) + s * p2;
  const Vec3 nh = t1 * p1 + t2 * p2 + vh * safe_sqrt(1.0f - p1 * p1 - p2 * p2);
  return normalize_or({ax * nh.x, ay * nh.y, std::max(0.0f, nh.z)}, {0, 0, 1});
}

/// Dupuy & Benyoub 2023: in the stretched configuration the visible normals are (c + v) / |c + v| for c uniform on
/// the spherical cap z >= -v.z of the unit sphere, so sample that cap (uniform z, uniform phi), add v, unstretch.
Vec3 sample_ggx_vndf_spherical_cap(Vec3 wo, float ax, float ay, Vec2 u) {
  return sample_ggx_vndf_spherical_cap(wo, ax, ay, u, turn_azimuth(u.x));
}

/// The azimuth phi = 2 pi u.x of the cap point comes in as (cos phi, sin phi).
Vec3 sample_ggx_vndf_spherical_cap(Vec3 wo, float ax, float ay, Vec2 u, Vec2 azimuth) {
  const Vec3 v = normalize_or({ax * wo.x, ay * wo.y, wo.z}, {0, 0, 1});
  // z uniform in (-v.z, 1]: the cap's solid angle is 2 pi (1 + v.z).
  const float z = std::fma(1.0f - u.y, 1.0f + v.z, -v.z);
  const float sin_theta = safe_sqrt(1.0f - z * z);
  const Vec3 c{sin_theta * azimuth.x, sin_theta * azimuth.y, z};
  const Vec3 h = c + v;  // unnormalised stretched normal; h.z >= 0 by construction
  return normalize_or({ax * h.x, ay * h.y, std::max(0.0f, h.z)}, {0, 0, 1});
}

/// Visible normal of solid-angle density ggx_vndf_pdf(wo, ., ax, ay) by the chosen method.
Vec3 sample_ggx_vndf(Vec3 wo, float ax, float ay, Vec2 u, VndfMethod method) {
  return method == VndfMethod::Heitz2018 ? sample_ggx_vndf_heitz(wo, ax, ay, u)
                                         : sample_ggx_vndf_spherical_cap(wo, ax, ay, u);
}

Vec3 sample_ggx_vndf(Vec3 wo, float ax, float ay, Vec2 u, VndfMethod method, Vec2 azimuth) {
  return method == VndfMethod::Heitz2018 ? sample_ggx_vndf_heitz(wo, ax, ay, u)
                                         : sample_ggx_vndf_spherical_cap(wo, ax, ay, u, azimuth);
}

}  // namespace lumis
