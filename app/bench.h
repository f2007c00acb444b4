// `lumis bench`: lumis's speed measured against Embree's own limit on the same scenes. For each scene: raw Embree
// throughput for the scene's kinds of rays (no shading), each integrator variant's samples/s and rays/s, the ratio
// of the two for the variant's own mix of rays, load and BVH build time, peak memory and thread scaling.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/render_overrides.h"
#include "integrators/scene.h"

namespace lumis {

struct BenchOptions {
  std::vector<std::string> scenes;  ///< empty: the generated large scene, the shipped scenes, the shared models
  RenderOverrides overrides;        ///< --spp, --width, --height, --threads, --integrator (one variant only), ...
  int repeat = 3;                   ///< every figure is the median of this many runs
  bool quick = false;               ///< tiny settings for the smoke test
  std::string json_out;             ///< write the results as JSON here when set
  std::string assets_dir;           ///< the shared assets folder (with gltf/); empty: next to the sources
  size_t large_triangles = 0;       ///< the generated scene's triangles; 0: kLargeSceneTriangles (quick: 20,000)
  size_t raw_rays = 0;              ///< rays per kind for the raw Embree measurement; 0: 2^19 (quick: 2^12)
};

/// Run the benchmark; prints the table on stdout. Returns the process exit code.
int run_bench(const BenchOptions& options);

/// The name that stands for the generated large scene in a scene list.
inline constexpr const char* kLargeSceneToken = "@large";
/// Triangles in the generated large scene unless --large-triangles says otherwise (--quick: 20,000).
inline constexpr size_t kLargeSceneTriangles = 1'000'000;

struct LargeSceneInfo {
  size_t triangles = 0;
  size_t bytes = 0;  ///< file size
};

/// Write the large benchmark scene as a binary glTF: a closed room (every incoherent ray hits something) whose
/// walls are finely tessellated, with tessellated spheres on the floor, a small emissive ceiling quad and a camera
/// inside. At least min_triangles triangles. Throws std::runtime_error when the file cannot be written.
LargeSceneInfo write_large_scene(const std::string& path, size_t min_triangles);

/// A throughput: rays per second of wall-clock time, and per second of CPU time over all the process's threads.
/// On a shared machine the CPU-time figure does not depend on how many cores the benchmark actually got.
struct Rate {
  double wall = 0, cpu = 0;
};

/// Embree's raw throughput (no shading) for the kinds of rays a path tracer traces in this scene: camera rays,
/// cosine-distributed bounce rays from the points camera rays hit, and shadow rays from those points toward points
/// sampled on the lights (by the scene's own light selector).
struct RawThroughput {
  Rate camera1, camera16;   ///< rtcIntersect1 / rtcIntersect16 (coherent 4x4 pixel packets)
  Rate bounce1, bounce16;   ///< rtcIntersect1 / rtcIntersect16 (incoherent)
  Rate shadow1, shadow16;   ///< rtcOccluded1 / rtcOccluded16
  /// rtcIntersect1 / rtcOccluded1 on the same bounce and shadow rays in a random order. Made in camera-ray order,
  /// the rays above come all samples of a 4x4-pixel block in a row (8 spp x 16 = 128 rays with the default 2^19
  /// rays at 256x256), a locality that this removes.
  Rate bounce1_shuffled, shadow1_shuffled;
  Rate light_query;         ///< Geometry::all_light_hits on the bounce rays (the `mis` density query)
  Rate bounce_lumis;        ///< Geometry::intersect on the bounce rays: rtcIntersect1 plus lumis's Hit record
  size_t camera_rays = 0, bounce_rays = 0, shadow_rays = 0;
  double camera_hit_fraction = 0, bounce_hit_fraction = 0, shadow_occluded_fraction = 0;
};

/// Makes the rays once (from the scene's camera at width x height, its hit points and its lights), then times
/// only the Embree calls, on `threads` threads, as often as asked; each kind's rays are traced again until
/// min_seconds have passed (0: once).
class RawBench {
 public:
  RawBench(const Scene& scene, int width, int height, int threads, size_t rays_per_kind, double min_seconds);
  ~RawBench();
  /// One timing of every kind of ray.
  RawThroughput measure();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// CPU seconds of the whole process so far (all threads, user + system).
double process_cpu_seconds();

/// Embree's time for a render's own queries, replayed without shading (app/bench_replay.cpp).
struct ReplayTiming {
  double wall = 0;   ///< seconds
  size_t rays = 0;   ///< rays replayed (the render's RenderStats::rays when every query was logged)
  size_t hits = 0;   ///< closest-hit rays that hit, occluded shadow rays, light queries that met a light
};

/// The kinds of ray the benchmark tells apart, in the order of its tables.
enum class RayKind { Camera, Bounce, Shadow, LightQuery };
inline constexpr int kRayKinds = 4;

/// The kind of ray a logged call traced, for a render with camera packets on (as the benchmark logs them): coherent
/// 16-ray packets are camera rays, other closest-hit calls bounce rays (incoherent packets, and a bounce's lone
/// last ray), occlusion calls shadow rays, all_light_hits light queries.
RayKind ray_kind(QueryLog::Call call);

/// Trace the queries of `logs` again on `threads` threads, one task per log (a render's tile), with no shading:
/// as they were made (coherent camera packets, shadow packets) or, with single_rays, every ray by
/// rtcIntersect1/rtcOccluded1 (light queries are Geometry::all_light_hits either way). With `only`, just the calls
/// of that kind of ray (ReplayTiming::rays counts those).
ReplayTiming replay_queries(const Geometry& geometry, const std::vector<QueryLog>& logs, int threads,
                            bool single_rays, std::optional<RayKind> only = std::nullopt);

/// Median of measurements: the middle one, or the mean of the middle two for an even count; 0 for none.
double median_of(std::vector<double> values);
/// Element-wise median of several measurements.
RawThroughput median_raw(const std::vector<RawThroughput>& runs);

/// One integrator variant on one scene (all threads unless stated).
struct BenchVariantResult {
  std::string integrator;
  double seconds = 0;                ///< median render time
  double cpu_seconds = 0;            ///< median CPU time of the render, all threads
  uint64_t samples = 0, rays = 0;    ///< per render
  uint64_t camera_rays = 0, bounce_rays = 0, shadow_rays = 0, light_queries = 0;  ///< rays split by kind
  double samples_per_s = 0, rays_per_s = 0;
  double raw_mix_rays_per_s = 0;     ///< raw Embree rate for this mix of rays (rtcIntersect1/rtcOccluded1)
  double raw_mix_packet_rays_per_s = 0;  ///< the same with 16-wide packets where Embree has them
  double ratio = 0, ratio_packets = 0;   ///< rays_per_s over the two raw mix rates (median over repetitions)
  double ratio_cpu = 0, ratio_cpu_packets = 0;  ///< the same per CPU-second (insensitive to other load)
  /// Against the render's own rays: lumis rays/s over single-ray Embree calls' rays/s on exactly the rays this
  /// render traced (its queries logged, then replayed without shading), wall clock (median).
  double ratio_own = 0;
  /// Against the raw rays with the bounce and shadow rays in a random order (RawThroughput::bounce1_shuffled,
  /// shadow1_shuffled; camera rays and light queries as in `ratio`): wall clock, median.
  double ratio_shuffled = 0;
  /// Embree's share of the render: the replay of the render's calls as it made them (its packets) over its time.
  double embree_share = 0;
  /// Rays in the replayed logs: `rays`, unless a render of more than 2^22 rays was logged at fewer samples per
  /// pixel (then the two figures above are per ray).
  size_t replay_rays = 0;
};

struct SceneResult {
  std::string name, path;
  std::string error;                 ///< non-empty: the scene could not be benchmarked
  size_t triangles = 0, lights = 0;
  int width = 0, height = 0;
  uint32_t spp = 0;
  double generate_seconds = 0;       ///< generated scene: writing the .glb
  size_t file_bytes = 0;
  double load_seconds = 0;           ///< load_scene, BVH build included (median)
  double bvh_seconds = 0;            ///< Geometry::commit of a copy of the scene's geometry (median)
  size_t baseline_rss = 0, peak_rss = 0;  ///< bytes: before loading; peak while loading and rendering
  bool peak_reset = false;           ///< the peak was reset before loading (else it is the process's peak)
  double bytes_per_triangle = 0;     ///< (peak - baseline) / triangles
  RawThroughput raw;
  std::vector<BenchVariantResult> variants;
  std::string scaling_integrator;
  int threads = 0;
  double samples_per_s_1 = 0, samples_per_s_n = 0;  ///< one thread, `threads` threads
  double cpu_utilisation = 0;        ///< CPU seconds / (wall seconds x threads) of the `threads`-thread render
  /// Samples per CPU-second with `threads` threads over the same with one: the parallel overhead alone, which a
  /// shared machine cannot hide (wall-clock speedup needs idle cores).
  double cpu_efficiency = 0;
  /// The scaling integrator, `threads` threads, with one kind of packet query turned off (camera rays:
  /// RenderOptions::camera_packets; shadow rays: shadow_packets; bounce rays: bounce_packets): samples/s, and the
  /// default renders' samples per CPU-second over these (the packets' gain, median of paired runs).
  struct PacketGain {
    double samples_per_s_without = 0, speedup_cpu = 0;
  } camera_packets, shadow_packets, bounce_packets;
  /// The scaling integrator's own rays (its logged render), replayed one kind at a time (RayKind order) by
  /// single-ray calls: rays/s, wall clock, median; 0 for a kind it traced none of. Beside RawThroughput's
  /// single-ray rates, they show which kinds of the render's rays cost Embree more than the raw table's.
  double own_rays_per_s[kRayKinds] = {};
};

struct BenchReport {
  std::string cpu;
  int cores = 0, threads = 0, repeat = 0;
  bool quick = false;
  size_t raw_rays = 0;  ///< rays of each kind asked for (--raw-rays); each scene traces whole frames, so a few more
  double load_average_start = 0, load_average_end = 0;
  std::vector<SceneResult> scenes;
};

/// The human-readable table (stdout).
void print_bench_report(const BenchReport& report);
/// The same as JSON.
std::string bench_report_json(const BenchReport& report);


}  // namespace lumis
