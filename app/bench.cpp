// `lumis bench`: the scenes to measure (the generated large scene, the shipped ones, the largest shared glTF
// models), each measured by bench_scene (app/bench_scene_run.cpp), then the table and the JSON report.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "app/bench_internal.h"
#include "app/memory_check.h"
#include "app/scene_loader.h"
#include "core/atomic_write.h"
#include "core/file_ext.h"
#include "integrators/integrator.h"

namespace lumis {

namespace {

namespace fs = std::filesystem;

double load_average() {
  std::ifstream in("/proc/loadavg");
  double a = 0;
  in >> a;
  return a;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const size_t c = line.find(':');
      return c == std::string::npos ? line : line.substr(c + 2);
    }
  return "unknown";
}

std::vector<BenchScene> default_scenes(const BenchOptions& o) {
  const fs::path src(LUMIS_SOURCE_DIR);
  std::vector<BenchScene> out;
  // The generated scene first: its peak memory is a target, measured before other scenes' renders, logs and raw
  // ray buffers have shaped the heap (after them the same scene read 204-244 bytes per triangle, alone 203).
  out.push_back({"large", kLargeSceneToken, true});
  const char* shipped[] = {"cornell-sphere", "veach-mis", "night-lights"};
  for (const char* n : shipped) {
    if (o.quick && std::string(n) != "cornell-sphere") continue;
    const fs::path p = fs::path(default_scene_path()).parent_path() / (std::string(n) + ".json");
    out.push_back({n, p.string()});
  }
  if (o.quick) return out;
  const fs::path assets = o.assets_dir.empty() ? src.parent_path() / "shared" / "assets" : fs::path(o.assets_dir);
  const char* models[] = {"ToyCar", "MetalRoughSpheresNoTextures"};
  std::string missing;
  for (const char* m : models) {
    const fs::path rel = fs::path("gltf") / m / "glTF" / (std::string(m) + ".gltf"), p = assets / rel;
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) out.push_back({m, p.string()});
    else missing += (missing.empty() ? "" : ", ") + rel.string();
  }
  if (!missing.empty())  // optional, but a run without them measures less than the docs describe: said, not silent
    std::cerr << "lumis bench: warning: " << assets.string() << ": no " << missing
              << "; measuring without (--assets names the shared assets folder)\n";
  return out;
}

}  // namespace

int run_bench(const BenchOptions& o) {
  // Two of the shared render options cannot take effect: a benchmark measures a fixed number of samples, and it
  // writes no image. Taken silently, they would make a run look as if it measured what was asked.
  if (o.overrides.time || o.overrides.exposure) {
    std::cerr << "lumis: bench: " << (o.overrides.time ? "--time" : "--exposure") << " does not apply: "
              << (o.overrides.time ? "bench renders a fixed number of samples per pixel (--spp, default 4)"
                                   : "bench writes no image")
              << "\n";
    return 2;
  }
  if (!o.overrides.camera.empty()) {  // nor can a camera: one name would not fit every scene
    std::cerr << "lumis: bench: --camera does not apply: bench measures each scene through the camera lumis "
                 "render uses without one\n";
    return 2;
  }
  RenderSettings probe;  // every scene is measured at these settings
  try {  // reject bad override names before any work
    set_bench_defaults(o, probe);
    apply_overrides(o.overrides, probe);
  } catch (const std::invalid_argument& e) {
    std::cerr << "lumis: " << e.what() << "\n";
    return 2;
  }
  {
    // Fail before any work rather than with a bare std::bad_alloc minutes in, or being killed: as render does.
    const size_t variants = o.overrides.integrator ? 1 : integrator_names().size();
    const uint64_t need = bench_memory_estimate(probe.width, probe.height, bench_raw_rays(o), variants);
    if (const std::string problem = memory_problem(need, probe.width, probe.height, "benchmark",
                                                   "film, raw rays and query logs, beyond the scene");
        !problem.empty()) {
      std::cerr << "lumis: bench: " << problem << "\n";
      return 1;
    }
  }
  // Options that only shape the default scene list or the generated room: named when they cannot take effect.
  const bool large_listed = o.scenes.empty() || std::count(o.scenes.begin(), o.scenes.end(), kLargeSceneToken) > 0;
  if (!o.assets_dir.empty() && (!o.scenes.empty() || o.quick))
    std::cerr << "lumis bench: warning: --assets only adds the shared glTF models to the default scene list; ignored "
              << (o.scenes.empty() ? "with --quick" : "when scenes are named") << "\n";
  if (o.large_triangles && !large_listed)
    std::cerr << "lumis bench: warning: --large-triangles only sizes the generated room; ignored, as the scenes named "
                 "do not include " << kLargeSceneToken << "\n";
  BenchReport report;
  report.cpu = cpu_model();
  report.cores = int(std::thread::hardware_concurrency());
  report.threads = o.overrides.threads ? *o.overrides.threads : report.cores;
  if (report.threads > report.cores) {  // TBB would run no more: capped as render caps it, so that scaling is true
    std::cerr << "lumis bench: warning: --threads " << report.threads << " is more than the " << report.cores
              << " cores; measuring with " << report.cores << "\n";
    report.threads = report.cores;
  }
  report.repeat = std::max(1, o.repeat);
  report.quick = o.quick;
  report.raw_rays = bench_raw_rays(o);
  report.load_average_start = load_average();

  std::vector<BenchScene> scenes;
  if (o.scenes.empty()) scenes = default_scenes(o);
  for (const std::string& p : o.scenes) {
    if (p == kLargeSceneToken) scenes.push_back({"large", p, true});
    else scenes.push_back({fs::path(p).stem().string(), p});
  }
  // A scene file that is not there fails the run before any scene is measured (a benchmark takes minutes).
  for (const BenchScene& sc : scenes) {
    std::error_code ec;
    if (!sc.generated && !fs::is_regular_file(sc.path, ec)) {
      std::cerr << "lumis: bench: " << sc.path
                << (fs::is_directory(sc.path, ec) ? ": is a folder, expected a scene file" : ": file not found")
                << (sc.path.rfind('@', 0) == 0 ? std::string(" (") + kLargeSceneToken + " is the generated scene)" : "")
                << "\n";
      return 1;
    }
  }
  if (!o.json_out.empty()) {
    if (const std::string problem = output_file_problem(o.json_out, "results.json"); !problem.empty()) {
      std::cerr << "lumis: bench: " << o.json_out << ": " << problem << "\n";
      return 2;
    }
    for (const BenchScene& sc : scenes) {
      std::error_code ec;
      if (!sc.generated && fs::equivalent(o.json_out, sc.path, ec)) {
        std::cerr << "lumis: bench: --json " << o.json_out << " is the scene file " << sc.path
                  << "; write the results elsewhere\n";
        return 2;
      }
    }
  }

  int status = 0;
  for (const BenchScene& sc : scenes) {
    SceneResult res;
    BenchScene which = sc;
    fs::path temp;
    try {
      if (sc.generated) {
        const size_t tris = o.large_triangles ? o.large_triangles : o.quick ? 20'000 : kLargeSceneTriangles;
        temp = fs::temp_directory_path() / ("lumis-bench-large-" + std::to_string(getpid()) + ".glb");
        std::fprintf(stderr, "lumis bench: writing the large scene (%zu triangles) to %s\n", tris,
                     temp.string().c_str());
        const auto t0 = BenchClock::now();
        const LargeSceneInfo info = write_large_scene(temp.string(), tris);
        res.generate_seconds = seconds_since(t0);
        res.file_bytes = info.bytes;
        which.path = temp.string();
      } else {
        std::error_code ec;
        res.file_bytes = fs::is_regular_file(sc.path, ec) ? size_t(fs::file_size(sc.path, ec)) : 0;
      }
      bench_scene(which, o, report.threads, res);
      if (sc.generated) res.path = "(generated) " + res.path;
    } catch (const BenchRefusal& e) {
      std::cerr << "lumis: bench: " << e.what() << "\n";
      std::error_code ec;
      if (!temp.empty()) fs::remove(temp, ec);
      return 2;
    } catch (const std::exception& e) {
      res.name = sc.name;
      res.path = which.path;
      res.error = e.what();
      std::cerr << "lumis: bench: " << sc.name << ": " << e.what() << "\n";
      status = 1;
    }
    if (!temp.empty()) {
      std::error_code ec;
      fs::remove(temp, ec);
    }
    report.scenes.push_back(std::move(res));
  }
  report.load_average_end = load_average();

  print_bench_report(report);
  if (!o.json_out.empty()) {
    if (const std::string why = write_file_atomically(o.json_out, bench_report_json(report) + "\n"); !why.empty()) {
      std::cerr << "lumis: " << o.json_out << ": " << why << "\n";
      return 1;
    }
  }
  return status;
}

}  // namespace lumis
