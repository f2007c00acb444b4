// `bsdf`: BSDF importance sampling only. Each vertex continues along a direction drawn from the BSDF (cosine
// for diffuse, visible normals for GGX, the lecture's lobe choice for pbr); emission is counted, unweighted,
// whenever a ray hits an emitter:  L = Le(x1) + f cos / p_b * (Le(x2) + ...).
// Noisy for small lights on rough surfaces (the lecture's "BRDF sampling" panel).
#include "integrators/path.h"

namespace lumis {
namespace {

struct BsdfVariant {
  Color emission_weight(const PathState&, const Scene&, int, const Hit*, Vec3) const { return Color(1); }
  static constexpr bool kLightDraws = false;
  std::optional<ShadowQuery> direct(const Vertex&, const LightDraw&, PathCounters&) const { return std::nullopt; }
  std::optional<Scatter> scatter(const Vertex& v, float, Vec2, float u_lobe, Vec2 u, Vec2 azimuth,
                                 PathCounters&) const {
    return scatter_bsdf(v, u_lobe, u, azimuth);
  }
};

}  // namespace

std::unique_ptr<Integrator> make_bsdf_integrator(const RenderSettings& s) {
  return std::make_unique<PathIntegrator<BsdfVariant>>(s, BsdfVariant{}, "bsdf");
}

}  // namespace lumis
