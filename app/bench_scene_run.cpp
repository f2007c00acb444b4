// `lumis bench` on one scene: load (timed, peak memory tracked), render every variant (timed, rays counted by kind),
// one-thread scaling and packet-less runs, raw Embree throughput on the same BVH, each variant's own rays replayed,
// BVH build on a copy, further loads for the median.
#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app/bench_internal.h"
#include "app/memory_check.h"
#include "app/scene_loader.h"
#include "integrators/integrator.h"
#include "integrators/render.h"

namespace lumis {

namespace {

// The most rays a variant's query log holds (128 MiB of rays).
constexpr size_t kMaxLoggedRays = size_t(1) << 22;

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

// Geometry::commit of a copy of the scene's geometry: the BVH build alone, with the flags the loader uses.
double time_bvh_build(const Geometry& g) {
  Geometry copy;
  for (uint32_t id = 0; id < g.geometry_count(); ++id) {
    if (g.is_mesh(id)) copy.add_mesh(g.mesh(id));
    else copy.add_sphere(g.sphere(id));
  }
  const auto t0 = BenchClock::now();
  copy.commit();
  return seconds_since(t0);
}

}  // namespace

void set_bench_defaults(const BenchOptions& o, RenderSettings& s) {
  s.width = s.height = o.quick ? 32 : 256;
  s.spp = o.quick ? 1 : 4;
}

size_t bench_raw_rays(const BenchOptions& o) {
  return o.raw_rays ? o.raw_rays : (o.quick ? size_t(1) << 12 : size_t(1) << 19);
}

uint64_t bench_memory_estimate(int width, int height, size_t raw_rays, size_t variants) {
  const uint64_t pixels = uint64_t(width) * uint64_t(height);
  // The film (render_memory_estimate's accumulators; no image is written); the raw benchmark's camera, bounce and
  // shadow rays, the last two also shuffled (five 32-byte rays per camera ray, where every camera ray hits); each
  // variant's log, kept for the replays: a 32-byte ray and an 8-byte call per pixel at the least. 4096 x 4096 on
  // the furnace: 7.7 GB estimated, a 7.1 GB peak measured.
  return render_memory_estimate(width, height, 0) + 5 * sizeof(Ray) * std::max<uint64_t>(pixels, raw_rays) +
         variants * (sizeof(Ray) + sizeof(QueryLog::Entry)) * pixels;
}

void bench_scene(const BenchScene& which, const BenchOptions& o, int threads, SceneResult& res) {
  const int repeat = std::max(1, o.repeat);
  res.name = which.name;
  res.path = which.path;
  malloc_trim(0);
  res.baseline_rss = proc_status_bytes("VmRSS");
  res.peak_reset = reset_peak_rss();
  auto t0 = BenchClock::now();
  std::unique_ptr<Scene> scene = load_scene(which.path);
  std::vector<double> loads{seconds_since(t0)};
  // Known only now: a texture, glTF file or buffer the scene reads, which the results must not be written over.
  for (const std::string& input : scene->inputs()) {
    std::error_code ec;
    if (!o.json_out.empty() && std::filesystem::equivalent(o.json_out, input, ec))
      throw BenchRefusal("--json " + o.json_out + " is a file scene " + which.name + " reads (" + input +
                         "); write the results elsewhere");
  }

  RenderSettings& s = scene->settings;
  set_bench_defaults(o, s);
  apply_overrides(o.overrides, *scene);  // --width alone keeps them square, as any override does
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
  const size_t rays = bench_raw_rays(o);
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
    t0 = BenchClock::now();
    std::unique_ptr<Scene> again = load_scene(which.path);
    loads.push_back(seconds_since(t0));
  }
  res.load_seconds = median_of(loads);
}

}  // namespace lumis
