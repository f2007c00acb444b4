// Embree's raw throughput on a scene's own BVH: the rays are made first (from the scene's camera, hit points and
// lights), then only the Embree calls are timed, over all threads, as the renderer would issue them.
#include <sys/resource.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

#include "app/bench.h"
#include "core/embree_util.h"
#include "core/frame.h"
#include "core/rng.h"
#include "core/warp.h"
#include "integrators/path.h"

namespace lumis {

namespace {

constexpr size_t kGrain = 1024;  // rays per task: large enough that scheduling costs nothing measurable

enum class Query { Intersect, Occluded };

// One timing of fn over n rays in tasks of kGrain rays, the whole set traced again until min_seconds have passed
// (the same rays in the same order, so their locality is that of one pass; a single pass of a fast kind takes tens
// of milliseconds, which one scheduling hiccup can spoil). fn returns a count (hits or occluded rays) so that the
// fraction can be checked.
Rate time_rays(tbb::task_arena& arena, double min_seconds, size_t n, const std::function<size_t(size_t, size_t)>& fn,
               double* fraction = nullptr) {
  if (n == 0) return {};
  const TracingFloatMode float_mode;
  std::atomic<size_t> count{0};
  const double c0 = process_cpu_seconds();
  const auto t0 = std::chrono::steady_clock::now();
  size_t passes = 0;
  double wall = 0;
  do {
    arena.execute([&] {
      tbb::parallel_for(size_t(0), (n + kGrain - 1) / kGrain,
                        [&](size_t c) { count += fn(c * kGrain, std::min(n, (c + 1) * kGrain)); });
    });
    ++passes;
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  } while (wall < min_seconds);
  const double cpu = process_cpu_seconds() - c0;
  const double rays = double(n) * double(passes);
  if (fraction) *fraction = double(count.load()) / rays;
  return {rays / std::max(wall, 1e-9), rays / std::max(cpu, 1e-6)};
}

size_t trace1(RTCScene scene, const std::vector<Ray>& rays, size_t begin, size_t end, Query q) {
  size_t count = 0;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (size_t i = begin; i < end; ++i) {
    if (q == Query::Intersect) {
      RTCRayHit rh = to_embree(rays[i]);
      rtcIntersect1(scene, &ctx, &rh);
      count += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    } else {
      RTCRay r = to_embree(rays[i]).ray;
      rtcOccluded1(scene, &ctx, &r);
      count += r.tfar < 0;
    }
  }
  return count;
}

// Packets of 16 consecutive rays (tasks are kGrain rays, a multiple of 16, so only the very last packet can be
// partial: its tail lanes are masked off).
size_t trace16(RTCScene scene, const std::vector<Ray>& rays, size_t begin, size_t end, Query q, bool coherent) {
  size_t count = 0;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  alignas(64) RTCRayHit16 p;
  alignas(64) int valid[16];
  for (size_t i = begin; i < end; i += 16) {
    const int lanes = int(std::min<size_t>(16, end - i));
    for (int k = 0; k < 16; ++k) {
      valid[k] = k < lanes ? -1 : 0;
      to_embree16(rays[i + std::min(k, lanes - 1)], p, k);
    }
    if (q == Query::Intersect) {
      rtcIntersect16(valid, scene, &ctx, &p);
      for (int k = 0; k < lanes; ++k) count += p.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    } else {
      rtcOccluded16(valid, scene, &ctx, reinterpret_cast<RTCRay16*>(&p.ray));
      for (int k = 0; k < lanes; ++k) count += p.ray.tfar[k] < 0;
    }
  }
  return count;
}

}  // namespace

double process_cpu_seconds() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct RawBench::Impl {
  const Scene& scene;
  tbb::task_arena arena;
  std::vector<Ray> cam, bounce, shadow;
  std::vector<Ray> bounce_shuffled, shadow_shuffled;  // the same rays in a random order
  double min_seconds;
  Impl(const Scene& s, int threads, double min_s) : scene(s), arena(std::max(1, threads)), min_seconds(min_s) {}
};

RawBench::~RawBench() = default;

RawBench::RawBench(const Scene& scene, int width, int height, int threads, size_t n_rays, double min_seconds)
    : impl_(std::make_unique<Impl>(scene, threads, min_seconds)) {
  // Camera rays in 4x4 pixel blocks, all samples of a block together: a packet is 16 neighbouring pixels, as a
  // packet tracer would form them; render() visits pixels in the same tile-local order.
  Camera camera = scene.camera;
  camera.prepare(width, height);
  const size_t pixels = size_t(width) * size_t(height);
  const uint32_t spp = uint32_t(std::max<size_t>(1, (n_rays + pixels - 1) / pixels));
  std::vector<Ray>& cam = impl_->cam;
  cam.reserve(pixels * spp);
  Pcg32 rng(7, 11);
  for (int by = 0; by < height; by += 4)
    for (int bx = 0; bx < width; bx += 4)
      for (uint32_t s = 0; s < spp; ++s)
        for (int y = by; y < std::min(by + 4, height); ++y)
          for (int x = bx; x < std::min(bx + 4, width); ++x)
            cam.push_back(camera.generate_ray({x + rng.next_float(), y + rng.next_float()}));

  // Bounce and shadow rays from the points the camera rays hit, one each per hit point that can scatter, in
  // camera-ray order (as the integrator issues them). Made in parallel with a seed per chunk.
  const size_t chunks = (cam.size() + kGrain - 1) / kGrain;
  std::vector<std::vector<Ray>> bounce_parts(chunks), shadow_parts(chunks);
  const TracingFloatMode float_mode;
  impl_->arena.execute([&] {
    tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
      Pcg32 r(hash_combine(c, 3), 5);
      for (size_t i = c * kGrain; i < std::min(cam.size(), (c + 1) * kGrain); ++i) {
        Hit hit;
        if (!scene.geometry.intersect(cam[i], hit) || hit.material < 0) continue;
        const Vec3 ng = hit.front ? hit.ng : -hit.ng;  // toward the camera
        const Vec3 wi = Frame::from_normal(ng).to_world(sample_cosine_hemisphere({r.next_float(), r.next_float()}));
        const Ray b = spawn_ray(hit, wi);
        if (is_finite(b.d) && length_squared(b.d) > 0) bounce_parts[c].push_back(b);
        const LightSampleContext ctx = light_context(hit);  // as the integrators sample lights
        const std::optional<LightChoice> choice = scene.light_selector.sample(ctx, r.next_float());
        if (!choice) continue;
        const std::optional<LightSample> ls =
            scene.lights[choice->index]->sample(ctx, {r.next_float(), r.next_float()});
        if (!ls || !(ls->pdf > 0) || dot(ls->wi, ng) <= 0) continue;
        const Ray s = std::isinf(ls->dist) ? spawn_ray(hit, ls->wi)
                                           : spawn_ray_to(hit, ls->p_light, ls->n_light, ls->p_error);
        if (is_finite(s.o) && is_finite(s.d)) shadow_parts[c].push_back(s);
      }
    });
  });
  for (size_t c = 0; c < chunks; ++c) {
    impl_->bounce.insert(impl_->bounce.end(), bounce_parts[c].begin(), bounce_parts[c].end());
    impl_->shadow.insert(impl_->shadow.end(), shadow_parts[c].begin(), shadow_parts[c].end());
  }
  // The same rays in a random order (Fisher-Yates, fixed seed): no two rays in a row share a pixel block.
  Pcg32 order(13, 17);
  const auto shuffled = [&](std::vector<Ray> v) {
    for (size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[order.next_u32() % uint32_t(i)]);
    return v;
  };
  impl_->bounce_shuffled = shuffled(impl_->bounce);
  impl_->shadow_shuffled = shuffled(impl_->shadow);
}

RawThroughput RawBench::measure() {
  Impl& m = *impl_;
  const RTCScene rtc = static_cast<RTCScene>(m.scene.geometry.embree_scene());
  const std::vector<Ray>&cam = m.cam, &bounce = m.bounce, &shadow = m.shadow;
  RawThroughput out;
  out.camera_rays = cam.size();
  out.bounce_rays = bounce.size();
  out.shadow_rays = shadow.size();
  using Range = std::function<size_t(size_t, size_t)>;
  out.camera1 = time_rays(m.arena, m.min_seconds, cam.size(), Range([&](size_t b, size_t e) {
                            return trace1(rtc, cam, b, e, Query::Intersect);
                          }),
                          &out.camera_hit_fraction);
  out.camera16 = time_rays(m.arena, m.min_seconds, cam.size(), Range([&](size_t b, size_t e) {
                             return trace16(rtc, cam, b, e, Query::Intersect, true);
                           }));
  out.bounce1 = time_rays(m.arena, m.min_seconds, bounce.size(), Range([&](size_t b, size_t e) {
                            return trace1(rtc, bounce, b, e, Query::Intersect);
                          }),
                          &out.bounce_hit_fraction);
  out.bounce16 = time_rays(m.arena, m.min_seconds, bounce.size(), Range([&](size_t b, size_t e) {
                             return trace16(rtc, bounce, b, e, Query::Intersect, false);
                           }));
  out.shadow1 = time_rays(m.arena, m.min_seconds, shadow.size(), Range([&](size_t b, size_t e) {
                            return trace1(rtc, shadow, b, e, Query::Occluded);
                          }),
                          &out.shadow_occluded_fraction);
  out.shadow16 = time_rays(m.arena, m.min_seconds, shadow.size(), Range([&](size_t b, size_t e) {
                             return trace16(rtc, shadow, b, e, Query::Occluded, false);
                           }));
  out.bounce1_shuffled = time_rays(m.arena, m.min_seconds, bounce.size(), Range([&](size_t b, size_t e) {
                                     return trace1(rtc, m.bounce_shuffled, b, e, Query::Intersect);
                                   }));
  out.shadow1_shuffled = time_rays(m.arena, m.min_seconds, shadow.size(), Range([&](size_t b, size_t e) {
                                     return trace1(rtc, m.shadow_shuffled, b, e, Query::Occluded);
                                   }));
  const Geometry& g = m.scene.geometry;
  out.bounce_lumis = time_rays(m.arena, m.min_seconds, bounce.size(), Range([&](size_t b, size_t e) {
                                 size_t found = 0;
                                 for (size_t i = b; i < e; ++i) {
                                   Hit h;
                                   found += g.intersect(bounce[i], h);
                                 }
                                 return found;
                               }));
  out.light_query = time_rays(m.arena, m.min_seconds, bounce.size(), Range([&](size_t b, size_t e) {
                                LightHitRecord hits[64];
                                size_t found = 0;
                                for (size_t i = b; i < e; ++i) found += g.all_light_hits(bounce[i], hits, 64) > 0;
                                return found;
                              }));
  return out;
}

}  // namespace lumis
