// `uniform`: the lecture's baseline. At each vertex the next direction is uniform on the hemisphere around the
// shading normal, by default uniform in (theta, phi) (density 1/(pi^2 sin theta) per solid angle; the
// lecture's "uniform" image), or uniform by solid angle (1/(2 pi)) with --uniform-measure solid-angle.
// Emission is counted, unweighted, whenever a ray hits an emitter:
//   L = Le(x1) + f(x1) cos / p_u * (Le(x2) + f(x2) cos / p_u * (...)).
#include "integrators/path.h"

namespace lumis {
namespace {

struct UniformVariant {
  UniformMeasure measure;

  Color emission_weight(const PathState&, const Scene&, int, const Hit*, Vec3) const { return Color(1); }
  static constexpr bool kLightDraws = false;
  std::optional<ShadowQuery> direct(const Vertex&, const LightDraw&, PathCounters&) const { return std::nullopt; }
  std::optional<Scatter> scatter(const Vertex& v, float, Vec2, float, Vec2 u, Vec2, PathCounters&) const {
    Vec3 wi;
    float pdf;
    if (measure == UniformMeasure::ThetaPhi) {
      wi = sample_uniform_theta_phi_hemisphere(u);
      pdf = uniform_theta_phi_hemisphere_pdf(wi);
    } else {
      wi = sample_uniform_hemisphere(u);
      pdf = uniform_hemisphere_pdf(wi);
    }
    if (!(pdf > 0) || !std::isfinite(pdf)) return std::nullopt;
    const Vec3 w = v.frame.to_world(wi);
    if (dot(w, v.ng) <= 0) return std::nullopt;
    const BsdfEval e = v.bsdf.eval(v.wo, wi);
    return std::make_optional<Scatter>(w, e.f * (std::abs(wi.z) / pdf), e.pdf);
  }
};

}  // namespace

std::unique_ptr<Integrator> make_uniform_integrator(const RenderSettings& s) {
  return std::make_unique<PathIntegrator<UniformVariant>>(s, UniformVariant{s.uniform_measure}, "uniform");
}

}  // namespace lumis
