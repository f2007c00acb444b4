// Shared by the files of `lumis bench` (bench.cpp runs the scenes, bench_scene_run.cpp measures one, bench_measure.cpp
// turns repetitions into medians and ratios); not part of the app's interface.
#pragma once

#include <chrono>
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

/// Everything `lumis bench` measures on one scene, with `threads` threads, into res (throws on a load error).
void bench_scene(const BenchScene& which, const BenchOptions& o, int threads, SceneResult& res);

/// One variant's medians over the repetitions; each ratio pairs a render with the raw timing (and the replay) of
/// the same repetition, so that slow drifts of the machine's load cancel.
BenchVariantResult aggregate(const std::vector<BenchVariantResult>& runs, const std::vector<RawThroughput>& raws,
                             const RawThroughput& raw_median, const std::vector<Replays>& replays);

}  // namespace lumis
