// `mis`: the lecture's one-sample combination of strategies ("combining sampling strategies"). At each vertex
// ONE direction is drawn: by light sampling with probability c_l (light j chosen with P_j, then p_j), otherwise
// by BSDF sampling (probability c_b = 1 - c_l). Its density is the mixture
//   p(w) = c_b p_b(w) + c_l sum_j P_j p_j(w),
// summed over every light whose solid angle contains w (visible or not: Geometry::all_light_hits). The path
// continues along w with throughput f cos / p, and emission is counted, unweighted, whenever a ray hits an
// emitter: f / p is the balance heuristic of a single sample.
#include "integrators/path.h"

namespace lumis {
namespace {

struct MisVariant {
  float c_light;  // c_l: probability of the light strategy

  Color emission_weight(const PathState&, const Scene&, int, const Hit*, Vec3) const { return Color(1); }
  static constexpr bool kLightDraws = false;
  std::optional<ShadowQuery> direct(const Vertex&, const LightDraw&, PathCounters&) const { return std::nullopt; }
  std::optional<Scatter> scatter(const Vertex& v, float u_choice, Vec2 u_light, float u_lobe, Vec2 u, Vec2 azimuth,
                                 PathCounters& c) const {
    const float c_l = v.scene.lights.empty() ? 0.0f : c_light;
    Vec3 wi_world;
    if (u_lobe < c_l) {
      const std::optional<LightChoice> choice = v.scene.light_selector.sample(v.ctx, u_choice);
      if (!choice) return std::nullopt;
      const std::optional<LightSample> ls = v.scene.lights[choice->index]->sample(v.ctx, u_light);
      if (!ls || !(ls->pdf > 0)) return std::nullopt;
      wi_world = ls->wi;
    } else {
      const float u_bsdf = std::min((u_lobe - c_l) / (1 - c_l), kOneMinusEpsilon);
      const std::optional<BsdfSample> bs = v.bsdf.sample(v.wo, u_bsdf, u, azimuth);
      if (!bs || !(bs->pdf > 0)) return std::nullopt;
      wi_world = v.frame.to_world(bs->wi);
    }
    if (dot(wi_world, v.ng) <= 0) return std::nullopt;
    const Vec3 wi = v.frame.to_local(wi_world);
    const BsdfEval e = v.bsdf.eval(v.wo, wi);
    const float pdf_bsdf = e.pdf;
    const float pdf_light = c_l > 0 ? light_strategy_pdf(v.scene, v.hit, v.ctx, wi_world, c) : 0.0f;
    const float pdf = (1 - c_l) * pdf_bsdf + c_l * pdf_light;
    if (!(pdf > 0)) return std::nullopt;
    return std::make_optional<Scatter>(wi_world, e.f * (std::abs(wi.z) / pdf), pdf_bsdf);
  }
};

}  // namespace

std::unique_ptr<Integrator> make_mis_integrator(const RenderSettings& s) {
  return std::make_unique<PathIntegrator<MisVariant>>(s, MisVariant{s.mis_light_probability}, "mis");
}

}  // namespace lumis
