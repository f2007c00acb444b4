// Embree's own time for exactly the rays a render traced: the render's query logs (RenderOptions::query_logs, one
// per tile) are traced again with nothing around them, one task per tile as the render divides its work. Two ways:
// as the render called Embree (its packets), and with every ray as a single-ray call (the basis of `ratio`).
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>

#include "app/bench.h"
#include "core/embree_util.h"

namespace lumis {

namespace {

// A 16-wide packet of rays[0..n) as Geometry::intersect16 / intersect_each / occluded16 build it (invalid and
// unused lanes masked off, with a finite ray); returns the number of hits (occluded rays).
size_t trace_packet(RTCScene scene, const Ray* rays, int n, bool occlusion, bool coherent) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  if (coherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // camera packets, as intersect16
  alignas(64) RTCRayHit16 p;
  alignas(64) int valid[16];
  to_embree16(rays, n, p, valid);
  size_t count = 0;
  if (occlusion) {
    rtcOccluded16(valid, scene, &ctx, reinterpret_cast<RTCRay16*>(&p.ray));
    for (int i = 0; i < n; ++i) count += valid[i] && p.ray.tfar[i] < 0;
  } else {
    rtcIntersect16(valid, scene, &ctx, &p);
    for (int i = 0; i < n; ++i) count += valid[i] && p.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
  }
  return count;
}

size_t trace_single(RTCScene scene, const Ray& ray, bool occlusion) {
  if (!ray_is_valid(ray)) return 0;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = to_embree(ray);
  if (occlusion) {
    rtcOccluded1(scene, &ctx, &rh.ray);
    return rh.ray.tfar < 0;
  }
  rtcIntersect1(scene, &ctx, &rh);
  return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

size_t replay_log(const Geometry& g, const QueryLog& log, bool single_rays, std::optional<RayKind> only) {
  const RTCScene scene = static_cast<RTCScene>(g.embree_scene());
  using Call = QueryLog::Call;
  size_t count = 0;
  LightHitRecord light_hits[64];
  for (const QueryLog::Entry& e : log.calls) {
    if (only && ray_kind(e.call) != *only) continue;
    const Ray* r = &log.rays[e.first];
    const bool occlusion = e.call == Call::Occluded1 || e.call == Call::Occluded16;
    if (!single_rays && (e.call == Call::Intersect16 || e.call == Call::Intersect16Incoherent ||
                         e.call == Call::Occluded16)) {
      count += trace_packet(scene, r, e.n, occlusion, e.call == Call::Intersect16);
    } else if (e.call == Call::LightHits) {
      for (int i = 0; i < e.n; ++i) count += g.all_light_hits(r[i], light_hits, 64) > 0;
    } else {
      for (int i = 0; i < e.n; ++i) count += trace_single(scene, r[i], occlusion);
    }
  }
  return count;
}

}  // namespace

RayKind ray_kind(QueryLog::Call call) {
  using Call = QueryLog::Call;
  switch (call) {
    case Call::Intersect16: return RayKind::Camera;
    case Call::Intersect1:
    case Call::Intersect16Incoherent: return RayKind::Bounce;
    case Call::Occluded1:
    case Call::Occluded16: return RayKind::Shadow;
    case Call::LightHits: return RayKind::LightQuery;
  }
  return RayKind::Bounce;
}

ReplayTiming replay_queries(const Geometry& g, const std::vector<QueryLog>& logs, int threads, bool single_rays,
                            std::optional<RayKind> only) {
  const TracingFloatMode float_mode;  // before the arena: it takes the mode it is initialized in
  tbb::task_arena arena(std::max(1, threads));
  ReplayTiming out;
  for (const QueryLog& log : logs)
    for (const QueryLog::Entry& e : log.calls)
      if (!only || ray_kind(e.call) == *only) out.rays += e.n;
  std::vector<size_t> counts(logs.size());
  const auto t0 = std::chrono::steady_clock::now();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, logs.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) counts[i] = replay_log(g, logs[i], single_rays, only);
    });
  });
  out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const size_t c : counts) out.hits += c;
  return out;
}

}  // namespace lumis
