// `light`: next event estimation with light sampling only. At each vertex one light is chosen (P_j by the
// selection strategy) and sampled (p_j per solid angle); the direct term is f cos Le V / (P_j p_j). The path
// continues by BSDF sampling, and a BSDF ray that hits an emitter adds nothing (that light was already counted
// by the light sample), except a camera ray, which sees emitters directly:
//   L = Le(x1) + sum_k beta_k f cos Le / (P p_l).
// Noisy for large lights on smooth surfaces (the lecture's "light sampling" panel).
#include "integrators/path.h"

namespace lumis {
namespace {

struct LightVariant {
  MisHeuristic heuristic;

  Color emission_weight(const PathState& prev, const Scene&, int, const Hit*, Vec3) const {
    return Color(prev.from_camera ? 1.0f : 0.0f);
  }
  static constexpr bool kLightDraws = true;
  std::optional<ShadowQuery> direct(const Vertex& v, const LightDraw& d, PathCounters& c) const {
    return sample_direct(v, d, /*mis_weighted=*/false, heuristic, c);
  }
  std::optional<Scatter> scatter(const Vertex& v, float, Vec2, float u_lobe, Vec2 u, Vec2 azimuth,
                                 PathCounters&) const {
    return scatter_bsdf(v, u_lobe, u, azimuth);
  }
};

}  // namespace

std::unique_ptr<Integrator> make_light_integrator(const RenderSettings& s) {
  return std::make_unique<PathIntegrator<LightVariant>>(s, LightVariant{s.mis_heuristic}, "light");
}

}  // namespace lumis
