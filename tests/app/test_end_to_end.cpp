// End to end through the scene loader and the renderer:
//  - determinism: the same scene, seed and spp give bitwise-identical images with 1 and 2 threads, for every
//    sampler (samples depend on (pixel, index, seed) only; each pixel is accumulated by one thread in order), and
//    with rays traced in packets or one by one (to float rounding of the hit distance); the lockstep loop over
//    a 16x16 tile's paths gives what each path traced alone gives; every pixel gets its own camera rays;
//  - a cancelled or timed-out render stops at a pass boundary and reports the samples it took;
//  - scenes/furnace.json renders to its closed form: 0.8 on the diffuse sphere, 1 on the background (z-tests of
//    region means at a Sidak-corrected alpha 0.01 over the 6 tests; fixed seed).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

#include "app/scene_loader.h"
#include "integrators/render.h"
#include "core/sampler.h"
#include "tests/support/render_film.h"
#include "tests/support/render_stats.h"

namespace lumis {
namespace {

std::string scene_path(const char* name) { return std::string(LUMIS_SOURCE_DIR) + "/scenes/" + name; }

// Packet flags: camera rays, shadow rays, bounce rays (RenderOptions).
struct Packets {
  bool camera = true, shadow = true, bounce = true;
};

Film render_with(Scene& scene, int threads, uint32_t spp, Packets packets = {}) {
  RenderOptions ro;
  ro.threads = threads;
  ro.camera_packets = packets.camera;
  ro.shadow_packets = packets.shadow;
  ro.bounce_packets = packets.bounce;
  return test::render_film(scene, spp, ro, FilmOptions{true, true, true, true}).film;
}

TEST(EndToEnd, BitwiseIdenticalForAnyThreadCount) {
  auto scene = load_scene(scene_path("cornell-sphere.json"));
  scene->settings.width = 40;
  scene->settings.height = 28;  // not a multiple of the tile size
  for (SamplerType sampler : {SamplerType::Independent, SamplerType::Stratified, SamplerType::Sobol}) {
    scene->settings.sampler = sampler;
    const Image a = render_with(*scene, 1, 8).to_image(), b = render_with(*scene, 2, 8).to_image();
    ASSERT_EQ(a.data.size(), b.data.size());
    EXPECT_EQ(0, std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)))
        << sampler_type_name(sampler) << ": 1 and 2 threads differ";
  }
}

// The paths of a 16x16 tile are traced in lockstep; their queries go to Embree as 16-ray packets (camera rays:
// rtcIntersect16 per 4x4 pixels, shadow rays: rtcOccluded16) or one by one. Every pixel keeps its own
// sampler, so the paths are the same; Embree's kernels round the hit distance differently in the last bits
// (measured for camera packets: 206 of 4884 values differ, by at most 8.4e-6 relative), so the images agree to
// 1e-4, not bit for bit. A path that took another branch, or a shadow ray credited to the wrong lane, would
// differ by far more. Every variant, since each has its own direct-light hook.
TEST(EndToEnd, PacketsDoNotChangeTheImage) {
  auto scene = load_scene(scene_path("cornell-sphere.json"));
  scene->settings.width = 37;
  scene->settings.height = 22;  // partial tiles (batches) and partial 4x4 packets
  const auto worst_difference = [](const Image& a, const Image& b) {
    EXPECT_EQ(a.data.size(), b.data.size());
    double worst = 0;
    for (size_t i = 0; i < std::min(a.data.size(), b.data.size()); ++i)
      worst = std::max(worst, std::abs(double(a.data[i]) - b.data[i]) / std::max(1e-3, std::abs(double(a.data[i]))));
    return worst;
  };
  for (const std::string& variant : integrator_names()) {
    scene->settings.integrator = variant;
    const Image one_by_one = render_with(*scene, 2, 4, {false, false, false}).to_image();
    const Packets modes[] = {{true, false, false}, {false, true, false}, {false, false, true}, {true, true, true}};
    for (const Packets& m : modes)
      EXPECT_LT(worst_difference(render_with(*scene, 2, 4, m).to_image(), one_by_one), 1e-4)
          << variant << ": camera " << m.camera << " shadow " << m.shadow << " bounce " << m.bounce;
  }
}

// The lockstep loop against paths traced alone: a full PathBatch (256 lanes, 16x16 pixels) gives each lane's
// radiance and AOV exactly as a batch of that lane alone (shadow and bounce packets off, camera rays traced by li:
// the same Embree calls, so bit for bit), for every variant and several samples per lane, on two scenes (one light;
// several lights of three kinds). With shadow and bounce packets on (a bounce's rays in several 16-ray packets), to
// Embree's packet rounding: 1e-4 relative (the largest seen, 2.6e-5, after a packet-rounded hit moved the rest of the
// path; shadow packets alone stayed within 1e-5), far below what a lane's radiance credited to another would give.
// A lane mix-up in the lockstep bookkeeping (a shadow ray or an emission credited to the wrong lane, a lane revived
// or dropped, a packet boundary off by one) fails it.
TEST(EndToEnd, LockstepBatchMatchesPathsTracedAlone) {
  for (const char* file : {"cornell-sphere.json", "night-lights.json"}) {
    auto scene = load_scene(scene_path(file));
    Camera camera = scene->camera;
    camera.prepare(32, 32);
    for (const std::string& variant : integrator_names()) {
      scene->settings.integrator = variant;
      const std::unique_ptr<Integrator> integrator = make_integrator(scene->settings);
      for (uint32_t index = 0; index < 8; ++index) {
        constexpr int n = PathBatch::kMaxLanes;
        Ray rays[n];
        Sampler samplers[n];
        for (int k = 0; k < n; ++k) {
          samplers[k] = Sampler(SamplerType::Independent, 8, 1);
          samplers[k].start(10 + k % 16, 12 + k / 16, index);
          rays[k] = camera.generate_ray({10.5f + k % 16, 12.5f + k / 16});
        }
        for (bool packets : {false, true}) {  // shadow and bounce rays one by one, or in packets
          Sampler lane_samplers[n];
          std::copy(samplers, samplers + n, lane_samplers);
          AovSample aov[n];
          Color radiance[n];
          PathCounters counters;
          PathBatch batch{n, rays, nullptr, lane_samplers, aov, radiance, packets, packets};
          integrator->li(*scene, batch, counters);
          for (int k = 0; k < n; ++k) {
            Sampler alone_sampler = samplers[k];
            AovSample alone_aov;
            Color alone;
            integrator->li(*scene, PathBatch{1, &rays[k], nullptr, &alone_sampler, &alone_aov, &alone, false},
                           counters);
            const std::string where = std::string(file) + " " + variant + " sample " + std::to_string(index) +
                                      " lane " + std::to_string(k) + (packets ? " (packets)" : "");
            for (int c = 0; c < 3; ++c) {
              if (packets)  // hit distances to ~1e-5 relative, and every later vertex of the path moves with them
                EXPECT_NEAR(radiance[k][c], alone[c], 1e-4f * std::max(1.0f, alone[c])) << where;
              else
                EXPECT_EQ(radiance[k][c], alone[c]) << where;
            }
            if (packets)  // bounce packets: li's own camera rays go in packets too
              EXPECT_NEAR(aov[k].depth, alone_aov.depth, 1e-5f * alone_aov.depth) << where;
            else
              EXPECT_EQ(aov[k].depth, alone_aov.depth) << where;
          }
        }
      }
    }
  }
}

// Radiance = the lane's camera ray direction, so a pixel's mean is its own viewing direction.
class DirectionIntegrator final : public Integrator {
 public:
  void li(const Scene&, const PathBatch& batch, PathCounters&) const override {
    for (int k = 0; k < batch.n; ++k) batch.radiance[k] = {batch.rays[k].d.x, batch.rays[k].d.y, batch.rays[k].d.z};
  }
  const char* name() const override { return "direction"; }
};

// The render loop's lanes (16x16 tiles clipped to the image, ordered 4x4 packet by packet) against
// the pixels they are credited to: each pixel's mean camera direction is the direction through its centre, to
// far less than the angle between neighbouring pixels (16 stratified jitters average to within ~0.02 pixel), and
// no pixel is left without samples. A lane credited to another pixel is at least one pixel's angle off.
TEST(EndToEnd, EveryPixelGetsItsOwnCameraRays) {
  auto scene = load_scene(scene_path("cornell-sphere.json"));
  const int w = 37, h = 22;
  for (bool packets : {true, false}) {
    Film film(w, h);
    RenderOptions options;
    options.spp = 16;
    options.threads = 2;
    options.camera_packets = packets;
    render(*scene, DirectionIntegrator(), film, options);
    Camera camera = scene->camera;
    camera.prepare(w, h);
    const float pixel_angle = length(camera.generate_ray({1.5f, 0.5f}).d - camera.generate_ray({0.5f, 0.5f}).d);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const Color m = film.mean(x, y);
        const Vec3 centre = camera.generate_ray({x + 0.5f, y + 0.5f}).d;
        EXPECT_LT(length(Vec3(m[0], m[1], m[2]) - centre), 0.25f * pixel_angle) << x << ", " << y;
      }
  }
}

// A render stops at a pass boundary when cancelled (Ctrl-C) or out of time, and its statistics say what it took.
// The first pass is one sample per pixel, so a cancel requested from the first progress report, or a budget of a
// nanosecond, stops after exactly 1 of the 64 samples per pixel asked for.
TEST(EndToEnd, EarlyStopReportsTheSamplesTaken) {
  auto scene = load_scene(scene_path("cornell-sphere.json"));
  scene->settings.width = 24;
  scene->settings.height = 20;
  const uint64_t pixels = 24 * 20;
  std::atomic<bool> cancel{false};
  int reports = 0;
  RenderOptions by_cancel;
  by_cancel.cancel = &cancel;
  by_cancel.on_progress = [&](const RenderProgress& p) {
    ++reports;
    EXPECT_EQ(p.samples_done, pixels);
    EXPECT_EQ(p.time_budget, 0.0);
    cancel = true;
  };
  RenderOptions by_time;
  by_time.time_budget = 1e-9;
  by_time.on_progress = [&](const RenderProgress& p) {
    EXPECT_EQ(p.time_budget, 1e-9);  // the budget reaches the progress report, whose fraction is then of the time
    EXPECT_EQ(p.fraction(), 1.0);
  };
  for (const RenderOptions& options : {by_cancel, by_time}) {
    const test::Rendered r = test::render_film(*scene, 64, options);
    EXPECT_TRUE(r.stats.stopped_early);
    EXPECT_EQ(r.stats.spp, 1u);
    EXPECT_EQ(r.stats.samples, pixels);
  }
  EXPECT_EQ(reports, 1);
  const test::Rendered full = test::render_film(*scene, 2, {});
  EXPECT_FALSE(full.stats.stopped_early);
  EXPECT_EQ(full.stats.spp, 2u);
  EXPECT_EQ(full.stats.samples, 2 * pixels);
}

// The progress bar's share: of the samples asked for, or of the time budget for a timed render (which asks for 2^20
// spp, so that by samples a 1.5 s render read "0.2 %, ETA 956 s"); whichever is further, never above 1.
TEST(RenderProgress, FractionIsOfTheSamplesOrOfTheBudget) {
  EXPECT_EQ((RenderProgress{16, 64, 3.0, 0}.fraction()), 0.25);
  EXPECT_EQ((RenderProgress{1, uint64_t{1} << 20, 0.75, 1.5}.fraction()), 0.5);
  EXPECT_EQ((RenderProgress{48, 64, 0.75, 1.5}.fraction()), 0.75);  // --spp and --time: the further of the two
  EXPECT_EQ((RenderProgress{1, 64, 2.0, 1.5}.fraction()), 1.0);     // a pass that overshot the budget
  EXPECT_EQ((RenderProgress{0, 0, 0.0, 0}.fraction()), 1.0);
}

TEST(EndToEnd, FurnaceSceneMatchesClosedForm) {
  auto scene = load_scene(scene_path("furnace.json"));
  scene->settings.width = scene->settings.height = 32;
  const Film film = render_with(*scene, 0, 64);
  const double z_max = test::sidak_z(0.01, 6);
  // Centre block: on the sphere; corner blocks: background (the sphere covers the middle of the frame).
  const test::RegionMean centre =
      test::region_mean(film, [](int x, int y) { return x >= 12 && x < 20 && y >= 12 && y < 20; });
  const test::RegionMean corner = test::region_mean(film, [](int x, int y) { return x < 3 && y < 3; });
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(std::abs(centre.mean[c] - 0.8), z_max * std::sqrt(centre.var[c]) + 1e-6) << "sphere " << centre.mean[c];
    EXPECT_LT(std::abs(corner.mean[c] - 1.0), z_max * std::sqrt(corner.var[c]) + 1e-6)
        << "background " << corner.mean[c];
  }
}

}  // namespace
}  // namespace lumis
