// `lumis bench [SCENE ...] [--json OUT] [--repeat N] [--quick] [--write-large-scene OUT.glb]`.
#include <iostream>
#include <memory>

#include "app/bench.h"
#include "app/cli.h"
#include "core/file_ext.h"

namespace lumis {

namespace {

struct BenchArgs {
  BenchOptions options;
  std::string write_large;
};

int run_bench_command(const BenchArgs& a) {
  if (!a.write_large.empty()) {
    try {
      const LargeSceneInfo info = write_large_scene(a.write_large, a.options.large_triangles);
      std::cerr << "lumis: wrote " << a.write_large << ": " << info.triangles << " triangles, " << info.bytes
                << " bytes\n";
      return 0;
    } catch (const std::exception& e) {
      std::cerr << "lumis: " << e.what() << "\n";
      return 1;
    }
  }
  return run_bench(a.options);
}

}  // namespace

void register_bench_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<BenchArgs>();
  BenchOptions& o = a->options;
  CLI::App* cmd = app.add_subcommand(
      "bench", "Measure samples/s and rays/s of every integrator against Embree's raw ray throughput");
  cmd->add_option("scenes", o.scenes,
                  "Scene files, or @large for the generated 1M-triangle room (default: @large, the shipped scenes "
                  "and the largest shared glTF models)");
  cmd->add_option("--json", o.json_out, "Write the results as JSON to this file");
  CLI::Option* repeat = cmd->add_option("--repeat", o.repeat, "Repetitions; every figure is their median (default 3; 1 with --quick)")->check(CLI::Range(1, 100));
  cmd->add_flag("--quick", o.quick,
                "Tiny settings (32x32, 1 spp, 1 repetition, small raw-ray batches, a 20k-triangle @large; of the "
                "default scenes only @large and cornell-sphere): a smoke test, not a measurement");
  cmd->add_option("--assets", o.assets_dir, "Shared assets folder with gltf/ (default: <source>/../shared/assets)")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--large-triangles", o.large_triangles, "Triangles in the generated scene (at least)")
      ->check(CLI::Range(size_t(100), size_t(100'000'000)));
  cmd->add_option("--raw-rays", o.raw_rays, "Rays per kind for the raw Embree measurement (default 524288)")
      ->check(CLI::Range(size_t(16), size_t(1) << 26));
  cmd->add_option("--write-large-scene", a->write_large,
                  "Only write the generated large scene to this .glb (with --large-triangles) and exit")
      ->check(CLI::Validator(
          [](std::string& path) -> std::string {
            return lower_extension(path) == ".glb" ? "" : "expected a .glb file name, found " + path;  // .GLB too
          },
          "FILE.glb"));
  add_render_overrides(*cmd, o.overrides);
  cmd->callback([a, repeat, &exit_code] {
    if (a->options.quick && repeat->count() == 0) a->options.repeat = 1;
    exit_code = run_bench_command(*a);
  });
}

}  // namespace lumis
