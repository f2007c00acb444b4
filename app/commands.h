// The commands behind lumis's command line: each takes its parsed arguments and returns the process exit code
// (0 success, 1 scene/IO error, 2 usage error; diff: 1 means the images differ). app/cli.cpp parses the command
// line into these structs; this header does not include CLI11, so the commands' files compile without it.
#pragma once

#include <optional>
#include <string>

#include "app/bench.h"
#include "app/render_overrides.h"

namespace lumis {

/// `lumis render`.
struct RenderArgs {
  std::string scene;   ///< empty: default_scene_path()
  std::string output;  ///< empty: <scene name>.png
  RenderOverrides overrides;
  bool quiet = false;
  bool aov_albedo = false, aov_normal = false, aov_depth = false;
};
int run_render(const RenderArgs& args);

/// `lumis compare`.
struct CompareArgs {
  std::string scene;
  std::string output;
  std::string integrators = "uniform,bsdf,light,mis,nee_mis";
  std::string reference;
  std::optional<uint32_t> reference_spp;
  std::string crop;
  bool convergence = false;
  bool quiet = false;
  RenderOverrides overrides;
};
int run_compare(const CompareArgs& args);

/// `lumis diff`.
struct DiffArgs {
  std::string a, b;
  std::string metric = "mse";
  std::optional<double> threshold;
  double tolerance = 0.01;
  std::string psnr_peak = "1";
  std::string heatmap;
  bool json = false;
  bool z_test = false;
  double alpha = 0.01;
  bool metric_given = false, alpha_given = false;  ///< on the command line (a warning when nothing uses them)
};
int run_diff(const DiffArgs& args);

/// `lumis bench`: the benchmark, or with write_large only the generated large scene.
struct BenchArgs {
  BenchOptions options;
  std::string write_large;
};
int run_bench_command(const BenchArgs& args);

}  // namespace lumis
