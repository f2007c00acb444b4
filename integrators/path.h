// The one path loop shared by every integrator variant, in the shape of Mitsuba's: the state carried between
// vertices is the previous vertex's receiver context and the densities its direction was drawn with.
// A variant supplies three hooks (see the variant files):
//   Color emission_weight(const PathState& prev, const Scene&, int light, const Hit* on_light, Vec3 dir) const;
//   Color direct(const Vertex& v, float u_choice, Vec2 u_light, PathCounters& c) const;  // NEE (or zero)
//   std::optional<Scatter> scatter(const Vertex& v, float u_choice, Vec2 u_light, float u_lobe, Vec2 u_dir,
//                                  PathCounters& c) const;
// Sampler dimensions per vertex are consumed in a fixed order whatever the variant, so stratification lines up:
// light choice (1D), light position (2D), BSDF/strategy choice (1D), direction (2D), Russian roulette (1D).
#pragma once

#include <optional>

#include "integrators/integrator.h"

namespace lumis {

/// A scattering vertex, shaded and oriented: frame.n and ng face the side the path arrived from.
struct Vertex {
  /// Members in order (a constructor, not aggregate init: clang 14 has no parenthesised aggregate init for emplace).
  Vertex(const Scene& scene_, const Hit& hit_, const Frame& frame_, Vec3 ng_, const Bsdf& bsdf_, Vec3 wo_,
         LightSampleContext ctx_)
      : scene(scene_), hit(hit_), frame(frame_), ng(ng_), bsdf(bsdf_), wo(wo_), ctx(ctx_) {}
  const Scene& scene;
  const Hit& hit;
  Frame frame;               ///< shading frame (world <-> local), flipped toward wo
  Vec3 ng;                   ///< geometric normal flipped toward wo (world)
  Bsdf bsdf;
  Vec3 wo;                   ///< local outgoing direction (toward the previous vertex), wo.z > 0
  LightSampleContext ctx;    ///< receiver for light sampling: hit point and ng
};

/// What the previous vertex passes on to the next emitter hit.
struct PathState {
  bool from_camera = true;   ///< the current ray is a camera ray
  LightSampleContext ctx;    ///< receiver context of the previous vertex
  float pdf_bsdf = 0;        ///< BSDF density of the current ray's direction at the previous vertex (solid angle)
};

/// The direction a vertex continues along, and the path throughput factor f cos / p.
struct Scatter {
  Vec3 wi;                   ///< world direction
  Color weight;              ///< f |cos| / p
  float pdf_bsdf = 0;        ///< BSDF density of wi (for MIS at the next emitter hit)
};

/// Balance (lecture) or power heuristic weight of strategy a against b; 0 when both vanish or are not finite.
float mis_weight(float pdf_a, float pdf_b, MisHeuristic heuristic);

/// One next-event-estimation sample at v: light chosen by the scene's selector, its sample, the shadow ray.
/// Returns f |cos| Le / (pmf pdf_light) times the MIS weight against BSDF sampling when mis_weighted.
Color estimate_direct(const Vertex& v, float u_choice, Vec2 u_light, bool mis_weighted, MisHeuristic heuristic,
                      PathCounters& counters);

/// Density of light sampling in direction wi from ctx (solid angle): sum over every light whose solid angle
/// contains wi of pmf(light) x pdf(light), visible or not. Used by the one-sample MIS combination.
float light_strategy_pdf(const Scene& scene, const Hit& from, const LightSampleContext& ctx, Vec3 wi,
                         PathCounters& counters);

/// Density with which light sampling at ctx would produce the emitter point on_light of light `light` along dir.
float light_pdf_for_hit(const Scene& scene, const LightSampleContext& ctx, int light, const Hit* on_light, Vec3 dir);

/// BSDF-sampled continuation shared by bsdf, light and nee_mis.
std::optional<Scatter> scatter_bsdf(const Vertex& v, float u_lobe, Vec2 u);

/// Orient and shade a hit; false when it cannot scatter (pure emitter, or degenerate).
bool make_vertex(const Scene& scene, const Hit& hit, Vec3 ray_dir, std::optional<Vertex>& out);

template <class Variant>
class PathIntegrator final : public Integrator {
 public:
  PathIntegrator(const RenderSettings& s, Variant v, const char* name)
      : max_depth_(s.max_depth), rr_depth_(s.rr_depth), variant_(std::move(v)), name_(name) {}

  const char* name() const override { return name_; }

  Color li(const Scene& scene, const Ray& camera_ray, const PrimaryHit* primary, Sampler& sampler, AovSample* aov,
           PathCounters& counters) const override {
    Color radiance(0), beta(1);
    PathState prev;
    Ray ray = camera_ray;
    for (int bounce = 0;; ++bounce) {
      Hit hit;
      ++counters.rays;
      const bool found = bounce == 0 && primary ? primary->hit != nullptr : scene.geometry.intersect(ray, hit);
      if (bounce == 0 && primary && found) hit = *primary->hit;
      if (!found) {
        if (scene.environment >= 0) {
          const Color le = scene.lights[scene.environment]->le_escaped(ray.d);
          if (!is_black(le))
            radiance += beta * le * variant_.emission_weight(prev, scene, scene.environment, nullptr, ray.d);
        }
        if (bounce == 0 && aov) *aov = AovSample{Color(0), Vec3(0), 0};
        break;
      }
      if (hit.light >= 0) {
        const Color le = scene.lights[hit.light]->le(hit, -ray.d);
        if (!is_black(le)) radiance += beta * le * variant_.emission_weight(prev, scene, hit.light, &hit, ray.d);
      }
      std::optional<Vertex> v;
      const bool can_scatter = make_vertex(scene, hit, ray.d, v);
      if (bounce == 0 && aov) {
        aov->albedo = hit.material >= 0 ? scene.materials[hit.material]->albedo(hit) : Color(0);
        aov->normal = can_scatter ? v->frame.n : hit.ng;
        aov->depth = hit.t * length(ray.d);
      }
      if (bounce >= max_depth_ || !can_scatter) break;

      // Dimensions: light choice, light position, strategy/lobe choice, direction, roulette (fixed order).
      const float u_choice = sampler.get1d();
      const Vec2 u_light = sampler.get2d();
      const float u_lobe = sampler.get1d();
      const Vec2 u_dir = sampler.get2d();
      const float u_rr = sampler.get1d();

      radiance += beta * variant_.direct(*v, u_choice, u_light, counters);
      const std::optional<Scatter> s = variant_.scatter(*v, u_choice, u_light, u_lobe, u_dir, counters);
      if (!s || is_black(s->weight) || !is_finite(s->weight)) break;
      beta *= s->weight;
      prev = {false, v->ctx, s->pdf_bsdf};

      // Unbiased Russian roulette: survive with probability q, divide by q.
      if (rr_depth_ > 0 && bounce + 1 >= rr_depth_) {
        const float q = std::min(0.95f, max_component(beta));
        if (u_rr >= q) break;
        beta /= q;
      }
      ray = spawn_ray(hit, s->wi);
    }
    return radiance;
  }

 private:
  int max_depth_, rr_depth_;
  Variant variant_;
  const char* name_;
};

}  // namespace lumis
