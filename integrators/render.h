// Tile-parallel rendering on TBB. Random numbers come from (pixel, sample index, seed) only, so the image is
// bitwise identical for any thread count. The paths of a 16x16-pixel tile are traced in lockstep (PathBatch): its
// camera rays go to Embree as 16-ray packets of 4x4 pixels, and each bounce's shadow rays in 16-ray packets.
// Rendering proceeds in passes of whole samples per pixel, so a time budget or a cancel request stops at a sample
// boundary with every pixel at the same count.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/film.h"
#include "integrators/integrator.h"
#include "integrators/scene.h"

namespace lumis {

struct RenderProgress {
  uint64_t samples_done = 0, samples_total = 0;  ///< pixel samples
  double elapsed = 0;                            ///< seconds
  double time_budget = 0;                        ///< seconds; 0 = none

  /// Share of the render done, in [0, 1]: samples of those asked for, or time of the budget, whichever is further.
  double fraction() const {
    const double by_samples = samples_total ? static_cast<double>(samples_done) / samples_total : 1.0;
    const double by_time = time_budget > 0 ? elapsed / time_budget : 0.0;
    return std::min(std::max(by_samples, by_time), 1.0);
  }
};

/// The samples per pixel a render under a time budget asks for (`--time`, `compare` at equal time): the budget, not
/// the count, is meant to end it; a render that reaches the count first (a tiny image, a long budget) says so.
inline constexpr uint32_t kTimedRenderSpp = 1u << 20;

struct RenderOptions {
  uint32_t spp = 16;
  double time_budget = 0;                 ///< seconds; 0 = render all spp
  int threads = 0;                        ///< 0 = all cores
  bool camera_packets = true;             ///< trace camera rays in 4x4-pixel packets of 16 (false: one by one)
  bool shadow_packets = true;             ///< trace each bounce's shadow rays of a tile in 16-ray packets
  bool bounce_packets = true;             ///< trace each bounce's closest-hit rays of a tile in 16-ray packets
  const std::atomic<bool>* cancel = nullptr;
  /// When set (lumis bench): cleared, then one QueryLog per tile (row-major) records every ray query of the render.
  std::vector<QueryLog>* query_logs = nullptr;
  std::function<void(const RenderProgress&)> on_progress;  ///< called from the calling thread between tiles
};

struct RenderStats {
  double seconds = 0;
  uint32_t spp = 0;           ///< samples per pixel actually taken
  uint64_t samples = 0;       ///< pixel samples
  uint64_t rays = 0;          ///< rays traced (closest hit + shadow + light-density queries)
  uint64_t shadow_rays = 0;   ///< of which shadow rays
  uint64_t light_queries = 0; ///< of which light-density queries (`mis`)
  uint64_t dropped = 0;       ///< non-finite samples dropped
  bool stopped_early = false; ///< time budget or cancel
};

RenderStats render(const Scene& scene, const Integrator& integrator, Film& film, const RenderOptions& options);

}  // namespace lumis
