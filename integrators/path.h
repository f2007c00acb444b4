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
#include "integrators/path_vertex.h"

namespace lumis {

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
