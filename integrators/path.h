// The one path loop shared by every integrator variant, in the shape of Mitsuba's: the state carried between
// vertices is the previous vertex's receiver context and the densities its direction was drawn with.
// A variant supplies three hooks (see the variant files):
//   Color emission_weight(const PathState& prev, const Scene&, int light, const Hit* on_light, Vec3 dir) const;
//   static constexpr bool kLightDraws;  // direct() uses the vertex's light draw (next-event estimation)
//   std::optional<ShadowQuery> direct(const Vertex& v, const LightDraw& d, PathCounters& c) const;
//                                                                   // NEE: the shadow ray and its value, or none
//   std::optional<Scatter> scatter(const Vertex& v, float u_choice, Vec2 u_light, float u_lobe, Vec2 u_dir,
//                                  Vec2 azimuth, PathCounters& c) const;   // azimuth = turn_azimuth(u_dir.x)
// Sampler dimensions per vertex are consumed in a fixed order whatever the variant, so stratification lines up:
// light choice (1D), light position (2D), BSDF/strategy choice (1D), direction (2D), Russian roulette (1D).
// The paths of a PathBatch (up to 256 neighbouring pixels) advance in lockstep, one bounce of every live lane at a
// time: closest hits (in 16-ray packets), then the sampler dimensions, the BSDF azimuths and (next-event variants)
// the light choices and light samples of all lanes side by side, then shading of each lane (its next-event estimate
// is held as a ShadowQuery), then all of the bounce's shadow rays in 16-ray Embree packets. Each lane has its own
// sampler and state, so its estimate is the one it would get alone (tests/app/test_end_to_end.cpp checks this bit
// for bit with the packets off; Embree's packet kernels round hit distances differently in the last bits).
#pragma once

#include <optional>

#include "core/sincos_batch.h"
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
  // In 16-byte slots (a Vec3 and a float), like Ray in core/geometry.h.
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

template <class Variant>
class PathIntegrator final : public Integrator {
 public:
  PathIntegrator(const RenderSettings& s, Variant v, const char* name)
      : max_depth_(s.max_depth), rr_depth_(s.rr_depth), variant_(std::move(v)), name_(name) {}

  const char* name() const override { return name_; }

  void li(const Scene& scene, const PathBatch& batch, PathCounters& counters) const override {
    constexpr int kLanes = PathBatch::kMaxLanes, kPacket = PathBatch::kPacket;
    const int n = std::min(batch.n, kLanes);
    // Per lane: the current ray and its hit, throughput, what the previous vertex passes on, whether it goes on.
    Ray rays[kLanes];
    Hit hits[kLanes];
    Color beta[kLanes];
    PathState prev[kLanes];
    bool alive[kLanes], found[kLanes];
    for (int k = 0; k < n; ++k) {
      rays[k] = batch.rays[k];
      beta[k] = Color(1);
      alive[k] = true;
      batch.radiance[k] = Color(0);
    }
    Ray shadow_rays[kLanes];
    ShadowQuery shadow[kLanes];
    bool occluded[kLanes];
    int owner[kLanes];  // lane of each shadow ray
    VertexDims dims[kLanes];
    int dim_lanes[kLanes], live_lanes[kLanes];
    float turns[kLanes], az_sin[kLanes], az_cos[kLanes];
    Vec2 azimuth[kLanes];  // turn_azimuth(dims[k].dir.x): the direction samplers' (cos, sin) of 2 pi u.x
    Uninitialised<LightDraw, Variant::kLightDraws ? kLanes : 1> draws;  // each lane's written before it is read
    for (int bounce = 0;; ++bounce) {
      // Closest hits of every live lane (bounce rays in incoherent 16-wide packets unless the batch says not).
      int live = 0;
      for (int k = 0; k < n; ++k) {  // the live lanes listed without a branch (which paths ended is unpredictable)
        live_lanes[live] = k;
        live += alive[k];
      }
      if (live == 0) break;
      counters.rays += live;
      if (bounce == 0 && batch.primary) {
        for (int k = 0; k < n; ++k) {
          found[k] = batch.primary[k] != nullptr;
          if (found[k]) hits[k] = *batch.primary[k];
        }
      } else {
        scene.geometry.intersect_each(rays, live_lanes, live, hits, found, batch.bounce_packets);
      }

      // The sampler dimensions of every lane that may scatter here, side by side (a lane that then cannot
      // scatter ends its path, so the numbers it drew go unused, as they would one lane at a time).
      int n_dims = 0;
      if (bounce < max_depth_)
        for (int k = 0; k < n; ++k) {  // without a branch: which lanes go on is unpredictable
          dim_lanes[n_dims] = k;
          n_dims += alive[k] & found[k];
        }
      Sampler::get_vertex_batch(batch.samplers, dim_lanes, n_dims, dims);
      for (int i = 0; i < n_dims; ++i) turns[i] = dims[dim_lanes[i]].dir.x;
      sincos_turns_many(turns, n_dims, az_sin, az_cos);
      for (int i = 0; i < n_dims; ++i) azimuth[dim_lanes[i]] = {az_cos[i], az_sin[i]};
      if constexpr (Variant::kLightDraws) draw_lights(scene, hits, dim_lanes, n_dims, dims, draws.data());

      // Shade each live lane; its next-event estimate waits in `shadow`.
      int n_shadow = 0;
      for (int i = 0; i < live; ++i) {
        const int k = live_lanes[i];
        bool has_shadow = false;
        alive[k] = shade(scene, bounce, rays[k], found[k], hits[k], beta[k], prev[k], batch.radiance[k], dims[k],
                         azimuth[k], draws[Variant::kLightDraws ? k : 0],
                         bounce == 0 && batch.aov ? &batch.aov[k] : nullptr, shadow[n_shadow], has_shadow, counters);
        owner[n_shadow] = k;
        n_shadow += has_shadow;
      }

      // Shadow rays of this bounce, in packets of 16 (the live lanes' rays are packed together, so every packet
      // but the last is full); a lone ray goes alone.
      if (n_shadow == 0) continue;
      for (int i = 0; i < n_shadow; ++i) shadow_rays[i] = shadow[i].ray;
      for (int first = 0; first < n_shadow; first += kPacket) {
        const int m = std::min(kPacket, n_shadow - first);
        if (batch.shadow_packets && m > 1)
          scene.geometry.occluded16(shadow_rays + first, m, occluded + first);
        else
          for (int i = first; i < first + m; ++i) occluded[i] = scene.geometry.occluded(shadow_rays[i]);
      }
      for (int i = 0; i < n_shadow; ++i)
        if (!occluded[i]) batch.radiance[owner[i]] += shadow[i].value;
    }
  }

 private:
  // One vertex of one lane: emission, AOV, next-event sample (when has_shadow, `shadow` holds it, its value
  // already times beta), continuation (ray, beta, prev updated). Returns whether the path goes on.
  bool shade(const Scene& scene, int bounce, Ray& ray, bool found, const Hit& hit, Color& beta, PathState& prev,
             Color& radiance, const VertexDims& u, Vec2 azimuth, const LightDraw& draw, AovSample* aov,
             ShadowQuery& shadow, bool& has_shadow, PathCounters& counters) const {
    if (!found) {
      if (scene.environment >= 0) {
        const Color le = scene.lights[scene.environment]->le_escaped(ray.d);
        if (!is_black(le))
          radiance += beta * le * variant_.emission_weight(prev, scene, scene.environment, nullptr, ray.d);
      }
      if (aov) *aov = AovSample{Color(0), Vec3(0), 0};
      return false;
    }
    if (hit.light >= 0) {
      const Color le = scene.lights[hit.light]->le(hit, -ray.d);
      if (!is_black(le)) radiance += beta * le * variant_.emission_weight(prev, scene, hit.light, &hit, ray.d);
    }
    // Returned, not passed in: a declared std::optional<Vertex> was zero-filled (152 bytes) at every vertex.
    // The light draw's receiver where draw_lights made one (this lane scatters here), not computed again.
    const bool drawn = Variant::kLightDraws && bounce < max_depth_;
    const std::optional<Vertex> v = make_vertex(scene, hit, ray.d, drawn ? &draw.ctx : nullptr);
    const bool can_scatter = v.has_value();
    if (aov) {
      aov->albedo = hit.material >= 0 ? scene.materials[hit.material]->albedo(hit) : Color(0);
      aov->normal = can_scatter ? v->frame.n : hit.ng;
      // From the camera's position: camera rays start near_clip along their (unit) direction.
      aov->depth = scene.camera.near_clip + hit.t * length(ray.d);
    }
    if (bounce >= max_depth_ || !can_scatter) return false;

    // Dimensions (u, drawn for this vertex in li, as is the light draw): light choice, light position,
    // strategy/lobe choice, direction, roulette (fixed order).
    const float u_choice = u.choice, u_lobe = u.lobe, u_rr = u.rr;
    const Vec2 u_light = u.light, u_dir = u.dir;

    if (std::optional<ShadowQuery> q = variant_.direct(*v, draw, counters)) {
      shadow = {q->ray, beta * q->value};
      has_shadow = true;
    }
    const std::optional<Scatter> s = variant_.scatter(*v, u_choice, u_light, u_lobe, u_dir, azimuth, counters);
    if (!s || is_black(s->weight) || !is_finite(s->weight)) return false;
    beta *= s->weight;
    prev = {false, v->ctx, s->pdf_bsdf};

    // Unbiased Russian roulette: survive with probability q, divide by q.
    if (rr_depth_ > 0 && bounce + 1 >= rr_depth_) {
      const float q = std::min(0.95f, max_component(beta));
      if (u_rr >= q) return false;
      beta /= q;
    }
    // spawn_ray(hit, s->wi) bit for bit, without computing the offset again: every variant scatters to the facing
    // side only (dot(wi, ng) > 0), where light_context's point is spawn_ray's origin.
    ray = {v->ctx.p, s->wi, 0, INFINITY};
    return true;
  }

  int max_depth_, rr_depth_;
  Variant variant_;
  const char* name_;
};

}  // namespace lumis
