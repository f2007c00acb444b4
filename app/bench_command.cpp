// `lumis bench [SCENE ...] [--json OUT] [--repeat N] [--quick] [--write-large-scene OUT.glb]`.
#include <iostream>
#include <memory>

#include "app/bench.h"
#include "app/commands.h"
#include "core/file_ext.h"

namespace lumis {

int run_bench_command(const BenchArgs& a) {
  if (!a.write_large.empty()) {
    if (const std::string problem = output_file_problem(a.write_large, "room.glb"); !problem.empty()) {
      std::cerr << "lumis: bench: " << a.write_large << ": " << problem << "\n";
      return 2;
    }
    try {
      const size_t triangles = a.options.large_triangles ? a.options.large_triangles : kLargeSceneTriangles;
      const LargeSceneInfo info = write_large_scene(a.write_large, triangles);
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

}  // namespace lumis
