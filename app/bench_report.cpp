// `lumis bench` output: the table on stdout, with the targets evaluated (reported, never asserted: the
// machine is shared and noisy). The same figures as JSON: app/bench_report_json.cpp.
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "app/bench_internal.h"

namespace lumis {

namespace {

using namespace bench_detail;

double mega(double v) { return v * 1e-6; }

std::string count(double v) {
  char buf[32];
  if (v >= 1e6) std::snprintf(buf, sizeof buf, "%.2fM", v * 1e-6);
  else if (v >= 1e3) std::snprintf(buf, sizeof buf, "%.1fk", v * 1e-3);
  else std::snprintf(buf, sizeof buf, "%.0f", v);
  return buf;
}

double pct(uint64_t part, uint64_t whole) { return whole ? 100.0 * double(part) / double(whole) : 0; }

}  // namespace

void print_bench_report(const BenchReport& r) {
  std::printf("lumis bench: %d thread%s on %d cores (%s), median of %d%s; load average %.1f -> %.1f\n", r.threads,
              r.threads == 1 ? "" : "s", r.cores, r.cpu.c_str(), r.repeat, r.quick ? ", quick" : "",
              r.load_average_start, r.load_average_end);
  std::printf("Shared machines are noisy: compare the ratios (measured in the same run), not absolute rates.\n\n");

  std::printf("%-28s %10s %8s %8s %9s %7s %6s\n", "scene", "triangles", "load s", "BVH s", "peak MiB", "B/tri",
              "lights");
  for (const SceneResult& s : r.scenes) {
    if (!s.error.empty()) {
      std::printf("%-28s error: %s\n", s.name.c_str(), s.error.c_str());
      continue;
    }
    char bpt[16] = "-";
    if (s.bytes_per_triangle > 0) std::snprintf(bpt, sizeof bpt, "%.0f", s.bytes_per_triangle);
    std::printf("%-28s %10zu %8.3f %8.3f %9.1f %7s %6zu\n", s.name.c_str(), s.triangles, s.load_seconds,
                s.bvh_seconds, double(s.peak_rss) / (1 << 20), bpt, s.lights);
  }
  // Every scene failed: the other tables would be headers over nothing.
  if (std::none_of(r.scenes.begin(), r.scenes.end(), [](const SceneResult& s) { return s.error.empty(); })) {
    std::printf("\nNo scene was measured.\n");
    return;
  }

  std::printf("\nRaw Embree, Mrays/s (wall clock), %d thread%s %15s %15s %15s %8s %8s\n", r.threads,
              r.threads == 1 ? "" : "s", "camera 1 / 16", "bounce 1 / 16", "shadow 1 / 16", "lightq", "lumis");
  for (const SceneResult& s : r.scenes) {
    if (!s.error.empty()) continue;
    const RawThroughput& w = s.raw;
    std::printf("%-43s %7.2f/%7.2f %7.2f/%7.2f %7.2f/%7.2f %8.2f %8.2f\n", s.name.c_str(), mega(w.camera1.wall),
                mega(w.camera16.wall), mega(w.bounce1.wall), mega(w.bounce16.wall), mega(w.shadow1.wall),
                mega(w.shadow16.wall), mega(w.light_query.wall), mega(w.bounce_lumis.wall));
  }
  std::printf("(lightq: Geometry::all_light_hits; lumis: Geometry::intersect, i.e. rtcIntersect1 plus the Hit record, "
              "on the bounce rays)\n");

  std::printf("\nEmbree by kind of ray, Mrays/s of single-ray calls  %16s %24s %24s %16s\n", "camera raw/own",
              "bounce raw/shuffled/own", "shadow raw/shuffled/own", "lightq raw/own");
  const auto own = [](const SceneResult& s, RayKind k) {
    char buf[16] = "-";
    if (const double v = s.own_rays_per_s[int(k)]; v > 0) std::snprintf(buf, sizeof buf, "%.2f", mega(v));
    return std::string(buf);
  };
  for (const SceneResult& s : r.scenes) {
    if (!s.error.empty()) continue;
    const RawThroughput& w = s.raw;
    char row[4][48];
    std::snprintf(row[0], sizeof row[0], "%.2f/%s", mega(w.camera1.wall), own(s, RayKind::Camera).c_str());
    std::snprintf(row[1], sizeof row[1], "%.2f/%.2f/%s", mega(w.bounce1.wall), mega(w.bounce1_shuffled.wall),
                  own(s, RayKind::Bounce).c_str());
    std::snprintf(row[2], sizeof row[2], "%.2f/%.2f/%s", mega(w.shadow1.wall), mega(w.shadow1_shuffled.wall),
                  own(s, RayKind::Shadow).c_str());
    std::snprintf(row[3], sizeof row[3], "%.2f/%s", mega(w.light_query.wall), own(s, RayKind::LightQuery).c_str());
    std::printf("%-28s %-22s %16s %24s %24s %16s\n", s.name.c_str(), s.scaling_integrator.c_str(), row[0], row[1],
                row[2], row[3]);
  }
  std::printf("(raw: the rays of the table above, made in camera-ray order; shuffled: the same rays in a random "
              "order;\n own: the render's own rays, replayed kind by kind; '-': the render traced none)\n");

  std::printf("\nratio = lumis rays/s over raw Embree rays/s for the same mix of rays (rtcIntersect1/rtcOccluded1;\n"
              "  cpu: per CPU-second, insensitive to other load; cpu16: against 16-wide packets;\n"
              "  own: against single-ray Embree calls on exactly the render's own rays, replayed without shading;\n"
              "  emb%%: Embree's share of the render, its calls replayed as made, packets included)\n");
  std::printf("%-28s %-8s %10s %8s %6s %17s %9s %6s %6s %6s %6s %5s\n", "scene", "variant", "samples/s", "Mrays/s",
              "ray/sp", "cam/bnc/shd/lq %", "raw Mr/s", "ratio", "cpu", "cpu16", "own", "emb%");
  for (const SceneResult& s : r.scenes) {
    if (!s.error.empty()) continue;
    for (const BenchVariantResult& v : s.variants) {
      char mix[64];
      std::snprintf(mix, sizeof mix, "%.0f/%.0f/%.0f/%.0f", pct(v.camera_rays, v.rays), pct(v.bounce_rays, v.rays),
                    pct(v.shadow_rays, v.rays), pct(v.light_queries, v.rays));
      std::printf("%-28s %-8s %10s %8.2f %6.2f %17s %9.2f %6.2f %6.2f %6.2f %6.2f %5.0f\n", s.name.c_str(),
                  v.integrator.c_str(), count(v.samples_per_s).c_str(), mega(v.rays_per_s),
                  v.samples ? double(v.rays) / double(v.samples) : 0.0, mix, mega(v.raw_mix_rays_per_s), v.ratio,
                  v.ratio_cpu, v.ratio_cpu_packets, v.ratio_own, 100 * v.embree_share);
    }
  }

  std::printf("\n%-28s %-8s %12s %12s %8s %10s %10s %9s\n", "thread scaling", "variant", "1 thread", "N threads",
              "speedup", "/ threads", "cpu share", "cpu eff");
  for (const SceneResult& s : r.scenes) {
    if (!s.error.empty()) continue;
    std::printf("%-28s %-8s %12s %12s %8.2f %10.2f %10.2f %9.2f\n", s.name.c_str(), s.scaling_integrator.c_str(),
                count(s.samples_per_s_1).c_str(), count(s.samples_per_s_n).c_str(),
                s.samples_per_s_1 > 0 ? s.samples_per_s_n / s.samples_per_s_1 : 0.0, efficiency(s),
                s.cpu_utilisation, s.cpu_efficiency);
  }
  std::printf("(cpu share: CPU seconds / (wall seconds x threads) of the N-thread render; cpu eff: samples per "
              "CPU-second, N threads over 1)\n");

  std::printf("\n%-28s %-8s %12s %14s %8s %14s %8s %14s %8s\n", "16-ray packets", "variant", "default",
              "camera 1 by 1", "speedup", "shadow 1 by 1", "speedup", "bounce 1 by 1", "speedup");
  for (const SceneResult& s : r.scenes) {
    if (!s.error.empty()) continue;
    std::printf("%-28s %-8s %12s %14s %8.3f %14s %8.3f %14s %8.3f\n", s.name.c_str(), s.scaling_integrator.c_str(),
                count(s.samples_per_s_n).c_str(), count(s.camera_packets.samples_per_s_without).c_str(),
                s.camera_packets.speedup_cpu, count(s.shadow_packets.samples_per_s_without).c_str(),
                s.shadow_packets.speedup_cpu, count(s.bounce_packets.samples_per_s_without).c_str(),
                s.bounce_packets.speedup_cpu);
  }
  std::printf("(samples/s, N threads; default: camera, shadow and bounce rays in packets; speedup: CPU seconds with "
              "that kind one by one over CPU seconds of the default, median of the paired runs)\n");

  std::printf("\nTargets (reported, not enforced):\n");
  for (const Target& t : targets(r))
    std::printf("  %-4s %-60s %-16s %8.3f (%s %g)\n", t.met() ? "met" : "MISS",
                ((t.detail ? "  " : "") + t.name).c_str(), t.scene.c_str(), t.value, t.at_least ? ">=" : "<", t.bound);
  if (targets(r).empty())
    std::printf("  none measured here: the rays/s targets are cornell-sphere's and @large's (nee_mis), thread scaling "
                "needs more than one thread, load time and memory need @large at 1M triangles\n");

  // nee_mis's figures only: with --integrator bsdf (say) there are none, and no heading either.
  std::vector<std::pair<const SceneResult*, Budget>> rows;
  for (const SceneResult& s : r.scenes) {
    const BenchVariantResult* v = s.error.empty() ? find_variant(s, "nee_mis") : nullptr;
    const Budget b = v ? budget(*v) : Budget{};
    if (b.per_sample > 0) rows.emplace_back(&s, b);
  }
  if (!rows.empty())
    std::printf("\nWhat the rays/s target leaves lumis's own code (nee_mis, CPU us per sample; Embree's part: "
                "emb%%):\n");
  for (const auto& [s, b] : rows) {
    std::printf("  %-28s now %.2f = Embree %.2f + lumis %.2f; at ratio %.1f: %.2f, lumis ", s->name.c_str(),
                b.per_sample * 1e6, b.embree * 1e6, b.lumis * 1e6, kTargetRatio,
                (b.embree + b.lumis_at_target) * 1e6);
    if (b.lumis_at_target <= 0) std::printf("out of reach (Embree alone takes longer)\n");
    else if (b.lumis_at_target < b.lumis)
      std::printf("%.2f (%.0f %% less time)\n", b.lumis_at_target * 1e6, 100 * (1 - b.lumis_at_target / b.lumis));
    else std::printf("%.2f (met)\n", b.lumis_at_target * 1e6);
  }
}

}  // namespace lumis
