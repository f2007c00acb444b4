// `lumis bench`'s targets (issue 7) evaluated on its results, and what the rays/s target leaves lumis's own code;
// shared by the table (app/bench_report.cpp) and the JSON report (app/bench_report_json.cpp).
#include <string>
#include <vector>

#include "app/bench_internal.h"

namespace lumis::bench_detail {

const BenchVariantResult* find_variant(const SceneResult& s, const std::string& name) {
  for (const BenchVariantResult& v : s.variants)
    if (v.integrator == name) return &v;
  return nullptr;
}

double efficiency(const SceneResult& s) {
  return s.samples_per_s_1 > 0 && s.threads > 0 ? s.samples_per_s_n / s.samples_per_s_1 / s.threads : 0;
}

std::vector<Target> targets(const BenchReport& r) {
  std::vector<Target> out;
  for (const SceneResult& s : r.scenes) {
    if (!s.error.empty()) continue;
    const bool large = s.name == "large";
    if (s.name == "cornell-sphere" || large)
      if (const BenchVariantResult* v = find_variant(s, "nee_mis"))
      {
        out.push_back({"nee_mis rays/s over raw Embree rays/s for the same mix", s.name, v->ratio, kTargetRatio,
                       true});
        out.push_back({"nee_mis rays/s over the render's own rays replayed (own)", s.name, v->ratio_own,
                       kTargetRatio, true, true});
        out.push_back({"nee_mis rays/s over raw rays in a random order (shuffled)", s.name, v->ratio_shuffled,
                       kTargetRatio, true, true});
      }
    if (s.threads > 1 && s.samples_per_s_1 > 0)
    {
      out.push_back({"thread scaling: speedup / threads (" + s.scaling_integrator + ")", s.name, efficiency(s),
                     0.9, true});
      out.push_back({"thread scaling per CPU-second (proxy on a busy machine)", s.name, s.cpu_efficiency, 0.9, true,
                     true});
    }
    if (large && s.triangles >= 1'000'000) {
      out.push_back({"load + BVH build of the 1M-triangle glTF, seconds", s.name, s.load_seconds, 1.5, false});
      out.push_back({"peak memory, bytes per triangle", s.name, s.bytes_per_triangle, 250, false});
    }
  }
  return out;
}

Budget budget(const BenchVariantResult& v) {
  Budget b;
  if (v.samples == 0 || !(v.cpu_seconds > 0) || !(v.ratio > 0) || !(v.embree_share > 0)) return b;
  b.per_sample = v.cpu_seconds / double(v.samples);
  b.embree = v.embree_share * b.per_sample;
  b.lumis = b.per_sample - b.embree;
  b.lumis_at_target = b.per_sample * v.ratio / kTargetRatio - b.embree;
  return b;
}

}  // namespace lumis::bench_detail
