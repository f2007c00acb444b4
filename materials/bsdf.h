// BSDF interface. Directions are unit vectors in the local shading frame (z = shading normal), both pointing away
// from the surface. f() EXCLUDES the cosine factor; pdf() is per unit solid angle of wi. The estimator weight of a
// sample is f * |cos(wi)| / pdf. BSDFs are small value types held in a std::variant (no heap allocation per hit).
#pragma once

#include <optional>
#include <variant>

#include "core/math.h"
#include "core/warp.h"

namespace lumis {

/// Has a constructor so that std::make_optional<BsdfSample> builds it in place (see LightSample).
struct BsdfSample {
  BsdfSample() = default;
  /// wi, f, pdf (the members themselves are ordered by slot).
  BsdfSample(Vec3 wi_, Color f_, float pdf_) : wi(wi_), pdf(pdf_), f(f_) {}
  // In 16-byte slots (a Vec3 and a float), like Ray in core/ray.h.
  Vec3 wi;       ///< sampled incident direction (local)
  float pdf = 0; ///< solid-angle density of wi under sample() (the full mixture density)
  Color f;       ///< BSDF value f(wo, wi), cosine excluded
};

/// f and pdf of one pair of directions together (Mitsuba's eval_pdf): the values f() and pdf() return, bit for bit,
/// for the work of one call where the two share intermediate results (the GGX half vector, D and Lambda(wo)).
struct BsdfEval {
  Color f;        ///< BSDF value, cosine excluded
  float pdf = 0;  ///< solid-angle density of wi under sample()
};

/// Lambertian reflection: f = albedo / pi on the upper hemisphere.
struct DiffuseBsdf {
  Color albedo;
  Color f(Vec3 wo, Vec3 wi) const { return eval(wo, wi).f; }        ///< local frame, cosine excluded
  float pdf(Vec3 wo, Vec3 wi) const { return eval(wo, wi).pdf; }    ///< solid angle of wi
  BsdfEval eval(Vec3 wo, Vec3 wi) const;                             ///< local frame; f and solid-angle pdf
  /// Local frame; wi's pdf per solid angle. u.x sets the azimuth: the 4-argument form takes turn_azimuth(u.x).
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const {
    return sample(wo, u_lobe, u, turn_azimuth(u.x));
  }
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u, Vec2 azimuth) const;
};

/// GGX microfacet reflection: D G2 F / (4 cos_o cos_i) with height-correlated Smith G2 and Schlick Fresnel.
struct GgxBsdf {
  Color f0;          ///< Fresnel reflectance at normal incidence
  float alpha;       ///< GGX roughness (isotropic), already clamped to a small minimum
  VndfMethod method = VndfMethod::SphericalCap2023;
  Color f(Vec3 wo, Vec3 wi) const { return eval(wo, wi).f; }        ///< local frame, cosine excluded
  float pdf(Vec3 wo, Vec3 wi) const { return eval(wo, wi).pdf; }    ///< solid angle of wi
  BsdfEval eval(Vec3 wo, Vec3 wi) const;                             ///< local frame; f and solid-angle pdf
  /// Local frame; wi's pdf per solid angle. u.x sets the azimuth: the 4-argument form takes turn_azimuth(u.x).
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const {
    return sample(wo, u_lobe, u, turn_azimuth(u.x));
  }
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u, Vec2 azimuth) const;
};

/// glTF metallic-roughness: a diffuse lobe base (1 - metallic) / pi, Fresnel-coupled by (1 - F(cos_o)) (1 - F(cos_i))
/// (docs/materials.md), plus a GGX lobe (F0 = mix(0.04, base, metallic), alpha = roughness^2). Lobe choice per the
/// lecture: diffuse with probability = luminance of base (1 - metallic), at most 0.5.
struct PbrBsdf {
  DiffuseBsdf diffuse;
  GgxBsdf specular;
  float diffuse_probability;
  Color f(Vec3 wo, Vec3 wi) const { return eval(wo, wi).f; }        ///< local frame, cosine excluded
  float pdf(Vec3 wo, Vec3 wi) const { return eval(wo, wi).pdf; }    ///< solid angle of wi
  BsdfEval eval(Vec3 wo, Vec3 wi) const;                             ///< local frame; f and solid-angle pdf
  /// Local frame; wi's pdf per solid angle. u.x sets the azimuth: the 4-argument form takes turn_azimuth(u.x).
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const {
    return sample(wo, u_lobe, u, turn_azimuth(u.x));
  }
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u, Vec2 azimuth) const;
};

/// Minimum GGX alpha, so that near-mirror materials stay representable in float.
inline constexpr float kMinGgxAlpha = 1e-3f;

PbrBsdf make_pbr_bsdf(Color base_color, float metallic, float roughness);

/// Closed set of BSDFs, dispatched by std::visit.
class Bsdf {
 public:
  Bsdf() : v_(DiffuseBsdf{Color(0.5f)}) {}
  template <class T>
  Bsdf(T b) : v_(std::move(b)) {}  // NOLINT: implicit on purpose
  Color f(Vec3 wo, Vec3 wi) const { return std::visit([&](const auto& b) { return b.f(wo, wi); }, v_); }
  float pdf(Vec3 wo, Vec3 wi) const { return std::visit([&](const auto& b) { return b.pdf(wo, wi); }, v_); }
  BsdfEval eval(Vec3 wo, Vec3 wi) const { return std::visit([&](const auto& b) { return b.eval(wo, wi); }, v_); }
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const {
    return sample(wo, u_lobe, u, turn_azimuth(u.x));
  }
  /// The same with azimuth = turn_azimuth(u.x) given (a path batch computes its lanes' azimuths side by side).
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u, Vec2 azimuth) const {
    return std::visit([&](const auto& b) { return b.sample(wo, u_lobe, u, azimuth); }, v_);
  }

 private:
  std::variant<DiffuseBsdf, GgxBsdf, PbrBsdf> v_;
};

}  // namespace lumis
