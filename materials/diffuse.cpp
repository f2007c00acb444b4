// Lambertian reflection and the diffuse material (albedo x optional texture x vertex colour).
#include <cmath>

#include "materials/material.h"
#include "materials/shading.h"

namespace lumis {

/// Local frame: f = albedo / pi (cosine excluded) and pdf = cos(theta_i) / pi per solid angle (projected-solid-
/// angle sampling), both 0 unless both directions are above the surface.
BsdfEval DiffuseBsdf::eval(Vec3 wo, Vec3 wi) const {
  if (!(wo.z > 0 && wi.z > 0)) return {};
  return {albedo * kInvPi, cosine_hemisphere_pdf(wi)};
}

/// Local frame: wi by cosine-weighted hemisphere sampling; u_lobe is unused (single lobe).
std::optional<BsdfSample> DiffuseBsdf::sample(Vec3 wo, float /*u_lobe*/, Vec2 u, Vec2 azimuth) const {
  if (!(wo.z > 0)) return std::nullopt;
  const Vec3 wi = sample_cosine_hemisphere(u, azimuth);
  const BsdfEval e = eval(wo, wi);
  if (!(e.pdf > 0)) return std::nullopt;  // u on the boundary can give wi.z == 0
  return std::make_optional<BsdfSample>(wi, e.f, e.pdf);
}

namespace {

class DiffuseMaterial final : public Material {
 public:
  DiffuseMaterial(Color albedo, std::optional<Texture> texture) : albedo_(albedo), texture_(std::move(texture)) {}

  /// World-space shading frame around hit.ns; Lambert with the textured albedo.
  ShadingPoint shade(const Hit& hit) const override {
    return {base_shading_frame(hit), DiffuseBsdf{albedo(hit)}};
  }

  /// albedo x texture RGB x vertex colour RGB, clamped to [0, 1] so that the BSDF conserves energy.
  Color albedo(const Hit& hit) const override {
    Color a = albedo_ * hit.color.xyz();
    if (texture_) a *= sample_texture(*texture_, hit).xyz();
    return min(max(a, Color(0.0f)), Color(1.0f));
  }

 private:
  Color albedo_;
  std::optional<Texture> texture_;
};

}  // namespace

std::unique_ptr<Material> make_diffuse_material(Color albedo, std::optional<Texture> texture) {
  return std::make_unique<DiffuseMaterial>(albedo, std::move(texture));
}

}  // namespace lumis
