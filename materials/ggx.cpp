// GGX microfacet reflection (Walter et al. 2007) with height-correlated Smith shadowing, Schlick Fresnel and
// visible-normal sampling, and the pure-specular material built on it.
#include <cmath>

#include "materials/fresnel.h"
#include "materials/material.h"
#include "materials/shading.h"

namespace lumis {

/// Local frame. f (cosine excluded) = D(h) G2(wo, wi) F(wo.h) / (4 cos_o cos_i) with h the half vector; pdf (solid
/// angle of wi) = the visible-normal density of h times the reflection Jacobian 1 / (4 wo.h), which simplifies to
/// D(h) G1(wo) / (4 cos_o): wo.h cancels. Written for the isotropic lobe with three divisions and no normalised h
/// (GgxBsdf.EvalMatchesTheTextbookForms checks it against ggx_d, ggx_g2 and ggx_vndf_pdf):
///   with s = wo + wi, D(h) = a^2 |s|^4 / (pi (s_x^2 + s_y^2 + a^2 s_z^2)^2), a = alpha;
///   with r(w) = sqrt(w_z^2 + a^2 (w_x^2 + w_y^2)) = cos(w) (1 + 2 Lambda(w)),
///   G2 / (4 cos_o cos_i) = 1 / (2 (cos_i r(wo) + cos_o r(wi))) and G1(wo) / (4 cos_o) = 1 / (2 (cos_o + r(wo))).
BsdfEval GgxBsdf::eval(Vec3 wo, Vec3 wi) const {
  if (!(wo.z > 0 && wi.z > 0)) return {};
  const Vec3 s = wo + wi;
  const float l2 = length_squared(s);
  if (!(l2 > 0)) return {};
  const float a2 = alpha * alpha;
  const float q = s.x * s.x + s.y * s.y + a2 * (s.z * s.z);
  const float d = a2 * (l2 * l2) / (kPi * (q * q));
  const float r_o = std::sqrt(wo.z * wo.z + a2 * (wo.x * wo.x + wo.y * wo.y));
  const float r_i = std::sqrt(wi.z * wi.z + a2 * (wi.x * wi.x + wi.y * wi.y));
  // For unit wo, wi: wo.h = wi.h = |wo + wi| / 2. This form is symmetric by construction (reciprocity survives
  // rounding) and stays accurate when wo and wi are nearly opposite, where h itself is ill-conditioned.
  const float cos_h = 0.5f * std::sqrt(l2);
  return {schlick_fresnel(f0, cos_h) * (d / (2.0f * (wi.z * r_o + wo.z * r_i))), d / (2.0f * (wo.z + r_o))};
}

/// Local frame: a visible normal for wo, mirrored; fails when the mirrored direction is below the surface.
std::optional<BsdfSample> GgxBsdf::sample(Vec3 wo, float /*u_lobe*/, Vec2 u, Vec2 azimuth) const {
  if (!(wo.z > 0)) return std::nullopt;
  const Vec3 wm = sample_ggx_vndf(wo, alpha, alpha, u, method, azimuth);
  const Vec3 wi = reflect(wo, wm);
  if (!(wi.z > 0)) return std::nullopt;
  // Evaluate through eval() so that a sample carries exactly what f() and pdf() return for (wo, wi).
  const BsdfEval e = eval(wo, wi);
  if (!(e.pdf > 0) || !std::isfinite(e.pdf)) return std::nullopt;
  return std::make_optional<BsdfSample>(wi, e.f, e.pdf);
}

namespace {

class GgxMaterial final : public Material {
 public:
  GgxMaterial(Color f0, float roughness)
      : f0_(min(max(f0, Color(0.0f)), Color(1.0f))),
        alpha_(std::max(sqr(clamp(roughness, 0.0f, 1.0f)), kMinGgxAlpha)) {}

  /// World-space shading frame around hit.ns with the GGX lobe (alpha = roughness^2, as glTF).
  ShadingPoint shade(const Hit& hit) const override {
    return {base_shading_frame(hit), GgxBsdf{f0_, alpha_}};
  }
  /// The normal-incidence reflectance stands in for the albedo AOV.
  Color albedo(const Hit& /*hit*/) const override { return f0_; }

 private:
  Color f0_;
  float alpha_;
};

}  // namespace

std::unique_ptr<Material> make_ggx_material(Color f0, float roughness) {
  return std::make_unique<GgxMaterial>(f0, roughness);
}

}  // namespace lumis
