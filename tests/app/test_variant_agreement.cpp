// All five integrator variants converge to the same image on the shipped scenes, and the efficiency claims of the
// lecture hold on them.
//
// Agreement: each variant's image (low resolution, fixed seed) is compared with a high-sample nee_mis reference by
// z-tests on region means (4x4-pixel blocks, per channel): z = (a - ref) / sqrt(var_a + var_ref), with variances
// from the films' per-pixel variance of the mean (an over-estimate for the stratified sampler, so conservative).
// Level: alpha = 0.01 per scene, Sidak-split over every block, channel and variant, so a correct renderer fails a
// scene with probability below 1% at any seed; the fixed seeds make a pass reproducible.
//
// Efficiency (deterministic at the fixed seed, measured numbers recorded in docs/estimators.md): on veach-mis with
// max depth 1, nee_mis has lower MSE than bsdf and than light at equal samples; on night-lights, importance light
// selection has lower MSE than uniform selection at equal samples.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "app/scene_loader.h"
#include "integrators/render.h"
#include "tests/support/render_film.h"
#include "tests/support/test_dir.h"
#include "tests/support/render_stats.h"

namespace lumis {
namespace {

std::string scene_path(const char* name) { return std::string(LUMIS_SOURCE_DIR) + "/scenes/" + name; }

// LUMIS_AGREEMENT_SEED overrides the variants' seed (default 1), to measure the tests' false-failure rate.
uint32_t test_seed() {
  const char* s = std::getenv("LUMIS_AGREEMENT_SEED");
  return s ? static_cast<uint32_t>(std::strtoul(s, nullptr, 10)) : 1u;
}

struct Config {
  int size = 24;
  int max_depth = 3;
  uint32_t spp = 128, reference_spp = 2048;
  int block = 4;            ///< block side in pixels
  uint32_t slow_spp = 0;    ///< spp for uniform/bsdf/light when they need more than `spp` (heavy tails)
  bool skip_uniform = false;
  std::string edit_from, edit_to;  ///< when set: render the scene file with this text replaced (a variant scene)
  int rr_depth = 0;         ///< Russian roulette off (see the note above expect_agreement)
};

Film render_variant(Scene& scene, const std::string& integrator, uint32_t spp, uint32_t seed) {
  scene.settings.integrator = integrator;
  scene.settings.seed = seed;
  return test::render_film(scene, spp).film;
}

std::unique_ptr<Scene> load_small(const char* name, const Config& s) {
  std::string path = scene_path(name);
  if (!s.edit_from.empty()) {
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t at = text.find(s.edit_from);
    if (at == std::string::npos) throw std::runtime_error(path + " has no " + s.edit_from);
    text.replace(at, s.edit_from.size(), s.edit_to);
    path = (test::fresh_test_dir("lumis_agreement") / name).string();
    std::ofstream(path) << text;
  }
  auto scene = load_scene(path);
  if (!s.edit_from.empty()) std::filesystem::remove_all(std::filesystem::path(path).parent_path());  // loaded
  const float aspect = static_cast<float>(scene->settings.width) / static_cast<float>(scene->settings.height);
  scene->settings.height = s.size;
  scene->settings.width = std::max(4, static_cast<int>(std::lround(s.size * aspect)) / 4 * 4);
  scene->settings.max_depth = s.max_depth;
  scene->settings.rr_depth = s.rr_depth;
  return scene;
}

// Russian roulette is off here: with q = max(beta), a path that survives a low q carries its whole remaining
// radiance (often a light seen directly), a rare large value that 4096 samples per block do not average out. With
// it on, `mis` (whose light-sampled directions near the light get small weights, so low q) failed 2 of 12 seeds on
// cornell-sphere and 3 of 12 on the rough variant, always low; with it off, 0 of 10 and 0 of 12. Roulette's
// unbiasedness is tested where the answer is exact (tests/unit/test_integrators_analytic.cpp, closed sphere).
void expect_agreement(const char* name, const Config& cfg) {
  auto scene = load_small(name, cfg);
  const Film ref = render_variant(*scene, "nee_mis", cfg.reference_spp, 1000);
  const int bw = cfg.block, nbx = ref.width() / bw, nby = ref.height() / bw;
  const int n_variants = cfg.skip_uniform ? 4 : 5;
  const double z_max = test::sidak_z(0.01, static_cast<double>(nbx) * nby * 3 * n_variants);
  for (const char* variant : {"uniform", "bsdf", "light", "mis", "nee_mis"}) {
    if (cfg.skip_uniform && std::string(variant) == "uniform") continue;
    const bool slow = cfg.slow_spp && std::string(variant) != "mis" && std::string(variant) != "nee_mis";
    const Film img = render_variant(*scene, variant, slow ? cfg.slow_spp : cfg.spp, test_seed());
    int rejected = 0;
    double worst = 0;
    for (int by = 0; by < nby; ++by)
      for (int bx = 0; bx < nbx; ++bx) {
        auto in_block = [&](int x, int y) { return x / bw == bx && y / bw == by; };
        const test::RegionMean a = test::region_mean(img, in_block), r = test::region_mean(ref, in_block);
        for (int c = 0; c < 3; ++c) {
          const double sd = std::sqrt(a.var[c] + r.var[c]);
          const double diff = std::abs(a.mean[c] - r.mean[c]);
          const double z = sd > 0 ? diff / sd : (diff > 1e-6 ? INFINITY : 0);
          worst = std::max(worst, z);
          if (z > z_max) {
            ++rejected;
            std::printf("%s: %s block (%d, %d) channel %d: %g, reference %g, z %.2f\n", name, variant, bx, by, c,
                        a.mean[c], r.mean[c], z);
          }
        }
      }
    EXPECT_EQ(rejected, 0) << name << ": " << variant << " disagrees with the reference in " << rejected
                           << " block-channels (largest z " << worst << ", limit " << z_max << ")";
  }
}

// `uniform` is left out on the shipped Cornell box: its copper sphere (roughness 0.25, GGX alpha 0.0625) reflects
// the small sphere light into caustics on the floor, which uniform directions find so rarely that the block means
// are still heavy-tailed at thousands of samples (measured at the fixed reference: uniform failed 10 of 12 seeds at
// 256 spp and 1 of 8 at 8192 spp, always low; at 131072 spp the worst block's red mean was 0.158 against nee_mis's
// 0.155, so it converges, slowly). It is checked on the same box with a rough copper sphere below.
TEST(VariantAgreement, CornellSphere) {
  Config cfg{24, 3, 256, 2048};
  cfg.skip_uniform = true;
  expect_agreement("cornell-sphere.json", cfg);
}

// The same box with the copper sphere at roughness 0.7 (alpha 0.49): glossy, but with a lobe wide enough for
// uniform sampling's block means to be near normal at 1024 spp. All five variants.
TEST(VariantAgreement, CornellRoughSphere) {
  Config cfg{24, 3, 256, 2048};
  cfg.slow_spp = 1024;
  cfg.edit_from = "\"roughness\": 0.25";
  cfg.edit_to = "\"roughness\": 0.7";
  expect_agreement("cornell-sphere.json", cfg);
}

// Veach's scene is built to defeat single strategies: light sampling on the near-mirror plate and BSDF sampling of
// the tiny lights are heavy-tailed, and a z-test needs enough hits of those rare paths for the central limit
// theorem to hold. So the single-strategy variants get more samples, and blocks are 6x6 pixels. At 8192 samples,
// `light` failed at seed 1 (z 4.2, low, in the block where the top plate mirrors the 0.1-radius light). A heavy
// tail, not a bias: that block's mean at other seeds is 11 % low at 8192 samples, 4 % at 131072 and 1.5 % at
// 1048576 (z 0.9, 1.1 and 1.1 against its own error). At 32768 samples, seeds 1-13 all pass.
// `uniform` is left out here: on the smoothest plate (alpha 0.0025) a uniform hemisphere direction lands in the
// specular lobe with probability about 1e-6, so no affordable sample count converges (at 8192 spp its largest
// block z was 19, its image still missing the reflections). Its unbiasedness is shown by the analytic tests and
// by the Cornell-box agreement above.
TEST(VariantAgreement, VeachMisDirect) {
  Config cfg{12, 1, 512, 4096, 6, 32768};
  cfg.skip_uniform = true;
  expect_agreement("veach-mis.json", cfg);
}

// Relative MSE, (a - ref)^2 / (ref^2 + 0.01) averaged over pixels and channels (as `lumis compare` reports): plain
// MSE would be dominated by the anti-aliased edges of directly visible lights, which every strategy shares.
double mse(const Film& a, const Film& b) {
  double s = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Color d = a.mean(x, y) - b.mean(x, y), r = b.mean(x, y);
      for (int c = 0; c < 3; ++c) s += d[c] * d[c] / (r[c] * r[c] + 0.01) / 3;
    }
  return s / (static_cast<double>(a.width()) * a.height());
}

TEST(Efficiency, VeachMisNeeMisBeatsBsdfAndLight) {
  auto scene = load_small("veach-mis.json", Config{32, 1});
  const Film ref = render_variant(*scene, "nee_mis", 4096, 1000);
  const double e_mis = mse(render_variant(*scene, "nee_mis", 16, 1), ref);
  const double e_bsdf = mse(render_variant(*scene, "bsdf", 16, 1), ref);
  const double e_light = mse(render_variant(*scene, "light", 16, 1), ref);
  std::printf("veach-mis, max depth 1, 16 spp: relMSE nee_mis %.4g, bsdf %.4g, light %.4g\n", e_mis, e_bsdf, e_light);
  EXPECT_LT(e_mis, e_bsdf);
  EXPECT_LT(e_mis, e_light);
}

TEST(Efficiency, NightLightsImportanceBeatsUniformSelection) {
  // 64x48: at 32x24 a handful of pixels decide the comparison (measured at seeds 1-3 and 64x48: importance
  // relMSE 0.052-0.072, uniform 0.149-0.159, power 0.159-0.175).
  auto scene = load_small("night-lights.json", Config{48, 1});
  const Film ref = render_variant(*scene, "nee_mis", 1024, 1000);
  scene->settings.light_selection = LightSelection::Uniform;
  scene->update_light_selector();
  const double e_uniform = mse(render_variant(*scene, "nee_mis", 16, 1), ref);
  scene->settings.light_selection = LightSelection::Importance;
  scene->update_light_selector();
  const double e_importance = mse(render_variant(*scene, "nee_mis", 16, 1), ref);
  std::printf("night-lights, max depth 1, 16 spp: relMSE importance %.4g, uniform %.4g\n", e_importance, e_uniform);
  EXPECT_LT(e_importance, e_uniform);
}

}  // namespace
}  // namespace lumis
