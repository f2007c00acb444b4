// Shared by the files of `lumis bench` (bench.cpp runs the scenes, bench_scene_run.cpp measures one, bench_measure.cpp
// turns repetitions into medians and ratios, bench_targets.cpp evaluates the targets for bench_report.cpp's table and
// bench_report_json.cpp's JSON); not part of the app's interface.
#pragma once

#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/bench.h"

namespace lumis {

using BenchClock = std::chrono::steady_clock;

/// Wall seconds since t0.
inline double seconds_since(BenchClock::time_point t0) {
  return std::chrono::duration<double>(BenchClock::now() - t0).count();
}

/// A scene to measure: a file, or the generated large scene (`generated`, path kLargeSceneToken until written).
struct BenchScene {
  std::string name, path;
  bool generated = false;
};

/// A variant's replays in one repetition: every ray by a single-ray call, and the calls as the render made them.
struct Replays {
  ReplayTiming single, as_called;
};

/// Stops the whole run rather than one scene: --json names a file a scene reads, known once that scene has loaded.
struct BenchRefusal : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Sets the benchmark's own defaults in s, which the command line's overrides then change: 256 x 256 pixels at
/// 4 spp (32 x 32 at 1 with --quick).
void set_bench_defaults(const BenchOptions& o, RenderSettings& s);

/// Rays per kind that the raw benchmark traces (--raw-rays, or its default).
size_t bench_raw_rays(const BenchOptions& o);

/// Bytes that measuring one scene at width x height allocates, about, beyond the scene itself: a film, the raw
/// benchmark's rays and each variant's query log (counted at one camera ray per pixel, its least).
uint64_t bench_memory_estimate(int width, int height, size_t raw_rays, size_t variants);

/// Everything `lumis bench` measures on one scene, with `threads` threads, into res (throws on a load error, and
/// BenchRefusal before measuring when --json names a file the scene reads).
void bench_scene(const BenchScene& which, const BenchOptions& o, int threads, SceneResult& res);

/// One variant's medians over the repetitions; each ratio pairs a render with the raw timing (and the replay) of
/// the same repetition, so that slow drifts of the machine's load cancel.
BenchVariantResult aggregate(const std::vector<BenchVariantResult>& runs, const std::vector<RawThroughput>& raws,
                             const RawThroughput& raw_median, const std::vector<Replays>& replays);

/// The parts of `lumis bench`'s report shared by its table and its JSON (app/bench_targets.cpp).
namespace bench_detail {

/// The rays/s target's ratio (issue 7).
constexpr double kTargetRatio = 0.7;

/// One of issue 7's targets on one scene: a measured value against its bound.
struct Target {
  std::string name, scene;
  double value = 0, bound = 0;
  bool at_least = true;  ///< value >= bound (else value < bound)
  bool detail = false;   ///< another view of the target above it: indented under it in the table
  bool met() const { return at_least ? value >= bound : value < bound; }
};

/// The variant named `name` in s, or nullptr.
const BenchVariantResult* find_variant(const SceneResult& s, const std::string& name);
/// Thread scaling: speedup over one thread, per thread (0 when not measured).
double efficiency(const SceneResult& s);
/// Every target that the report's scenes measure, in the order of the table.
std::vector<Target> targets(const BenchReport& r);

/// What the rays/s target leaves lumis's own code, in CPU seconds per sample: the render's (all threads), Embree's
/// part of it (the replay's share, embree_share), lumis's part, and lumis's part at ratio kTargetRatio (the same
/// Embree time in kTargetRatio / ratio of the render's time; negative: out of reach even with lumis at zero).
/// All 0 when the render, its CPU time or its replay is missing.
struct Budget {
  double per_sample = 0, embree = 0, lumis = 0, lumis_at_target = 0;
};
/// The budget of one variant's render.
Budget budget(const BenchVariantResult& v);

}  // namespace bench_detail

}  // namespace lumis
