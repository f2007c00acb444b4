// The tile renderer's sample indices under a time budget (integrators/render.cpp): the count a render stops at is
// not known in advance, and the stratified sampler must still give stratified sets, not a random handful of the
// strata of one set sized for the 2^20 samples the budget allows.
#include <gtest/gtest.h>

#include <cmath>

#include "core/film.h"
#include "integrators/render.h"

namespace lumis {
namespace {

/// Radiance 1 where the lane's first sampler dimension after the pixel jitter is below 1/2, else 0: a pixel's mean
/// times its sample count is how many of its samples fell there.
class LowerHalf : public Integrator {
 public:
  void li(const Scene&, const PathBatch& batch, PathCounters&) const override {
    for (int k = 0; k < batch.n; ++k) batch.radiance[k] = Color(batch.samplers[k].get1d() < 0.5f ? 1.0f : 0.0f);
  }
  const char* name() const override { return "lower-half"; }
};

// Independent samples put Binomial(N, 1/2) of a pixel's N samples in the lower half: the squared deviation from
// N/2, summed over the pixels, has expectation pixels x N / 4. Stratified blocks of 1, 2, 4, 8, ... samples put
// exactly half of each block of 2 or more there; only the first sample and the unfinished last block deviate
// (hypergeometric), which bounds the expected ratio to the independent one by about 1/6 + 1/N (measured 0.10 to
// 0.16 in 6 runs of about 5000 samples per pixel). One stratified set sized for 2^20 samples, as before, measured
// 0.97 to 0.98 (3 runs): its ratio is 1 with a standard deviation of sqrt(2 / 1024) = 0.044 over 32 x 32 pixels, so
// the bound of 0.5 is 11 standard deviations below it. The stratified ratio is a mean over 1024 independent pixels
// of terms with mean at most 1/6 + 1/N and a standard deviation of about 0.3 (near-normal deviations), so 0.5 is
// about 36 of its standard deviations away: a false failure has probability below 1e-3 by Chebyshev's inequality,
// and far less in practice.
TEST(RenderTimeBudget, StratifiedSamplesStayStratifiedWhereverTheRenderStops) {
  Scene scene;
  scene.settings.sampler = SamplerType::Stratified;
  scene.settings.seed = 7;
  Film film(32, 32);
  RenderOptions options;
  options.spp = 1u << 20;
  options.time_budget = 0.25;
  options.camera_packets = false;  // no geometry: the integrator never traces
  const RenderStats stats = render(scene, LowerHalf(), film, options);
  ASSERT_TRUE(stats.stopped_early);
  const double n = stats.spp;
  ASSERT_GE(n, 8) << "too few samples in the budget to tell";
  double squared = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      ASSERT_EQ(film.count(x, y), stats.spp);
      const double below = film.mean(x, y).x * n;
      squared += (below - n / 2) * (below - n / 2);
    }
  const double ratio = squared / (32 * 32 * n / 4);
  EXPECT_LT(ratio, 0.5) << "at " << n << " samples per pixel";
}

}  // namespace
}  // namespace lumis
