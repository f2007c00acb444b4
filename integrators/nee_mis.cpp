// `nee_mis`: next event estimation plus BSDF continuation, combined by the lecture's two-sample MIS estimator.
// At each vertex, a light sample w_l (light j chosen with P_j, density p_l = P_j p_j) and the BSDF sample w_b
// (density p_b) that continues the path each estimate direct light:
//   f(w_l) cos Le / p_l * w(p_l, p_b)   +   f(w_b) cos Le / p_b * w(p_b, p_l)   [at the emitter w_b hits]
// with w the balance heuristic w(a, b) = a / (a + b) (lecture) or the power heuristic a^2 / (a^2 + b^2)
// (--mis-heuristic power). p_l at a BSDF hit is recomputed from the previous vertex exactly as the light sample
// would have drawn it. Camera rays count emission with weight 1.
#include "integrators/path.h"

namespace lumis {
namespace {

struct NeeMisVariant {
  MisHeuristic heuristic;

  Color emission_weight(const PathState& prev, const Scene& scene, int light, const Hit* on_light, Vec3 dir) const {
    if (prev.from_camera) return Color(1);
    const float pdf_light = light_pdf_for_hit(scene, prev.ctx, light, on_light, dir);
    return Color(mis_weight(prev.pdf_bsdf, pdf_light, heuristic));
  }
  static constexpr bool kLightDraws = true;
  std::optional<ShadowQuery> direct(const Vertex& v, const LightDraw& d, PathCounters& c) const {
    return sample_direct(v, d, /*mis_weighted=*/true, heuristic, c);
  }
  std::optional<Scatter> scatter(const Vertex& v, float, Vec2, float u_lobe, Vec2 u, Vec2 azimuth,
                                 PathCounters&) const {
    return scatter_bsdf(v, u_lobe, u, azimuth);
  }
};

}  // namespace

std::unique_ptr<Integrator> make_nee_mis_integrator(const RenderSettings& s) {
  return std::make_unique<PathIntegrator<NeeMisVariant>>(s, NeeMisVariant{s.mis_heuristic}, "nee_mis");
}

}  // namespace lumis
