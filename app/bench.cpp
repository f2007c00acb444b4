// `lumis bench`: per scene, load (timed, peak memory tracked), render every variant (timed, rays counted by kind),
// one-thread scaling run, raw Embree throughput on the same BVH, BVH build on a copy, further loads for the median.
#include "app/bench.h"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include <tbb/enumerable_thread_specific.h>

#include "app/scene_error.h"
#include "app/scene_loader.h"
#include "core/atomic_write.h"
#include "core/file_ext.h"
#include "integrators/integrator.h"
#include "integrators/render.h"

namespace lumis {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The most rays a variant's query log holds (128 MiB of rays).
constexpr size_t kMaxLoggedRays = size_t(1) << 22;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// A field of /proc/self/status in bytes (VmRSS, VmHWM); 0 when unavailable.
size_t proc_status_bytes(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key + ":", 0) == 0) return size_t(std::stoull(line.substr(key.size() + 1))) * 1024;
  return 0;
}

// Resets the kernel's peak-RSS mark (VmHWM) to the current RSS, so that each scene's peak is its own.
bool reset_peak_rss() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return bool(out);
}

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

// One render of scene.settings.integrator: wall and CPU time, rays by kind (the counts are the same every time: the
// random numbers depend only on pixel, sample index and seed). With logs, every query is recorded (not timed).
BenchVariantResult render_once(const Scene& scene, int threads, bool camera_packets = true,
                               bool shadow_packets = true, bool bounce_packets = true,
                               std::vector<QueryLog>* logs = nullptr) {
  const std::unique_ptr<Integrator> integrator = make_integrator(scene.settings);
  Film film(scene.settings.width, scene.settings.height, FilmOptions{false, false, false, false});
  RenderOptions ro;
  ro.spp = scene.settings.spp;
  ro.threads = threads;
  ro.camera_packets = camera_packets;
  ro.shadow_packets = shadow_packets;
  ro.bounce_packets = bounce_packets;
  ro.query_logs = logs;
  const double c0 = process_cpu_seconds();
  const RenderStats st = render(scene, *integrator, film, ro);
  BenchVariantResult v;
  v.cpu_seconds = process_cpu_seconds() - c0;
  v.seconds = st.seconds;
  v.integrator = integrator->name();
  v.samples = st.samples;
  v.rays = st.rays;
  v.camera_rays = st.samples;  // one camera ray per pixel sample
  v.shadow_rays = st.shadow_rays;
  v.light_queries = st.light_queries;
  v.bounce_rays = st.rays - st.shadow_rays - st.light_queries - std::min<uint64_t>(st.rays, st.samples);
  return v;
}

// Seconds Embree takes for this mix of rays at the given rates (wall or CPU; single rays with the bounce and shadow
// rays in a random order when shuffled); 0 when a needed rate is missing.
double raw_seconds(const BenchVariantResult& v, const RawThroughput& raw, bool packets, bool cpu,
                   bool shuffled = false) {
  const auto pick = [cpu](const Rate& r) { return cpu ? r.cpu : r.wall; };
  const Rate& bounce = shuffled ? raw.bounce1_shuffled : packets ? raw.bounce16 : raw.bounce1;
  const Rate& shadow = shuffled ? raw.shadow1_shuffled : packets ? raw.shadow16 : raw.shadow1;
  const std::pair<uint64_t, double> parts[] = {
      {v.camera_rays, pick(packets ? raw.camera16 : raw.camera1)},
      {v.bounce_rays, pick(bounce)},
      {v.shadow_rays, pick(shadow)},
      {v.light_queries, pick(raw.light_query)}};
  double s = 0;
  for (const auto& [n, rate] : parts) {
    if (n == 0) continue;
    if (!(rate > 0)) return 0;
    s += double(n) / rate;
  }
  return s;
}

// A variant's replays in one repetition: every ray by a single-ray call, and the calls as the render made them.
struct Replays {
  ReplayTiming single, as_called;
};

// Medians over the repetitions; each ratio pairs a render with the raw timing (and the replay) of the same
// repetition, so that slow drifts of the machine's load cancel.
BenchVariantResult aggregate(const std::vector<BenchVariantResult>& runs, const std::vector<RawThroughput>& raws,
                             const RawThroughput& raw_median, const std::vector<Replays>& replays) {
  BenchVariantResult v = runs.back();
  std::vector<double> wall, cpu, ratio[4], shuffled, own, share;
  for (size_t r = 0; r < runs.size(); ++r) {
    wall.push_back(runs[r].seconds);
    cpu.push_back(runs[r].cpu_seconds);
    // Per ray: the log may come from a render with fewer samples per pixel (kMaxLoggedRays).
    const double logged = r < replays.size() ? double(replays[r].single.rays) : 0;
    if (logged > 0 && runs[r].seconds > 0) {
      const double scale = double(runs[r].rays) / logged / runs[r].seconds;
      own.push_back(replays[r].single.wall * scale);
      share.push_back(replays[r].as_called.wall * scale);
      v.replay_rays = replays[r].single.rays;
    }
    for (int k = 0; k < 4; ++k) {
      const bool packets = k & 1, use_cpu = k & 2;
      const double raw_s = raw_seconds(v, raws[r], packets, use_cpu);
      const double own_s = use_cpu ? runs[r].cpu_seconds : runs[r].seconds;
      if (raw_s > 0 && own_s > 0) ratio[k].push_back(raw_s / own_s);
    }
    const double shuffled_s = raw_seconds(v, raws[r], false, false, true);
    if (shuffled_s > 0 && runs[r].seconds > 0) shuffled.push_back(shuffled_s / runs[r].seconds);
  }
  v.seconds = median_of(wall);
  v.cpu_seconds = median_of(cpu);
  v.samples_per_s = double(v.samples) / std::max(v.seconds, 1e-12);
  v.rays_per_s = double(v.rays) / std::max(v.seconds, 1e-12);
  const double s1 = raw_seconds(v, raw_median, false, false), s16 = raw_seconds(v, raw_median, true, false);
  v.raw_mix_rays_per_s = s1 > 0 ? double(v.rays) / s1 : 0;
  v.raw_mix_packet_rays_per_s = s16 > 0 ? double(v.rays) / s16 : 0;
  v.ratio = median_of(ratio[0]);
  v.ratio_packets = median_of(ratio[1]);
  v.ratio_cpu = median_of(ratio[2]);
  v.ratio_cpu_packets = median_of(ratio[3]);
  v.ratio_own = median_of(own);
  v.ratio_shuffled = median_of(shuffled);
  v.embree_share = median_of(share);
  return v;
}

// Geometry::commit of a copy of the scene's geometry: the BVH build alone, with the flags the loader uses.
double time_bvh_build(const Geometry& g) {
  Geometry copy;
  for (uint32_t id = 0; id < g.geometry_count(); ++id) {
    if (g.is_mesh(id)) copy.add_mesh(g.mesh(id));
    else copy.add_sphere(g.sphere(id));
  }
  const auto t0 = Clock::now();
  copy.commit();
  return seconds_since(t0);
}

struct BenchScene {
  std::string name, path;
  bool generated = false;
};

void bench_scene(const BenchScene& which, const BenchOptions& o, int threads, SceneResult& res) {
  const int repeat = std::max(1, o.repeat);
  res.name = which.name;
  res.path = which.path;
  malloc_trim(0);
  res.baseline_rss = proc_status_bytes("VmRSS");
  res.peak_reset = reset_peak_rss();
  auto t0 = Clock::now();
  std::unique_ptr<Scene> scene = load_scene(which.path);
  std::vector<double> loads{seconds_since(t0)};

  RenderSettings& s = scene->settings;
  // The benchmark's defaults, then the command line's (--width alone keeps them square, as any override does).
  s.width = s.height = o.quick ? 32 : 256;
  s.spp = o.quick ? 1 : 4;
  apply_overrides(o.overrides, *scene);
  s.time_budget = 0;
  scene->update_light_selector();
  res.triangles = scene->geometry.triangle_count();
  res.lights = scene->lights.size();
  res.width = s.width;
  res.height = s.height;
  res.spp = s.spp;
  res.threads = threads;

  std::vector<std::string> variants = integrator_names();
  if (o.overrides.integrator) variants = {*o.overrides.integrator};
  // Thread scaling on nee_mis (the default and the variant the targets are about), or the one variant asked for.
  res.scaling_integrator = o.overrides.integrator ? *o.overrides.integrator : "nee_mis";
  const size_t rays = o.raw_rays ? o.raw_rays : (o.quick ? size_t(1) << 12 : size_t(1) << 19);
  std::vector<std::vector<BenchVariantResult>> runs(variants.size());
  std::vector<BenchVariantResult> single, no_camera_packets, no_shadow_packets, no_bounce_packets;
  std::vector<RawThroughput> raws;
  std::unique_ptr<RawBench> raw;
  // Each variant's queries, recorded once (an extra render, not timed) and replayed in every repetition.
  std::vector<std::vector<QueryLog>> logs(variants.size());
  std::vector<std::vector<Replays>> replays(variants.size());
  std::vector<double> own_by_kind[kRayKinds];  // the scaling integrator's rays, kind by kind, rays/s
  // Repetitions outermost: the renders and the raw timings they are compared with see the same machine load.
  for (int r = 0; r < repeat; ++r) {
    std::fprintf(stderr, "lumis bench: %s: repetition %d of %d\n", res.name.c_str(), r + 1, repeat);
    for (size_t i = 0; i < variants.size(); ++i) {
      s.integrator = variants[i];
      runs[i].push_back(render_once(*scene, threads));
    }
    s.integrator = res.scaling_integrator;
    single.push_back(render_once(*scene, 1));
    no_camera_packets.push_back(render_once(*scene, threads, /*camera_packets=*/false, true, true));
    no_shadow_packets.push_back(render_once(*scene, threads, true, /*shadow_packets=*/false, true));
    no_bounce_packets.push_back(render_once(*scene, threads, true, true, /*bounce_packets=*/false));
    if (r == 0) {  // the peak of loading and rendering, before the raw benchmark's ray buffers exist
      res.peak_rss = proc_status_bytes("VmHWM");
      raw = std::make_unique<RawBench>(*scene, s.width, s.height, threads, rays, o.quick ? 0.0 : 0.1);
      const uint32_t spp = s.spp;
      for (size_t i = 0; i < variants.size(); ++i) {
        // At most kMaxLoggedRays rays (32 bytes each) per variant: beyond, a render with fewer samples per pixel
        // is logged; its rays are drawn alike, and the ratios are taken per ray.
        const double per_spp = double(runs[i][0].rays) / std::max(1u, spp);
        s.spp = uint32_t(std::clamp(std::floor(double(kMaxLoggedRays) / std::max(per_spp, 1.0)), 1.0, double(spp)));
        s.integrator = variants[i];
        render_once(*scene, threads, true, true, true, &logs[i]);
      }
      s.spp = spp;
    }
    raws.push_back(raw->measure());
    for (size_t i = 0; i < variants.size(); ++i)
      replays[i].push_back({replay_queries(scene->geometry, logs[i], threads, true),
                            replay_queries(scene->geometry, logs[i], threads, false)});
    for (size_t i = 0; i < variants.size(); ++i)
      for (int k = 0; k < kRayKinds && variants[i] == res.scaling_integrator; ++k) {
        const ReplayTiming t = replay_queries(scene->geometry, logs[i], threads, true, RayKind(k));
        if (t.rays) own_by_kind[k].push_back(double(t.rays) / std::max(t.wall, 1e-9));
      }
  }
  for (int k = 0; k < kRayKinds; ++k) res.own_rays_per_s[k] = median_of(own_by_kind[k]);
  raw.reset();
  logs.clear();
  res.raw = median_raw(raws);
  for (size_t i = 0; i < variants.size(); ++i)
    res.variants.push_back(aggregate(runs[i], raws, res.raw, replays[i]));
  std::vector<double> single_rates, utilisation, cpu_eff;
  for (const BenchVariantResult& v : single) single_rates.push_back(double(v.samples) / std::max(v.seconds, 1e-12));
  res.samples_per_s_1 = median_of(single_rates);
  for (size_t i = 0; i < variants.size(); ++i) {
    if (variants[i] != res.scaling_integrator) continue;
    res.samples_per_s_n = res.variants[i].samples_per_s;
    for (size_t r = 0; r < runs[i].size(); ++r) {
      const BenchVariantResult& v = runs[i][r];
      utilisation.push_back(v.cpu_seconds / std::max(v.seconds * threads, 1e-12));
      if (v.cpu_seconds > 0 && single[r].cpu_seconds > 0) cpu_eff.push_back(single[r].cpu_seconds / v.cpu_seconds);
    }
  }
  const auto packet_gain = [&](const std::vector<BenchVariantResult>& without) {
    SceneResult::PacketGain g;
    std::vector<double> rates, gain;
    for (const BenchVariantResult& v : without) rates.push_back(double(v.samples) / std::max(v.seconds, 1e-12));
    g.samples_per_s_without = median_of(rates);
    for (size_t i = 0; i < variants.size(); ++i)
      for (size_t r = 0; variants[i] == res.scaling_integrator && r < runs[i].size(); ++r)
        if (runs[i][r].cpu_seconds > 0) gain.push_back(without[r].cpu_seconds / runs[i][r].cpu_seconds);
    g.speedup_cpu = median_of(gain);
    return g;
  };
  res.camera_packets = packet_gain(no_camera_packets);
  res.shadow_packets = packet_gain(no_shadow_packets);
  res.bounce_packets = packet_gain(no_bounce_packets);
  res.cpu_utilisation = median_of(utilisation);
  res.cpu_efficiency = median_of(cpu_eff);
  if (res.triangles >= 10000 && res.peak_rss > res.baseline_rss)
    res.bytes_per_triangle = double(res.peak_rss - res.baseline_rss) / double(res.triangles);

  std::vector<double> builds;
  for (int r = 0; r < repeat; ++r) builds.push_back(time_bvh_build(scene->geometry));
  res.bvh_seconds = median_of(builds);
  scene.reset();
  for (int r = 1; r < repeat; ++r) {
    t0 = Clock::now();
    std::unique_ptr<Scene> again = load_scene(which.path);
    loads.push_back(seconds_since(t0));
  }
  res.load_seconds = median_of(loads);
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
  for (const char* m : models) {
    const fs::path p = assets / "gltf" / m / "glTF" / (std::string(m) + ".gltf");
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) out.push_back({m, p.string()});
  }
  return out;
}

}  // namespace

int run_bench(const BenchOptions& o) {
  try {  // reject bad override names before any work
    RenderSettings probe;
    apply_overrides(o.overrides, probe);
  } catch (const std::invalid_argument& e) {
    std::cerr << "lumis: " << e.what() << "\n";
    return 2;
  }
  BenchReport report;
  report.cpu = cpu_model();
  report.cores = int(std::thread::hardware_concurrency());
  report.threads = o.overrides.threads ? *o.overrides.threads : report.cores;
  report.repeat = std::max(1, o.repeat);
  report.quick = o.quick;
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
                << (fs::is_directory(sc.path, ec) ? ": is a folder, expected a scene file\n" : ": file not found\n");
      return 1;
    }
  }
  if (!o.json_out.empty()) {
    if (const std::string problem = output_file_problem(o.json_out); !problem.empty()) {
      std::cerr << "lumis: bench: " << o.json_out << ": " << problem << "\n";
      return 2;
    }
  }

  int status = 0;
  for (const BenchScene& sc : scenes) {
    SceneResult res;
    BenchScene which = sc;
    fs::path temp;
    try {
      if (sc.generated) {
        const size_t tris = o.quick ? std::min<size_t>(o.large_triangles, 20000) : o.large_triangles;
        temp = fs::temp_directory_path() / ("lumis-bench-large-" + std::to_string(getpid()) + ".glb");
        std::fprintf(stderr, "lumis bench: writing the large scene (%zu triangles) to %s\n", tris,
                     temp.string().c_str());
        const auto t0 = Clock::now();
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
