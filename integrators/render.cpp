#include "integrators/render.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <memory>
#include <thread>

#include "core/embree_util.h"
#include "core/rng.h"

namespace lumis {

namespace {

// A tile is one PathBatch: 16x16 pixels, their camera rays as rtcIntersect16 packets of 4x4 pixels.
constexpr int kTile = 16, kLanes = PathBatch::kMaxLanes, kPacketSide = 4;
static_assert(kTile * kTile == kLanes && kPacketSide * kPacketSide == PathBatch::kPacket && kTile % kPacketSide == 0);

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Where pixel sample i of a render with a time budget comes from, for the stratified sampler: sample `index` of a
/// Sampler(stratified, spp, seed). The count is not known in advance, and one stratified set sized for the 2^20
/// samples a budget allows would spread the few taken over a random handful of its strata, no better than
/// independent samples. Instead sample i belongs to block p = floor(log2(i + 1)), a stratified set of 2^p samples
/// with a seed of its own: blocks of 1, 2, 4, 8, ... samples, so whatever count the render stops at, its whole
/// blocks, about half of its samples or more, are complete stratified sets.
struct BlockSample {
  uint32_t block, spp, seed, index;
};
BlockSample doubling_block(uint32_t i, uint32_t seed) {
  const uint32_t p = static_cast<uint32_t>(std::bit_width(uint64_t{i} + 1)) - 1;
  const uint32_t size = 1u << p;
  return {p, size, static_cast<uint32_t>(hash_combine(seed, 0x6c756d6973000000ULL + p)), i + 1 - size};
}

}  // namespace

RenderStats render(const Scene& scene, const Integrator& integrator, Film& film, const RenderOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const int width = film.width(), height = film.height();
  const int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
  const int n_tiles = tiles_x * tiles_y;
  // TBB runs at most one thread per core whatever the arena asks for (and warns on stderr when asked for more):
  // more threads than cores are capped here. The image does not depend on the thread count.
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int threads = options.threads > 0 ? std::min(options.threads, cores) : cores;
  const TracingFloatMode float_mode;  // before the arena: it takes the mode it is initialized in
  tbb::task_arena arena(threads);
  Camera camera = scene.camera;
  camera.prepare(width, height);
  const SamplerType sampler_type = scene.settings.sampler;
  const uint32_t seed = scene.settings.seed;
  const uint32_t spp = std::max(1u, options.spp);
  const bool packets = options.camera_packets;
  const bool doubling = options.time_budget > 0 && sampler_type == SamplerType::Stratified;  // doubling_block

  if (options.query_logs) options.query_logs->assign(static_cast<size_t>(n_tiles), QueryLog{});
  tbb::enumerable_thread_specific<PathCounters> counters;
  RenderStats stats;
  uint32_t done = 0;
  uint32_t pass = 1;  // samples per pixel in the next pass; grows so that passes take about half a second
  const uint64_t pixels = static_cast<uint64_t>(width) * height;
  std::atomic<int> pass_sync{0};
  while (done < spp) {
    if (options.cancel && options.cancel->load()) break;
    const uint32_t begin = done, end = std::min(spp, done + pass);
    const auto pass_start = std::chrono::steady_clock::now();
    // An explicit release/acquire handshake around each pass: TBB's join is invisible to ThreadSanitizer (TBB is
    // not instrumented), and without it the main thread's reuse of these locals looks like a race.
    pass_sync.store(0, std::memory_order_release);
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, n_tiles, 1), [&](const tbb::blocked_range<int>& r) {
        pass_sync.load(std::memory_order_acquire);
        PathCounters& local = counters.local();
        // A tile of pixels shares each sample index: their paths form one PathBatch. Each pixel keeps its own
        // sampler, so the numbers (and the image) are those of one-by-one tracing.
        Sampler samplers[kLanes];
        for (Sampler& s : samplers) s = Sampler(sampler_type, spp, seed);
        uint32_t samplers_block = UINT32_MAX;  // doubling: the block `samplers` are made for
        Ray rays[kLanes];
        const Hit* primary[kLanes];
        Hit hits[kLanes];
        bool found[kLanes];
        AovSample aov[kLanes];
        Color radiance[kLanes];
        Vec2 jitter[kLanes];
        PathBatch batch;
        batch.rays = rays;
        batch.primary = packets ? primary : nullptr;
        batch.samplers = samplers;
        batch.aov = film.has_aovs() ? aov : nullptr;  // first-hit albedo costs a material lookup per sample
        batch.radiance = radiance;
        batch.shadow_packets = options.shadow_packets;
        batch.bounce_packets = options.bounce_packets;
        for (int tile = r.begin(); tile < r.end(); ++tile) {
          const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
          const int x1 = std::min(x0 + kTile, width), y1 = std::min(y0 + kTile, height);
          if (options.query_logs) Geometry::record_queries(&(*options.query_logs)[static_cast<size_t>(tile)]);
          // The tile's pixels (clipped to the image) as lanes, 4x4 block by block: each block's camera rays are
          // one coherent packet.
          int px[kLanes], py[kLanes], packet_end[kLanes / PathBatch::kPacket];
          int n = 0, n_packets = 0;
          for (int sy = y0; sy < y1; sy += kPacketSide)
            for (int sx = x0; sx < x1; sx += kPacketSide) {
              for (int y = sy; y < std::min(sy + kPacketSide, y1); ++y)
                for (int x = sx; x < std::min(sx + kPacketSide, x1); ++x) px[n] = x, py[n++] = y;
              packet_end[n_packets++] = n;
            }
          batch.n = n;
          for (uint32_t i = begin; i < end; ++i) {
            uint32_t index = i;
            if (doubling) {
              const BlockSample b = doubling_block(i, seed);
              if (b.block != samplers_block)
                for (Sampler& s : samplers) s = Sampler(sampler_type, b.spp, b.seed);
              samplers_block = b.block;
              index = b.index;
            }
            Sampler::start_batch(samplers, n, px, py, index, jitter);  // box filter: uniform over the pixel
            for (int k = 0; k < n; ++k) rays[k] = camera.generate_ray({px[k] + jitter[k].x, py[k] + jitter[k].y});
            if (packets) {
              scene.geometry.intersect_packets(rays, packet_end, n_packets, hits, found);
              for (int k = 0; k < n; ++k) primary[k] = found[k] ? &hits[k] : nullptr;
            }
            integrator.li(scene, batch, local);
            for (int k = 0; k < n; ++k) film.add(px[k], py[k], radiance[k], batch.aov ? &aov[k] : nullptr);
          }
          if (options.query_logs) Geometry::record_queries(nullptr);
        }
        pass_sync.fetch_add(1, std::memory_order_release);
      });
    });
    pass_sync.load(std::memory_order_acquire);
    done = end;
    stats.samples += pixels * (end - begin);
    const double pass_seconds = seconds_since(pass_start);
    if (options.on_progress) options.on_progress({done * pixels, spp * pixels, seconds_since(t0), options.time_budget});
    if (options.time_budget > 0 && seconds_since(t0) >= options.time_budget) break;
    // Next pass: aim at ~0.5 s, and at a quarter of what is left of a time budget, so that a pass whose speed was
    // over-estimated (the first one, with cold caches or warm threads) overshoots the budget by little.
    const double per_sample = pass_seconds / std::max(1u, end - begin);
    double target = 0.5;
    if (options.time_budget > 0)
      target = std::min(target, std::max(0.0, 0.25 * (options.time_budget - seconds_since(t0))));
    pass = static_cast<uint32_t>(std::clamp(target / std::max(per_sample, 1e-9), 1.0, 1024.0));
  }
  stats.seconds = seconds_since(t0);
  stats.spp = done;
  stats.stopped_early = done < spp;
  for (const PathCounters& c : counters) {
    stats.rays += c.rays;
    stats.shadow_rays += c.shadow_rays;
    stats.light_queries += c.light_queries;
  }
  stats.dropped = film.dropped();
  return stats;
}

}  // namespace lumis
