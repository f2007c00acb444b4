// `lumis bench`'s JSON report (--json): the table's figures (app/bench_report.cpp) and the targets, for scripts.
#include <string>

#include <nlohmann/json.hpp>

#include "app/bench_internal.h"

namespace lumis {

using Json = nlohmann::json;
using namespace bench_detail;

namespace {
/// A figure that was not measured is null, as the table's '-': bytes per triangle below 10,000 triangles (bench
/// leaves it out there), a kind of ray the render did not trace (light queries of nee_mis).
Json not_zero(double v) { return v > 0 ? Json(v) : Json(nullptr); }
}  // namespace

std::string bench_report_json(const BenchReport& r) {
  Json doc;
  doc["machine"] = {{"cpu", r.cpu}, {"cores", r.cores}, {"load_average_start", r.load_average_start},
                    {"load_average_end", r.load_average_end}};
  doc["lumis_version"] = LUMIS_VERSION;
  doc["settings"] = {{"threads", r.threads}, {"repeat", r.repeat}, {"quick", r.quick}, {"raw_rays", r.raw_rays}};
  Json scenes = Json::array();
  for (const SceneResult& s : r.scenes) {
    Json j = {{"name", s.name}, {"path", s.path}};
    if (!s.error.empty()) {
      j["error"] = s.error;
      scenes.push_back(j);
      continue;
    }
    j["triangles"] = s.triangles;
    j["lights"] = s.lights;
    j["width"] = s.width;
    j["height"] = s.height;
    j["spp"] = s.spp;
    j["file_bytes"] = s.file_bytes;
    if (s.generate_seconds > 0) j["generate_seconds"] = s.generate_seconds;
    j["load_seconds"] = s.load_seconds;
    j["bvh_build_seconds"] = s.bvh_seconds;
    j["memory"] = {{"baseline_rss_bytes", s.baseline_rss}, {"peak_rss_bytes", s.peak_rss},
                   {"peak_reset_per_scene", s.peak_reset}, {"bytes_per_triangle", not_zero(s.bytes_per_triangle)}};
    const RawThroughput& w = s.raw;
    j["raw_rays_per_s"] = {{"camera_intersect1", w.camera1.wall},  {"camera_intersect16", w.camera16.wall},
                           {"bounce_intersect1", w.bounce1.wall},  {"bounce_intersect16", w.bounce16.wall},
                           {"shadow_occluded1", w.shadow1.wall},   {"shadow_occluded16", w.shadow16.wall},
                           {"light_query", w.light_query.wall},    {"camera_rays", w.camera_rays},
                           {"bounce_geometry_intersect", w.bounce_lumis.wall},
                           {"bounce_rays", w.bounce_rays},    {"shadow_rays", w.shadow_rays},
                           {"camera_hit_fraction", w.camera_hit_fraction},
                           {"bounce_hit_fraction", w.bounce_hit_fraction},
                           {"shadow_occluded_fraction", w.shadow_occluded_fraction}};
    j["raw_rays_per_s"]["bounce_intersect1_shuffled"] = w.bounce1_shuffled.wall;
    j["raw_rays_per_s"]["shadow_occluded1_shuffled"] = w.shadow1_shuffled.wall;
    j["own_rays_per_s"] = {{"integrator", s.scaling_integrator},
                           {"camera", not_zero(s.own_rays_per_s[int(RayKind::Camera)])},
                           {"bounce", not_zero(s.own_rays_per_s[int(RayKind::Bounce)])},
                           {"shadow", not_zero(s.own_rays_per_s[int(RayKind::Shadow)])},
                           {"light_query", not_zero(s.own_rays_per_s[int(RayKind::LightQuery)])}};
    j["raw_rays_per_cpu_s"] = {{"camera_intersect1", w.camera1.cpu},  {"camera_intersect16", w.camera16.cpu},
                               {"bounce_intersect1", w.bounce1.cpu},  {"bounce_intersect16", w.bounce16.cpu},
                               {"shadow_occluded1", w.shadow1.cpu},   {"shadow_occluded16", w.shadow16.cpu},
                               {"light_query", w.light_query.cpu},
                               {"bounce_geometry_intersect", w.bounce_lumis.cpu}};
    Json vs = Json::array();
    for (const BenchVariantResult& v : s.variants)
      vs.push_back({{"integrator", v.integrator},
                    {"seconds", v.seconds},
                    {"cpu_seconds", v.cpu_seconds},
                    {"samples", v.samples},
                    {"rays", v.rays},
                    {"rays_by_kind",
                     {{"camera", v.camera_rays}, {"bounce", v.bounce_rays}, {"shadow", v.shadow_rays},
                      {"light_query", v.light_queries}}},
                    {"samples_per_s", v.samples_per_s},
                    {"rays_per_s", v.rays_per_s},
                    {"raw_mix_rays_per_s", v.raw_mix_rays_per_s},
                    {"raw_mix_packet_rays_per_s", v.raw_mix_packet_rays_per_s},
                    {"ratio_to_raw", v.ratio},
                    {"ratio_to_raw_packets", v.ratio_packets},
                    {"ratio_to_raw_cpu", v.ratio_cpu},
                    {"ratio_to_raw_packets_cpu", v.ratio_cpu_packets},
                    {"ratio_to_own_rays", v.ratio_own},
                    {"ratio_to_raw_shuffled", v.ratio_shuffled},
                    {"embree_share", v.embree_share},
                    {"replay_rays", v.replay_rays},
                    {"budget_cpu_s_per_sample",
                     [&v] {
                       const Budget b = budget(v);
                       return Json{{"render", b.per_sample}, {"embree", b.embree}, {"lumis", b.lumis},
                                   {"lumis_at_target", b.lumis_at_target}, {"target_ratio", kTargetRatio}};
                     }()}});
    j["variants"] = vs;
    j["thread_scaling"] = {{"integrator", s.scaling_integrator},
                           {"threads", s.threads},
                           {"samples_per_s_1", s.samples_per_s_1},
                           {"samples_per_s_n", s.samples_per_s_n},
                           {"speedup", s.samples_per_s_1 > 0 ? s.samples_per_s_n / s.samples_per_s_1 : 0.0},
                           {"efficiency", efficiency(s)},
                           {"cpu_utilisation", s.cpu_utilisation},
                           {"cpu_efficiency", s.cpu_efficiency}};
    for (const auto& [key, g] : {std::pair{"camera_packets", s.camera_packets}, {"shadow_packets", s.shadow_packets},
                                 {"bounce_packets", s.bounce_packets}})
      j[key] = {{"integrator", s.scaling_integrator},
                {"samples_per_s_packets", s.samples_per_s_n},
                {"samples_per_s_single_rays", g.samples_per_s_without},
                {"speedup_cpu", g.speedup_cpu}};
    scenes.push_back(j);
  }
  doc["scenes"] = scenes;
  Json ts = Json::array();
  for (const Target& t : targets(r))
    ts.push_back({{"name", t.name}, {"scene", t.scene}, {"value", t.value}, {"bound", t.bound},
                  {"at_least", t.at_least}, {"met", t.met()}});
  doc["targets"] = ts;
  return doc.dump(2);
}

}  // namespace lumis
