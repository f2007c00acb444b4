// The glTF 2.0 metallic-roughness BSDF: a GGX specular lobe over a Lambert lobe, and the textured material.
//
// Diffuse/specular coupling. glTF's reference "fresnel_mix" weights the diffuse lobe by 1 - F(wo.h), which is
// reciprocal but lets a white dielectric reflect more than it receives near grazing incidence (the specular lobe
// already returns about F(cos_o) there while the diffuse lobe keeps ~90%). Here the diffuse lobe is instead
//   f_d = base (1 - metallic) / pi * (1 - F(cos_o)) * (1 - F(cos_i)),   F = Schlick with the specular lobe's F0,
// which is symmetric in (wo, wi) and leaves to the diffuse lobe only what the specular lobe's Fresnel did not
// take at either end. Its directional albedo is at most (1 - F(cos_o)) (1 - F0) 20/21, so the total stays <= 1
// whenever the GGX lobe's albedo stays below F(cos_o) + margin, which tests/unit/test_materials_bsdf.cpp checks
// over roughness, angle, base colour and metallic.
#include <cmath>

#include "materials/fresnel.h"
#include "materials/material.h"
#include "materials/shading.h"

namespace lumis {

/// Local frame. f (cosine excluded): the Fresnel-coupled Lambert lobe plus the GGX lobe; pdf (solid angle of wi):
/// the mixture density c p_diffuse + (1 - c) p_specular that sample() draws from.
BsdfEval PbrBsdf::eval(Vec3 wo, Vec3 wi) const {
  if (!(wo.z > 0 && wi.z > 0)) return {};
  const Color white(1.0f);
  const Color coupling = (white - schlick_fresnel(specular.f0, wo.z)) * (white - schlick_fresnel(specular.f0, wi.z));
  const BsdfEval d = diffuse.eval(wo, wi), s = specular.eval(wo, wi);
  const float c = diffuse_probability;
  float p = 0;
  if (c > 0) p += c * d.pdf;
  if (c < 1) p += (1 - c) * s.pdf;
  return {d.f * coupling + s.f, p};
}

/// Local frame: u_lobe < diffuse_probability picks the cosine lobe, otherwise visible-normal sampling.
std::optional<BsdfSample> PbrBsdf::sample(Vec3 wo, float u_lobe, Vec2 u, Vec2 azimuth) const {
  if (!(wo.z > 0)) return std::nullopt;
  Vec3 wi;
  if (u_lobe < diffuse_probability) {
    wi = sample_cosine_hemisphere(u, azimuth);
  } else {
    wi = reflect(wo, sample_ggx_vndf(wo, specular.alpha, specular.alpha, u, specular.method, azimuth));
  }
  if (!(wi.z > 0)) return std::nullopt;
  const BsdfEval e = eval(wo, wi);
  if (!(e.pdf > 0) || !std::isfinite(e.pdf)) return std::nullopt;
  return std::make_optional<BsdfSample>(wi, e.f, e.pdf);
}

/// glTF parameters -> lobes: diffuse albedo base (1 - m), F0 = mix(0.04, base, m), alpha = max(r^2, min alpha);
/// the diffuse lobe is sampled with probability min(luminance(diffuse albedo), 0.5) (the lecture's rule).
PbrBsdf make_pbr_bsdf(Color base_color, float metallic, float roughness) {
  const Color base = min(max(base_color, Color(0.0f)), Color(1.0f));
  const float m = std::isfinite(metallic) ? clamp(metallic, 0.0f, 1.0f) : 0.0f;
  const float r = std::isfinite(roughness) ? clamp(roughness, 0.0f, 1.0f) : 1.0f;
  const Color diffuse_albedo = base * (1 - m);
  const Color f0 = lerp(m, Color(0.04f), base);
  const float alpha = std::max(r * r, kMinGgxAlpha);
  const float c = std::min(luminance(diffuse_albedo), 0.5f);
  return PbrBsdf{DiffuseBsdf{diffuse_albedo}, GgxBsdf{f0, alpha}, c};
}

namespace {

class PbrMaterial final : public Material {
 public:
  explicit PbrMaterial(PbrParams p) : p_(std::move(p)) {}

  /// World-space shading frame (normal-mapped when there is a normal texture) and the BSDF from the textures.
  ShadingPoint shade(const Hit& hit) const override {
    float metallic = p_.metallic, roughness = p_.roughness;
    if (p_.metallic_roughness_texture) {
      const Vec4 mr = sample_texture(*p_.metallic_roughness_texture, hit);
      roughness *= mr.y;
      metallic *= mr.z;
    }
    const Frame frame =
        p_.normal_texture ? normal_mapped_frame(hit, *p_.normal_texture, p_.normal_scale) : base_shading_frame(hit);
    return {frame, make_pbr_bsdf(albedo(hit), metallic, roughness)};
  }

  /// Base colour: factor x texture RGB (already linear) x vertex colour RGB (COLOR_0).
  Color albedo(const Hit& hit) const override {
    Color base = p_.base_color * hit.color.xyz();
    if (p_.base_color_texture) base *= sample_texture(*p_.base_color_texture, hit).xyz();
    return base;
  }

 private:
  PbrParams p_;
};

}  // namespace

std::unique_ptr<Material> make_pbr_material(PbrParams params) {
  return std::make_unique<PbrMaterial>(std::move(params));
}

}  // namespace lumis
