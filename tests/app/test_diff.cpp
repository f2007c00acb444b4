// `lumis diff` internals: metrics against hand-computed values, the per-pixel z-test on synthetic noise with known
// variance, mismatch errors, and the heatmap and font that draw the pictures.
#include <gtest/gtest.h>

#include <cmath>

#include "app/diff.h"
#include "app/montage.h"
#include "core/rng.h"

using namespace lumis;

namespace {

Image rgb_image(int w, int h, const std::vector<float>& values) {
  Image img(w, h, {"R", "G", "B"});
  img.data = values;
  return img;
}

// A 2x1 pair whose differences are 0.5 (pixel 0, R) and -0.2 (pixel 1, G), all else equal.
Image tiny_a() { return rgb_image(2, 1, {1.0f, 0.0f, 0.5f, 0.0f, 0.0f, 0.0f}); }
Image tiny_b() { return rgb_image(2, 1, {0.5f, 0.0f, 0.5f, 0.0f, 0.2f, 0.0f}); }

double gaussian(Pcg32& rng) {
  // Box-Muller; 1 - u keeps the logarithm finite.
  const double u1 = 1.0 - rng.next_double(), u2 = rng.next_double();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

// Mean + Gaussian noise of the given standard deviation of the mean, with variance channels stating it.
Image noisy_render(int w, int h, double mean, double sigma, uint64_t seed) {
  Image img(w, h, {"R", "G", "B", "variance.R", "variance.G", "variance.B"});
  Pcg32 rng(seed, 7);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 3; ++k) {
        img.at(x, y, k) = static_cast<float>(mean + sigma * gaussian(rng));
        img.at(x, y, 3 + k) = static_cast<float>(sigma * sigma);
      }
  return img;
}

}  // namespace

TEST(DiffMetrics, HandComputedValuesAndOptions) {
  {  // HandComputedValues
    const DiffMetrics m = compute_metrics(tiny_a(), tiny_b());
    const double mse = (0.25 + 0.04) / 6;
    EXPECT_NEAR(m.mse, mse, 1e-7);
    EXPECT_NEAR(m.rmse, std::sqrt(mse), 1e-7);
    EXPECT_NEAR(m.mae, 0.7 / 6, 1e-7);
    // (a - b)^2 / (b^2 + 0.01): 0.25 / 0.26 and 0.04 / 0.05, over six pixel-channels.
    EXPECT_NEAR(m.rel_mse, (0.25 / 0.26 + 0.04 / 0.05) / 6, 1e-7);
    EXPECT_NEAR(m.max_abs, 0.5, 1e-7);
    EXPECT_NEAR(m.psnr, 10 * std::log10(1 / mse), 1e-5);
    EXPECT_DOUBLE_EQ(m.psnr_peak, 1.0);
    EXPECT_DOUBLE_EQ(m.over_tolerance_percent, 100.0);
    EXPECT_EQ(m.nonfinite, 0u);
  }
  {  // ToleranceAndPeakOptions
    DiffOptions o;
    o.tolerance = 0.3;  // only pixel 0 (error 0.5) is over
    o.psnr_peak = 0;    // the reference's largest value, 0.5
    const DiffMetrics m = compute_metrics(tiny_a(), tiny_b(), o);
    EXPECT_DOUBLE_EQ(m.over_tolerance_percent, 50.0);
    EXPECT_NEAR(m.psnr_peak, 0.5, 1e-7);
    EXPECT_NEAR(m.psnr, 10 * std::log10(0.25 / ((0.25 + 0.04) / 6)), 1e-5);
  }
  {  // ExtremePeaks: the square of the peak would overflow (1e320) or underflow (1e-340) a double
    DiffOptions o;
    o.psnr_peak = 1e160;
    const DiffMetrics high = compute_metrics(tiny_a(), tiny_b(), o);
    EXPECT_NEAR(high.psnr, 3200 - 10 * std::log10(high.mse), 1e-9);
    EXPECT_NEAR(high.psnr, 3200 - 10 * std::log10((0.25 + 0.04) / 6), 1e-5);
    o.psnr_peak = 1e-170;
    const DiffMetrics low = compute_metrics(tiny_a(), tiny_b(), o);
    EXPECT_NEAR(low.psnr, -3400 - 10 * std::log10(low.mse), 1e-9);
  }
}

TEST(DiffMetrics, ThresholdsNonFiniteAndChannelOrder) {
  {  // IdenticalImagesAndThresholds
    const DiffMetrics m = compute_metrics(tiny_b(), tiny_b());
    EXPECT_EQ(m.mse, 0.0);
    EXPECT_TRUE(std::isinf(m.psnr));
    EXPECT_EQ(m.over_tolerance_percent, 0.0);
    EXPECT_TRUE(metric_passes("mse", 0.01, 0.01));
    EXPECT_FALSE(metric_passes("mse", 0.011, 0.01));
    EXPECT_TRUE(metric_passes("psnr", 40, 30));  // higher PSNR is better
    EXPECT_FALSE(metric_passes("psnr", 20, 30));
    EXPECT_FALSE(metric_passes("mse", std::nan(""), 1.0));
    const DiffMetrics t = compute_metrics(tiny_a(), tiny_b());
    EXPECT_DOUBLE_EQ(metric_value(t, "relmse"), t.rel_mse);
    EXPECT_DOUBLE_EQ(metric_value(t, "over"), t.over_tolerance_percent);
    EXPECT_THROW(metric_value(t, "ssim"), std::invalid_argument);
  }
  {  // NonFiniteMakesMetricsNaN
    Image a = tiny_a();
    a.data[1] = NAN;
    const DiffMetrics m = compute_metrics(a, tiny_b());
    EXPECT_EQ(m.nonfinite, 1u);
    EXPECT_TRUE(std::isnan(m.mse));
    EXPECT_FALSE(metric_passes("mse", m.mse, 1e9));
    // Every metric, `over` included: one NaN pixel among many must not pass a threshold on the share of pixels.
    for (const std::string& name : metric_names())
      EXPECT_FALSE(metric_passes(name, metric_value(m, name), name == "psnr" ? -1e9 : 1e9)) << name;
  }
  {  // ChannelsFoundByNameNotPosition
    Image b(2, 1, {"B", "G", "R", "A"});
    const Image ref = tiny_b();
    for (int x = 0; x < 2; ++x)
      for (int k = 0; k < 3; ++k) b.at(x, 0, 2 - k) = ref.at(x, 0, k);
    EXPECT_EQ(compute_metrics(ref, b).mse, 0.0);
  }
}

TEST(DiffMetrics, MismatchesAreErrorsNamingBothImages) {
  DiffOptions o;
  o.name_a = "left.exr";
  o.name_b = "right.exr";
  try {
    compute_metrics(tiny_a(), rgb_image(1, 2, std::vector<float>(6, 0.0f)), o);
    FAIL() << "size mismatch accepted";
  } catch (const DiffError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("left.exr"), std::string::npos) << msg;
    EXPECT_NE(msg.find("right.exr"), std::string::npos) << msg;
    EXPECT_NE(msg.find("2x1"), std::string::npos) << msg;
  }
  Image alpha_only(2, 1, {"A"});
  try {
    compute_metrics(tiny_a(), alpha_only, o);
    FAIL() << "missing channels accepted";
  } catch (const DiffError& e) {
    EXPECT_NE(std::string(e.what()).find("right.exr"), std::string::npos) << e.what();
  }
  EXPECT_THROW(z_test(tiny_a(), tiny_b(), {}, o), DiffError);  // reference without variance channels
}

TEST(DiffMetrics, AGreyImageComparesAsEqualRGB) {
  // One channel named Y (a greyscale PNG as OpenImageIO reads it) stands for R = G = B.
  Image grey(2, 1, {"Y"});
  grey.at(0, 0, 0) = 0.25f;
  grey.at(1, 0, 0) = 0.5f;
  const Image rgb = rgb_image(2, 1, {0.25f, 0.25f, 0.25f, 0.5f, 0.5f, 0.5f});
  EXPECT_EQ(compute_metrics(grey, rgb).mse, 0.0);
  const Image off = rgb_image(2, 1, {0.25f, 0.25f, 0.35f, 0.5f, 0.5f, 0.5f});
  EXPECT_NEAR(compute_metrics(grey, off).max_abs, 0.1, 1e-6);
}

TEST(DiffMetrics, YIsGreyOnlyWithoutOtherColourChannels) {
  // Y with an alpha channel is still grey; Y beside X and Z (an XYZ image) is not, and is refused by name.
  Image grey_alpha(2, 1, {"Y", "A"});
  grey_alpha.data = {0.25f, 1.0f, 0.5f, 1.0f};
  const Image rgb = rgb_image(2, 1, {0.25f, 0.25f, 0.25f, 0.5f, 0.5f, 0.5f});
  EXPECT_TRUE(is_grey(grey_alpha));
  EXPECT_FALSE(is_grey(rgb));
  EXPECT_EQ(compute_metrics(grey_alpha, rgb).mse, 0.0);
  Image xyz(2, 1, {"X", "Y", "Z"});
  EXPECT_FALSE(is_grey(xyz));
  // Channels that are not colour beside a grey Y (a depth Z, normals) are ignored, as they are beside R, G, B.
  EXPECT_TRUE(is_grey(Image(2, 1, {"Y", "Z", "N.X", "N.Y", "N.Z"})));
  EXPECT_FALSE(is_grey(Image(2, 1, {"R", "G", "B", "Y"})));
  DiffOptions o;
  o.name_a = "xyz.exr";
  try {
    compute_metrics(xyz, rgb, o);
    FAIL() << "an XYZ image compared as grey";
  } catch (const DiffError& e) {
    EXPECT_NE(std::string(e.what()).find("xyz.exr: no R, G, B channel (has X, Y, Z)"), std::string::npos) << e.what();
  }
}

// Two independent renders of the same mean: 64x64x3 = 12288 pixel-channels, each with sigma 0.01 (A) and 0.02 (B)
// and both variances stated. Alpha 0.01 is family-wise (Sidak), so this passes with probability 0.99 for a fresh
// seed: the false-failure rate is 1%; seeds 1 and 2 are fixed so the outcome is deterministic.
TEST(DiffZTest, AcceptsIndependentNoiseWithKnownVariance) {
  const Image a = noisy_render(64, 64, 0.5, 0.01, 1), b = noisy_render(64, 64, 0.5, 0.02, 2);
  const ZTestResult r = z_test(a, b, ZTestOptions{0.01});
  EXPECT_TRUE(r.passed) << r.rejected << " rejected, min p " << r.min_p;
  EXPECT_TRUE(r.used_a_variance);
  EXPECT_EQ(r.tested, 12288u);
  EXPECT_NEAR(r.per_test_alpha, 1 - std::pow(0.99, 1.0 / 12288), 1e-12);
  // Min p over 12288 null p-values is about 1/12288; far above 1e-2 would mean the variances were not used.
  EXPECT_LT(r.min_p, 1e-2);
  EXPECT_GT(r.min_p, r.per_test_alpha);
}

TEST(DiffZTest, RejectsShiftedMeanAndSingleOutlier) {
  const Image b = noisy_render(64, 64, 0.5, 0.02, 2);
  // Shift by 6 combined standard deviations (sqrt(0.01^2 + 0.02^2) = 0.0224): |z| ~ N(6, 1) against a Sidak
  // threshold of |z| = 4.9, so most pixel-channels are rejected.
  const Image shifted = noisy_render(64, 64, 0.5 + 6 * 0.02236, 0.01, 1);
  const ZTestResult r = z_test(shifted, b);
  EXPECT_FALSE(r.passed);
  EXPECT_GT(r.failing_fraction(), 0.5);
  // One channel of one pixel 10 sigma off in an otherwise matching image: exactly that one is rejected.
  Image one = noisy_render(64, 64, 0.5, 0.01, 1);
  one.at(17, 9, 1) = b.at(17, 9, 1) + 10 * 0.02236f;
  const ZTestResult o = z_test(one, b);
  EXPECT_FALSE(o.passed);
  EXPECT_EQ(o.rejected, 1u);
  EXPECT_EQ(o.worst_x, 17);
  EXPECT_EQ(o.worst_y, 9);
  EXPECT_EQ(o.worst_channel, 1);
}

TEST(DiffZTest, ReferenceVarianceAloneAndZeroVariance) {
  Image b = noisy_render(4, 4, 0.5, 0.02, 2);
  Image a = rgb_image(4, 4, std::vector<float>(b.data.size() / 2, 0.0f));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      for (int k = 0; k < 3; ++k) a.at(x, y, k) = b.at(x, y, k);
  // Background pixel: no variance; identical values pass, a difference beyond 1e-5 relative fails.
  b.at(0, 0, 0) = 0.25f;
  b.at(0, 0, 3) = 0.0f;
  a.at(0, 0, 0) = 0.25f;
  ZTestResult r = z_test(a, b);
  EXPECT_FALSE(r.used_a_variance);
  EXPECT_TRUE(r.passed);
  EXPECT_EQ(r.zero_variance, 1u);
  EXPECT_EQ(r.zero_variance_rejected, 0u);
  EXPECT_EQ(r.unscored_x, -1);
  EXPECT_EQ(r.scored(), 4u * 4 * 3 - 1);
  a.at(0, 0, 0) = 0.25f * (1 + 1e-4f);
  r = z_test(a, b);
  EXPECT_FALSE(r.passed);
  EXPECT_EQ(r.rejected, 1u);
  EXPECT_EQ(r.zero_variance_rejected, 1u);
  EXPECT_EQ(r.unscored_x, 0);  // where: min_p, over scored pixel-channels only, cannot say
  EXPECT_EQ(r.unscored_y, 0);
  EXPECT_EQ(r.unscored_channel, 0);
  a.at(0, 0, 0) = 0.25f;
  b.at(1, 1, 4) = -1.0f;  // a negative variance is corrupt data, never a pass
  r = z_test(a, b);
  EXPECT_FALSE(r.passed);
  EXPECT_EQ(r.nonfinite, 1u);
  EXPECT_EQ(r.scored(), 4u * 4 * 3 - 2);  // the zero-variance (0, 0) R and the corrupt (1, 1) G
  EXPECT_EQ(r.zero_variance_rejected, 0u);
  EXPECT_EQ(r.unscored_x, 1);  // variance.G of pixel (1, 1)
  EXPECT_EQ(r.unscored_y, 1);
  EXPECT_EQ(r.unscored_channel, 1);
  // Also when the tested image's own variance would make the sum positive (or zero), in either image.
  Image av(4, 4, {"R", "G", "B", "variance.R", "variance.G", "variance.B"});
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      for (int k = 0; k < 6; ++k) av.at(x, y, k) = b.at(x, y, k);
  b.at(1, 1, 4) = b.at(2, 2, 4);
  av.at(1, 1, 4) = b.at(1, 1, 4);
  ASSERT_TRUE(z_test(av, b).passed);
  for (const float neg_b : {-5e-4f, -1e-4f}) {
    Image bb = b, aa = av;
    bb.at(1, 1, 4) = neg_b;
    aa.at(1, 1, 4) = 5e-4f;
    EXPECT_FALSE(z_test(aa, bb).passed) << neg_b;
    EXPECT_FALSE(z_test(bb, aa).passed) << neg_b;  // the negative one in the tested image
  }
}

// The variance of a difference is the sum of both images' variances: a 1x1 image 0.04 above the reference, whose
// own variance is 8e-4 against the reference's 1e-4, is 0.04 / 0.03 = 1.33 standard deviations off (p = 0.18) and
// passes; without its variance channels it is 4 off (p = 6.3e-5, below the per-test alpha 0.0033) and fails.
// Deterministic.
TEST(DiffZTest, BothImagesVariancesAdd) {
  Image b(1, 1, {"R", "G", "B", "variance.R", "variance.G", "variance.B"});
  Image a = b;
  for (int k = 0; k < 3; ++k) {
    b.at(0, 0, k) = 0.5f;
    b.at(0, 0, 3 + k) = 1e-4f;
    a.at(0, 0, k) = k == 1 ? 0.54f : 0.5f;
    a.at(0, 0, 3 + k) = 8e-4f;
  }
  const ZTestResult both = z_test(a, b);
  EXPECT_TRUE(both.used_a_variance);
  EXPECT_TRUE(both.passed) << both.min_p;
  EXPECT_NEAR(both.min_p, std::erfc(0.04 / 0.03 / std::sqrt(2.0)), 1e-4);
  EXPECT_EQ(both.worst_channel, 1);
  Image plain = rgb_image(1, 1, {0.5f, 0.54f, 0.5f});
  const ZTestResult alone = z_test(plain, b);
  EXPECT_FALSE(alone.used_a_variance);
  EXPECT_FALSE(alone.passed);
  EXPECT_EQ(alone.rejected, 1u);
  EXPECT_NEAR(alone.min_p, std::erfc(4 / std::sqrt(2.0)), 1e-6);
}

TEST(DiffPictures, HeatmapRampAndFont) {
  {  // ErrorMapAndColourBar
    const std::vector<float> e = abs_error_map(tiny_a(), tiny_b());
    ASSERT_EQ(e.size(), 2u);
    EXPECT_NEAR(e[0], 0.5 / 3, 1e-6);
    EXPECT_NEAR(e[1], 0.2 / 3, 1e-6);
    const Image h = error_heatmap(e, 2, 1, 0, 0.5 / 3);
    // A 2x1 map is enlarged to 128 pixels wide; pixel 0 is the top of the ramp, pixel 1 is 40% up it.
    EXPECT_GE(h.width, 128);
    const Color top = false_colour(1), mid = false_colour(0.4f);
    const Color p0 = h.rgb(6 + 10, 6), p1 = h.rgb(6 + 64 + 10, 6);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(p0[k], top[k], 1e-6);
      EXPECT_NEAR(p1[k], mid[k], 1e-6);
    }
  }
  {  // NonFiniteErrorsShowMagenta: a NaN in the map is not drawn as "no error"
    const Image h = error_heatmap({NAN, 0.1f}, 2, 1, 0, 0.2);
    const Color nan_px = h.rgb(6 + 10, 6), ok_px = h.rgb(6 + 64 + 10, 6), half = false_colour(0.5f);
    EXPECT_EQ(nan_px, Color(1, 0, 1));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(ok_px[k], half[k], 1e-6);
  }
  {  // RampBrightensMonotonically
    float prev = -1;
    for (int i = 0; i <= 64; ++i) {
      const float l = luminance(false_colour(i / 64.0f));
      EXPECT_GT(l, prev) << "at t = " << i / 64.0;
      prev = l;
    }
  }
  {  // GlyphsDrawWhereExpected
    Image c = make_canvas(20, 10, Color(0));
    draw_text(c, 1, 1, "T", Color(1));
    // 'T': full top row, then only the middle column.
    for (int x = 0; x < 5; ++x) EXPECT_EQ(c.at(1 + x, 1, 0), 1.0f) << x;
    EXPECT_EQ(c.at(3, 5, 0), 1.0f);
    EXPECT_EQ(c.at(1, 5, 0), 0.0f);
    EXPECT_EQ(text_width("ab", 1), 11);
    EXPECT_EQ(text_width("ab", 2), 22);
    // Lower case maps to upper case; unknown characters get the hollow box, not a blank.
    EXPECT_EQ(glyph_rows('e')[0], glyph_rows('E')[0]);
    EXPECT_EQ(glyph_rows('~')[0], 0x1f);
    EXPECT_EQ(glyph_rows('~')[3], 0x11);
  }
}
