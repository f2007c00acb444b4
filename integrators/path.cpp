#include "integrators/path_vertex.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "materials/shading.h"

namespace lumis {

float mis_weight(float pdf_a, float pdf_b, MisHeuristic heuristic) {
  if (heuristic == MisHeuristic::Power) {
    // Squared in double: a float density above 1.8e19 (a light smaller than 1e-10 of its distance) overflows
    // float when squared, which made both weights 0 and dropped the light.
    const double a = double(pdf_a) * pdf_a, b = double(pdf_b) * pdf_b;
    const double w = a / (a + b);
    return std::isfinite(w) ? static_cast<float>(w) : 0.0f;
  }
  const float w = pdf_a / (pdf_a + pdf_b);
  return std::isfinite(w) ? w : 0.0f;
}

std::optional<Vertex> make_vertex(const Scene& scene, const Hit& hit, Vec3 ray_dir, const LightSampleContext* ctx) {
  if (hit.material < 0) return std::nullopt;
  ShadingPoint sp = scene.materials[hit.material]->shade(hit);
  Frame frame = sp.frame;
  const Vec3 ng = facing_ng(hit);
  if (!hit.front) frame = Frame(frame.s, -frame.t, -frame.n);  // two-sided shading: the surface faces the ray
  const Vec3 wo_world = -normalize_unless_unit(ray_dir);  // bounce rays' directions are unit already
  // Shading-normal rule 3 (materials/shading.h): a shading normal that hides wo, or mirrors it below the geometric
  // surface, is bent toward ng just enough that neither happens (without it, glossy normal-mapped surfaces turn
  // black at grazing angles). Flat geometry (shading normal = ng) never needs it.
  if (!(frame.n == ng)) frame = adapt_shading_frame(frame, ng, wo_world);
  Vec3 wo = frame.to_local(wo_world);
  // What rule 3 cannot fix (wo grazing the geometric surface itself): shade with the geometric normal.
  if (!(wo.z > 1e-6f)) {
    frame = Frame::from_normal(ng);
    wo = frame.to_local(wo_world);
    if (!(wo.z > 0)) return std::nullopt;
  }
  // Built in place (see LightSample in lights/light.h): copied from a temporary, store-forwarding stalls were 65 %
  // of this function's time.
  return std::make_optional<Vertex>(scene, hit, frame, ng, sp.bsdf, wo, ctx ? *ctx : light_context(hit));
}

void draw_lights(const Scene& scene, const Hit* hits, const int* lanes, int m, const VertexDims* dims,
                 LightDraw* out) {
  constexpr int kLanes = PathBatch::kMaxLanes;
  m = std::min(m, kLanes);
  if (m <= 0) return;
  // Scratch written before it is read, left uninitialised (as arrays of these types, tens of kilobytes per call
  // would be zeroed by their member initialisers).
  Uninitialised<LightSampleContext, kLanes> ctx, group_ctx;
  Uninitialised<Vec2, kLanes> group_u;
  Uninitialised<LightChoice, kLanes> choice;
  Uninitialised<LightSample, kLanes> samples;
  float u_choice[kLanes];
  for (int i = 0; i < m; ++i) {
    const Hit& hit = hits[lanes[i]];
    ctx[i] = light_context(hit);
    u_choice[i] = dims[lanes[i]].choice;
  }
  scene.light_selector.sample_many(ctx.data(), u_choice, m, choice.data());
  // Each light samples its receivers together: the lanes grouped by the light chosen (lane order kept within a
  // light), their receivers and numbers gathered. `order` lists them light by light, from start[light].
  const int n_lights = static_cast<int>(scene.lights.size());
  int order[kLanes], start[kLanes + 1];
  if (n_lights > kLanes) {  // many lights: one receiver at a time
    for (int i = 0; i < m; ++i) {
      LightDraw& d = out[lanes[i]];
      d.ctx = ctx[i];
      d.choice = choice[i];
      const std::optional<LightSample> ls =
          choice[i].index >= 0 ? scene.lights[choice[i].index]->sample(ctx[i], dims[lanes[i]].light) : std::nullopt;
      d.ok = ls.has_value();
      if (d.ok) d.sample = *ls;
    }
    return;
  }
  if (n_lights == 1) {
    start[0] = 0;
    start[1] = 0;
    for (int i = 0; i < m; ++i) {  // without a branch, as the path loop lists its lanes
      order[start[1]] = i;
      start[1] += choice[i].index == 0;
    }
  } else {  // counting sort by light
    std::fill(start, start + n_lights + 1, 0);
    for (int i = 0; i < m; ++i)
      if (choice[i].index >= 0) ++start[choice[i].index + 1];
    for (int j = 0; j < n_lights; ++j) start[j + 1] += start[j];
    int next[kLanes];
    std::copy(start, start + n_lights, next);
    for (int i = 0; i < m; ++i)
      if (choice[i].index >= 0) order[next[choice[i].index]++] = i;
  }
  for (int i = 0; i < m; ++i) {
    out[lanes[i]].ctx = ctx[i];
    out[lanes[i]].choice = choice[i];
    out[lanes[i]].ok = false;
  }
  bool ok[kLanes];
  for (int j = 0; j < n_lights; ++j) {
    const int first = start[j], count = start[j + 1] - first;
    if (count == 0) continue;
    for (int g = 0; g < count; ++g) {
      const int i = order[first + g];
      group_ctx[g] = ctx[i];
      group_u[g] = dims[lanes[i]].light;
    }
    scene.lights[j]->sample_many(group_ctx.data(), group_u.data(), count, samples.data(), ok);
    for (int g = 0; g < count; ++g) {
      LightDraw& d = out[lanes[order[first + g]]];
      d.ok = ok[g];
      if (ok[g]) d.sample = samples[g];
    }
  }
}

std::optional<ShadowQuery> sample_direct(const Vertex& v, const LightDraw& draw, bool mis_weighted,
                                        MisHeuristic heuristic, PathCounters& counters) {
  if (draw.choice.index < 0 || !draw.ok) return std::nullopt;
  const LightSample& ls = draw.sample;
  if (!(ls.pdf > 0) || is_black(ls.le)) return std::nullopt;
  // Shading-normal rule: light arriving from below the geometric surface does not reflect (no light leaks).
  if (dot(ls.wi, v.ng) <= 0) return std::nullopt;
  const Vec3 wi = v.frame.to_local(ls.wi);
  const BsdfEval e = v.bsdf.eval(v.wo, wi);
  if (is_black(e.f)) return std::nullopt;
  ++counters.rays;
  ++counters.shadow_rays;
  const float pdf_light = draw.choice.pmf * ls.pdf;
  const float w = mis_weighted ? mis_weight(pdf_light, e.pdf, heuristic) : 1.0f;
  return std::make_optional<ShadowQuery>(
      // From v.ctx.p: spawn_ray's origin toward wi, which is on the facing side (light_context), computed once.
      std::isinf(ls.dist) ? Ray{v.ctx.p, ls.wi, 0, INFINITY}
                          : shadow_ray(v.ctx.p, ls.p_light, ls.n_light, ls.p_error),
      e.f * ls.le * (std::abs(wi.z) * w / pdf_light));
}

float light_pdf_for_hit(const Scene& scene, const LightSampleContext& ctx, int light, const Hit* on_light, Vec3 dir) {
  const float pmf = scene.light_selector.pmf(ctx, light);
  if (!(pmf > 0)) return 0;
  static const Hit kNoHit;
  return pmf * scene.lights[light]->pdf(ctx, normalize(dir), on_light ? *on_light : kNoHit);
}

float light_strategy_pdf(const Scene& scene, const Hit& from, const LightSampleContext& ctx, Vec3 wi,
                         PathCounters& counters) {
  float pdf = 0;
  if (scene.environment >= 0) pdf += light_pdf_for_hit(scene, ctx, scene.environment, nullptr, wi);
  // Up to kMaxHits crossings of light surfaces on the stack; a direction through more (a row of 40 sphere lights)
  // queries again with room for all of them, since each one missed would make the mixture density too small.
  constexpr int kMaxHits = 64;
  LightHitRecord stack_hits[kMaxHits];
  uint32_t stack_spheres[kMaxHits];
  const LightHitRecord* hits = stack_hits;
  uint32_t* spheres_seen = stack_spheres;
  std::vector<LightHitRecord> heap_hits;
  std::vector<uint32_t> heap_spheres;
  const Ray ray = spawn_ray(from, wi);
  ++counters.rays;
  ++counters.light_queries;
  int n = scene.geometry.all_light_hits(ray, stack_hits, kMaxHits);
  if (n > kMaxHits) [[unlikely]] {
    heap_hits.resize(static_cast<size_t>(n));
    heap_spheres.resize(static_cast<size_t>(n));
    ++counters.rays;
    ++counters.light_queries;
    n = std::min(n, scene.geometry.all_light_hits(ray, heap_hits.data(), n));
    hits = heap_hits.data();
    spheres_seen = heap_spheres.data();
  }
  int n_spheres = 0;
  for (int i = 0; i < n; ++i) {
    const LightHitRecord& r = hits[i];
    // A sphere's density is per direction: its near and far intersections count once.
    if (!scene.geometry.is_mesh(r.geom_id)) {
      bool seen = false;
      for (int k = 0; k < n_spheres; ++k) seen |= spheres_seen[k] == r.geom_id;
      if (seen) continue;
      spheres_seen[n_spheres++] = r.geom_id;
    }
    Hit h;
    h.p = ray.o + ray.d * r.t;
    h.t = r.t;
    scene.geometry.fill_hit(r.geom_id, r.prim_id, r.u, r.v, h);
    h.front = dot(wi, h.ng) < 0;
    pdf += light_pdf_for_hit(scene, ctx, h.light, &h, wi);
  }
  return pdf;
}

std::optional<Scatter> scatter_bsdf(const Vertex& v, float u_lobe, Vec2 u, Vec2 azimuth) {
  const std::optional<BsdfSample> bs = v.bsdf.sample(v.wo, u_lobe, u, azimuth);
  if (!bs || !(bs->pdf > 0)) return std::nullopt;
  const Vec3 wi = v.frame.to_world(bs->wi);
  if (dot(wi, v.ng) <= 0) return std::nullopt;  // through the geometric surface: no contribution
  return std::make_optional<Scatter>(wi, bs->f * (std::abs(bs->wi.z) / bs->pdf), bs->pdf);
}

}  // namespace lumis
