// What one vertex of a path needs, shared by the path loop (integrators/path.h) and its variants: the shaded
// vertex, what the previous vertex passes on, next-event estimation in two halves (the light draw, then the shadow
// query), the light-sampling densities MIS needs, and the MIS weight itself. Implemented in integrators/path.cpp.
#pragma once

#include <optional>

#include "integrators/integrator.h"

namespace lumis {

/// A scattering vertex, shaded and oriented: frame.n and ng face the side the path arrived from.
struct Vertex {
  /// Members in order.
  Vertex(const Scene& scene_, const Hit& hit_, const Frame& frame_, Vec3 ng_, const Bsdf& bsdf_, Vec3 wo_,
         LightSampleContext ctx_)
      : scene(scene_), hit(hit_), frame(frame_), ng(ng_), bsdf(bsdf_), wo(wo_), ctx(ctx_) {}
  const Scene& scene;
  const Hit& hit;
  Frame frame;               ///< shading frame (world <-> local), flipped toward wo
  Vec3 ng;                   ///< geometric normal flipped toward wo (world)
  Bsdf bsdf;
  Vec3 wo;                   ///< local outgoing direction (toward the previous vertex), wo.z > 0
  LightSampleContext ctx;    ///< light_context(hit): the rays' origin off the surface, and ng
};

/// What the previous vertex passes on to the next emitter hit.
struct PathState {
  bool from_camera = true;   ///< the current ray is a camera ray
  LightSampleContext ctx;    ///< receiver context of the previous vertex
  float pdf_bsdf = 0;        ///< BSDF density of the current ray's direction at the previous vertex (solid angle)
};

/// The direction a vertex continues along, and the path throughput factor f cos / p.
/// (Constructors: std::make_optional builds these in place, see LightSample in lights/light.h.)
struct Scatter {
  Scatter() = default;
  /// wi, weight, pdf_bsdf (the members themselves are ordered by slot).
  Scatter(Vec3 wi_, Color weight_, float pdf_bsdf_) : wi(wi_), pdf_bsdf(pdf_bsdf_), weight(weight_) {}
  // In 16-byte slots (a Vec3 and a float), like Ray in core/ray.h.
  Vec3 wi;                   ///< world direction
  float pdf_bsdf = 0;        ///< BSDF density of wi (for MIS at the next emitter hit)
  Color weight;              ///< f |cos| / p
};

/// Balance (lecture) or power heuristic weight of strategy a against b; 0 when both vanish or are not finite.
float mis_weight(float pdf_a, float pdf_b, MisHeuristic heuristic);

/// A next-event-estimation sample waiting for its shadow ray: value counts when ray is unoccluded.
struct ShadowQuery {
  ShadowQuery() = default;
  /// Members in order.
  ShadowQuery(const Ray& ray_, Color value_) : ray(ray_), value(value_) {}
  Ray ray;      ///< from the vertex to the light point (world)
  Color value;  ///< f |cos| Le / (pmf pdf_light), times the MIS weight when asked (pdf_light: solid angle)
};

/// The geometric normal of a hit turned toward the arriving ray (two-sided shading): Vertex::ng.
inline Vec3 facing_ng(const Hit& hit) { return hit.front ? hit.ng : -hit.ng; }

/// The receiver for light sampling at a hit (Vertex::ctx, whether drawn in make_vertex or draw_lights), world
/// space: the point every ray leaving the hit on its facing side starts from (spawn_ray's offset origin, bit for
/// bit) and facing_ng. Light directions drawn from hit.p itself missed small lights from that origin (`mis`
/// traces them: 4 % too dark under a 0.03-radius sphere over a 2000-unit ground, whose offset is 4e-3).
inline LightSampleContext light_context(const Hit& hit) {
  const Vec3 ng = facing_ng(hit);
  return {offset_ray_origin(hit.p, hit.p_error, ng, ng), ng};
}

/// Next-event estimation's first half at one vertex: the light the scene's selector chose and that light's sample.
struct LightDraw {
  LightSample sample;      ///< valid when ok
  LightSampleContext ctx;  ///< the receiver, light_context(hit): make_vertex takes it instead of computing it again
  LightChoice choice;      ///< index -1: no light can contribute here
  bool ok = false;         ///< the chosen light gave a sample
};

/// The light draws of a bounce's lanes[0..m) into out[lane], from their hits and their vertex dimensions (choice,
/// light), each what one lane alone would draw: the receiver is make_vertex's ctx, light_context(hit).
/// Selection and sampling run for all lanes at once (vectorised where the light has a batch kernel).
void draw_lights(const Scene& scene, const Hit* hits, const int* lanes, int m, const VertexDims* dims,
                 LightDraw* out);

/// One next-event-estimation sample at v from its light draw: the shadow ray to trace and its value; nullopt when
/// the sample contributes nothing whatever the visibility. MIS-weighted against BSDF sampling when mis_weighted.
std::optional<ShadowQuery> sample_direct(const Vertex& v, const LightDraw& draw, bool mis_weighted,
                                         MisHeuristic heuristic, PathCounters& counters);

/// Density of light sampling in direction wi from ctx (solid angle): sum over every light whose solid angle
/// contains wi of pmf(light) x pdf(light), visible or not. Used by the one-sample MIS combination.
float light_strategy_pdf(const Scene& scene, const Hit& from, const LightSampleContext& ctx, Vec3 wi,
                         PathCounters& counters);

/// Density with which light sampling at ctx would produce the emitter point on_light of light `light` along dir.
float light_pdf_for_hit(const Scene& scene, const LightSampleContext& ctx, int light, const Hit* on_light, Vec3 dir);

/// BSDF-sampled continuation shared by bsdf, light and nee_mis; azimuth = turn_azimuth(u.x).
std::optional<Scatter> scatter_bsdf(const Vertex& v, float u_lobe, Vec2 u, Vec2 azimuth);

/// Orient and shade a hit; nullopt when it cannot scatter (pure emitter, or degenerate). ctx: light_context(hit)
/// when the caller has it already (draw_lights), else null.
std::optional<Vertex> make_vertex(const Scene& scene, const Hit& hit, Vec3 ray_dir,
                                  const LightSampleContext* ctx = nullptr);

}  // namespace lumis
