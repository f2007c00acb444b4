// Geometry's ray queries: one ray (intersect, occluded, all_light_hits), shadow packets (occluded16), and closest
// hits for many rays: camera packets (intersect_packets, intersect16) and a bounce's rays (intersect_each), traced
// chunk by chunk with their hit records filled in a pipeline behind the tracing.
#include "core/embree_util.h"
#include "core/geometry.h"
#include "core/geometry_impl.h"

#include <algorithm>

namespace lumis {

namespace {

/// Start loading the cache line that holds p: a hint, no effect on any value. Inline assembly on x86-64 because
/// GCC treats __builtin_prefetch as free of side effects: a void function that only reads memory and prefetches,
/// left out of line, is found const by its IPA pure-const pass and every call to it deleted. That is what became
/// of prefetch_hit_record until the thirteenth round (no prefetch instruction in the binary).
inline void prefetch_line(const void* p) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  asm volatile("prefetcht0 (%0)" : : "r"(p));
#else
  __builtin_prefetch(p);
#endif
}

}  // namespace

inline void Geometry::prefetch_hit_record(uint32_t geom_id, uint32_t prim_id) const {
  const Impl::Slot& slot = impl_->slots[geom_id];
  if (!slot.mesh) return;
  // The triangle record (48 bytes: up to two cache lines) and, when fill_hit reads attributes, the triangle's indices.
  const Impl::TriangleRecord* record = slot.records + prim_id;
  prefetch_line(record);
  prefetch_line(reinterpret_cast<const char*>(record) + sizeof(Impl::TriangleRecord) - 1);
  if (slot.has_attributes) prefetch_line(&slot.mesh->indices[3 * size_t(prim_id)]);
}

inline void Geometry::prefetch_hit_attributes(uint32_t geom_id, uint32_t prim_id) const {
  const Impl::Slot& slot = impl_->slots[geom_id];
  if (!slot.has_attributes) return;
  const TriangleMesh& mesh = *slot.mesh;
  const uint32_t* idx = &mesh.indices[3 * size_t(prim_id)];
  for (int j = 0; j < 3; ++j) {
    if (!mesh.normals.empty()) prefetch_line(&mesh.normals[idx[j]]);
    if (!mesh.uv0.empty()) prefetch_line(&mesh.uv0[idx[j]]);
  }
}

void Geometry::intersect_each(const Ray* rays, const int* lanes, int m, Hit* hits, bool* found,
                              bool packets) const {
  int chunk_end[kMaxChunks];
  const int chunks = (m + 15) / 16;
  if (chunks > kMaxChunks) {  // not from the renderer (at most 256 lanes): in parts
    intersect_each(rays, lanes, 16 * kMaxChunks, hits, found, packets);
    intersect_each(rays, lanes + 16 * kMaxChunks, m - 16 * kMaxChunks, hits, found, packets);
    return;
  }
  for (int c = 0; c < chunks; ++c) chunk_end[c] = std::min(16 * (c + 1), m);
  pipeline(rays, lanes, 0, chunk_end, chunks, hits, found, packets ? Trace::Incoherent16 : Trace::Single);
}

void Geometry::intersect_packets(const Ray* rays, const int* packet_end, int n_packets, Hit* hits,
                                 bool* found) const {
  for (int p = 0; p < n_packets; p += kMaxChunks)
    pipeline(rays, nullptr, p ? packet_end[p - 1] : 0, packet_end + p, std::min(kMaxChunks, n_packets - p), hits,
             found, Trace::Coherent16);
}

void Geometry::intersect16(const Ray* rays, int n, Hit* hits, bool* found) const {
  intersect_packets(rays, &n, 1, hits, found);
}

void Geometry::pipeline(const Ray* rays, const int* lanes, int start, const int* chunk_end, int chunks, Hit* hits,
                        bool* found, Trace how) const {
  // Pipelined so that cache misses overlap with Embree's traversal instead of stalling: chunk c is traced and its
  // triangle records (and indices) prefetched; then the shading attributes of chunk c - 1 are prefetched through
  // its indices, loaded by now; then the hits of chunk c - 2 are filled.
  RawHit raw[3][16];
  bool got[3][16];
  const auto first = [&](int c) { return c == 0 ? start : chunk_end[c - 1]; };
  const auto size = [&](int c) { return chunk_end[c] - first(c); };
  if (!impl_->prefetch) {  // records that stay in the cache: each chunk filled as soon as it is traced
    for (int c = 0; c < chunks; ++c) {
      trace16(rays, lanes, first(c), size(c), raw[0], got[0], how, false);
      fill16(rays, lanes, first(c), size(c), raw[0], got[0], hits, found);
    }
    return;
  }
  for (int c = 0; c < chunks + 2; ++c) {
    if (c < chunks) trace16(rays, lanes, first(c), size(c), raw[c % 3], got[c % 3], how, true);
    if (c >= 1 && c - 1 < chunks) {
      const RawHit* r = raw[(c - 1) % 3];
      const bool* g = got[(c - 1) % 3];
      for (int i = 0, n = size(c - 1); i < n; ++i)
        if (g[i]) prefetch_hit_attributes(r[i].geom_id, r[i].prim_id);
    }
    if (c >= 2) fill16(rays, lanes, first(c - 2), size(c - 2), raw[(c - 2) % 3], got[(c - 2) % 3], hits, found);
  }
}

void Geometry::trace16(const Ray* rays, const int* lanes, int first, int m, RawHit* raw, bool* got, Trace how,
                       bool prefetch) const {
  const auto lane = [&](int i) { return lanes ? lanes[first + i] : first + i; };
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  QueryLog* const log = t_query_log;
  // One packet; a lone incoherent ray goes alone, below.
  if (how == Trace::Coherent16 || (how == Trace::Incoherent16 && m > 1)) {
    if (how == Trace::Coherent16) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) RTCRayHit16 p;
    alignas(64) int valid[16];
    for (int i = 0; i < 16; ++i) {
      const bool ok = i < m && ray_is_valid(rays[lane(i)]);
      valid[i] = ok ? -1 : 0;
      to_embree16(ok ? rays[lane(i)] : Ray{{0, 0, 0}, {0, 0, 1}, 0, 0}, p, i);
    }
    if (log) [[unlikely]] {
      Ray packet[16];
      for (int i = 0; i < m; ++i) packet[i] = rays[lane(i)];
      log->add(how == Trace::Coherent16 ? QueryLog::Call::Intersect16 : QueryLog::Call::Intersect16Incoherent,
               packet, m);
    }
    rtcIntersect16(valid, impl_->scene, &ctx, &p);
    for (int i = 0; i < m; ++i) {
      got[i] = valid[i] && p.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
      if (got[i]) raw[i] = {p.hit.geomID[i], p.hit.primID[i], p.hit.u[i], p.hit.v[i], p.ray.tfar[i]};
    }
    if (prefetch)
      for (int i = 0; i < m; ++i)
        if (got[i]) prefetch_hit_record(raw[i].geom_id, raw[i].prim_id);
    return;
  }
  for (int i = 0; i < m; ++i) {
    const Ray& ray = rays[lane(i)];
    got[i] = false;
    if (!ray_is_valid(ray)) continue;
    if (log) [[unlikely]] log->add(QueryLog::Call::Intersect1, &ray, 1);
    RTCRayHit rh = to_embree(ray);
    rtcIntersect1(impl_->scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    got[i] = true;
    raw[i] = {rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar};
    if (prefetch) prefetch_hit_record(raw[i].geom_id, raw[i].prim_id);  // as soon as the ray is traced
  }
}

void Geometry::fill16(const Ray* rays, const int* lanes, int first, int m, const RawHit* raw, const bool* got,
                      Hit* hits, bool* found) const {
  for (int i = 0; i < m; ++i) {
    const int k = lanes ? lanes[first + i] : first + i;
    found[k] = got[i];
    if (!got[i]) continue;
    Hit& hit = hits[k];
    hit.t = raw[i].t;
    hit.p = rays[k].o + rays[k].d * hit.t;
    fill_hit(raw[i].geom_id, raw[i].prim_id, raw[i].u, raw[i].v, hit);
    hit.front = dot(rays[k].d, hit.ng) < 0;
  }
}

void Geometry::record_queries(QueryLog* log) { t_query_log = log; }

bool Geometry::intersect(const Ray& ray, Hit& hit) const {
  if (!ray_is_valid(ray)) return false;
  if (QueryLog* log = t_query_log) [[unlikely]] log->add(QueryLog::Call::Intersect1, &ray, 1);
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = to_embree(ray);
  rtcIntersect1(impl_->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit.t = rh.ray.tfar;
  hit.p = ray.o + ray.d * hit.t;
  fill_hit(rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, hit);
  hit.front = dot(ray.d, hit.ng) < 0;
  return true;
}

bool Geometry::occluded(const Ray& ray) const {
  if (!ray_is_valid(ray)) return true;
  if (QueryLog* log = t_query_log) [[unlikely]] log->add(QueryLog::Call::Occluded1, &ray, 1);
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r = to_embree(ray).ray;
  rtcOccluded1(impl_->scene, &ctx, &r);
  return r.tfar < 0;  // Embree sets tfar = -inf on an occluded ray
}

void Geometry::occluded16(const Ray* rays, int n, bool* occluded) const {
  if (QueryLog* log = t_query_log) [[unlikely]] log->add(QueryLog::Call::Occluded16, rays, n);
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  alignas(64) RTCRayHit16 p;
  alignas(64) int valid[16];
  to_embree16(rays, n, p, valid);
  rtcOccluded16(valid, impl_->scene, &ctx, reinterpret_cast<RTCRay16*>(&p.ray));
  for (int i = 0; i < n; ++i) occluded[i] = !valid[i] || p.ray.tfar[i] < 0;  // invalid: as occluded() says
}

namespace {
struct CollectContext {
  RTCIntersectContext base;  // first member: Embree passes &base to the filter
  LightHitRecord* out;
  int max_hits, count;
};

void collect_filter(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<CollectContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (ctx->count < ctx->max_hits)
      ctx->out[ctx->count] = {RTCHitN_geomID(args->hit, args->N, i), RTCHitN_primID(args->hit, args->N, i),
                              RTCRayN_tfar(args->ray, args->N, i), RTCHitN_u(args->hit, args->N, i),
                              RTCHitN_v(args->hit, args->N, i)};
    ++ctx->count;
    args->valid[i] = 0;  // reject, so traversal goes on to every other hit
  }
}
}  // namespace

int Geometry::all_light_hits(const Ray& ray, LightHitRecord* out, int max_hits) const {
  if (!ray_is_valid(ray)) return 0;
  if (QueryLog* log = t_query_log) [[unlikely]] log->add(QueryLog::Call::LightHits, &ray, 1);
  CollectContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.base.filter = collect_filter;
  ctx.out = out;
  ctx.max_hits = max_hits;
  ctx.count = 0;
  RTCRayHit rh = to_embree(ray);
  rtcIntersect1(impl_->light_scene, &ctx.base, &rh);
  return ctx.count;
}

}  // namespace lumis
