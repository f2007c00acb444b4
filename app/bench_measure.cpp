// `lumis bench`'s arithmetic: Embree's time for a render's mix of rays, and medians and ratios over repetitions.
#include <algorithm>
#include <utility>

#include "app/bench_internal.h"

namespace lumis {

namespace {

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

}  // namespace

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

double median_of(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const size_t m = values.size() / 2;
  return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

RawThroughput median_raw(const std::vector<RawThroughput>& runs) {
  if (runs.empty()) return {};
  RawThroughput out = runs.back();
  auto med = [&](Rate RawThroughput::*field) {
    std::vector<double> w, c;
    for (const RawThroughput& r : runs) {
      w.push_back((r.*field).wall);
      c.push_back((r.*field).cpu);
    }
    out.*field = {median_of(w), median_of(c)};
  };
  for (Rate RawThroughput::*f : {&RawThroughput::camera1, &RawThroughput::camera16, &RawThroughput::bounce1,
                                 &RawThroughput::bounce16, &RawThroughput::shadow1, &RawThroughput::shadow16,
                                 &RawThroughput::bounce1_shuffled, &RawThroughput::shadow1_shuffled,
                                 &RawThroughput::light_query, &RawThroughput::bounce_lumis})
    med(f);
  return out;
}

}  // namespace lumis
