// Environment lights: a synthetic 32x16 map with a bright spot (rotated), whose sampled directions must follow
// pdf() (chi-square) and whose pdf integrates to 1; a constant map and the constant environment give 1/(4 pi);
// radiance is the nearest texel, zero wherever the density is zero; sample() agrees with pdf() and le_escaped().
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <cstdio>

#include "core/chi2.h"
#include "lights/light.h"

namespace lumis {
namespace {

// Chi-square family: 2 tests (spot map, constant environment), Sidak-corrected alpha 0.01 for the family
// (1% false failures per run); seeds fixed.
constexpr int kChiTests = 2;

// 32x16 map: dim sky, a bright 3x2-texel spot at columns 20-22, rows 4-5 (above the horizon), one black row band.
std::shared_ptr<Image> spot_map() {
  auto img = std::make_shared<Image>(32, 16, std::vector<std::string>{"R", "G", "B"});
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) {
      const float v = (y == 12) ? 0.0f : 0.2f + 0.01f * x;
      for (int c = 0; c < 3; ++c) img->at(x, y, c) = v;
    }
  for (int y = 4; y <= 5; ++y)
    for (int x = 20; x <= 22; ++x) {
      img->at(x, y, 0) = 60;
      img->at(x, y, 1) = 50;
      img->at(x, y, 2) = 40;
    }
  return img;
}

const LightSampleContext kCtx{{0.3f, 0.1f, -0.2f}, {0, 1, 0}};

TEST(EnvironmentLight, MapDirectionsFollowPdf) {
  const auto light = make_image_environment(spot_map(), 1.5f, 30.0f);
  DirectionalTest cfg;
  // Texel edges cross almost every histogram cell, and each crossing costs the expected-count quadrature a
  // refinement: a 20 x 40 grid keeps this test to about a second.
  cfg.cos_theta_bins = 20;
  cfg.phi_bins = 40;
  cfg.samples = 200'000;
  cfg.num_tests = kChiTests;
  cfg.seed = 81;
  cfg.integration_resolution = 2;  // adaptive refinement does the work at the edges
  const Hit none;
  const auto r = chi_square_directions(
      [&](Pcg32& rng) -> std::optional<Vec3> {
        const auto s = light->sample(kCtx, {rng.next_float(), rng.next_float()});
        if (!s) return std::nullopt;
        return s->wi;
      },
      [&](Vec3 w) { return light->pdf(kCtx, w, none); }, cfg);
  EXPECT_TRUE(r.passed) << r.message;
  std::printf("spot map: %s\n", r.message.c_str());
  EXPECT_NEAR(integrate_over_sphere([&](Vec3 w) { return light->pdf(kCtx, w, none); }, 256), 1.0, 2e-3);
}

TEST(EnvironmentLight, ConstantEnvironmentIsUniform) {
  const auto light = make_constant_environment({0.5f, 0.6f, 0.7f});
  DirectionalTest cfg;
  cfg.samples = 200'000;
  cfg.num_tests = kChiTests;
  cfg.seed = 82;
  const Hit none;
  const auto r = chi_square_directions(
      [&](Pcg32& rng) -> std::optional<Vec3> {
        const auto s = light->sample(kCtx, {rng.next_float(), rng.next_float()});
        EXPECT_FLOAT_EQ(s->pdf, 1 / (4 * kPi));
        return s->wi;
      },
      [&](Vec3 w) { return light->pdf(kCtx, w, none); }, cfg);
  EXPECT_TRUE(r.passed) << r.message;
  EXPECT_EQ(light->le_escaped({0, 1, 0}), Color(0.5f, 0.6f, 0.7f));
  EXPECT_TRUE(light->is_environment());
  EXPECT_NEAR(light->importance(kCtx), 2 * kPi * luminance({0.5f, 0.6f, 0.7f}), 1e-5f);
  EXPECT_NEAR(light->importance({kCtx.p, {0, 0, 0}}), 4 * kPi * luminance({0.5f, 0.6f, 0.7f}), 1e-5f);
}

TEST(EnvironmentLight, ConstantMapGivesOneOverFourPi) {
  auto img = std::make_shared<Image>(32, 16, std::vector<std::string>{"R", "G", "B"});
  std::fill(img->data.begin(), img->data.end(), 0.25f);
  const auto light = make_image_environment(img, 2.0f, 17.0f);
  Pcg32 rng(83, 1);
  const Hit none;
  for (int i = 0; i < 1000; ++i) {
    const auto s = light->sample(kCtx, {rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(s->pdf * 4 * kPi, 1.0f, 1e-4f);
    const float z = 2 * rng.next_float() - 1, phi = 2 * kPi * rng.next_float(), r = std::sqrt(1 - z * z);
    EXPECT_NEAR(light->pdf(kCtx, {r * std::cos(phi), z, r * std::sin(phi)}, none) * 4 * kPi, 1.0f, 1e-4f);
  }
  EXPECT_EQ(light->le_escaped({0, 1, 0}), Color(0.5f));
}

TEST(EnvironmentLight, SampleAgreesWithPdfAndNearestTexelRadiance) {
  const auto img = spot_map();
  const auto light = make_image_environment(img, 1.5f, 30.0f);
  Pcg32 rng(84, 2);
  const Hit none;
  int in_spot = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto s = light->sample(kCtx, {rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s.has_value());
    EXPECT_TRUE(std::isinf(s->dist));
    EXPECT_NEAR(s->pdf / light->pdf(kCtx, s->wi, none), 1.0f, 1e-3f);
    EXPECT_EQ(s->le, light->le_escaped(s->wi));
    EXPECT_EQ(light->le(none, -s->wi), s->le);
    if (s->le.x > 80) ++in_spot;
  }
  // The spot holds about two thirds of the map's luminance x solid angle; it must dominate the samples.
  EXPECT_GT(in_spot, 1000);
  // Zero density <=> zero radiance, texel by texel (the black row 12 and nowhere else).
  for (int i = 0; i < 20000; ++i) {
    const float z = 2 * rng.next_float() - 1, phi = 2 * kPi * rng.next_float(), r = std::sqrt(1 - z * z);
    const Vec3 w{r * std::cos(phi), z, r * std::sin(phi)};
    EXPECT_EQ(light->pdf(kCtx, w, none) == 0, is_black(light->le_escaped(w)));
  }
  // Map convention, without rotation: u = 0.5, v = 0.5 (the corner of texel 16, 8) looks down -Z, u grows toward
  // +X; rotation turns the map about +Y.
  img->at(16, 8, 0) = 7;
  const auto plain = make_image_environment(img, 1.0f, 0.0f);
  EXPECT_EQ(plain->le_escaped({0.05f, -0.01f, -1}).x, 7.0f);
  const auto turned = make_image_environment(img, 1.0f, 90.0f);
  EXPECT_EQ(turned->le_escaped({-1, -0.01f, -0.05f}).x, 7.0f) << "+90 degrees about +Y takes -Z to -X";
}

// Sampling by luminance x solid angle makes luminance(radiance) / pdf the same for every sample, the map's luminance
// integral x scale, up to the rounding of the sampling tables to the sampler's 2^-24 grid (core/distribution.h): a
// cell of k steps has its probability, and so its pdf, off f / sum by under 1 / k, in the column (the texel within
// its row) and in the row. A sample whose radiance came from a neighbouring texel (a direction on a texel's edge)
// breaks it by the neighbours' ratio, up to 10^4 here. A 2048 x 1024 map of random texels (no cell below one step),
// 10^6 samples, each held to 1e-4 (float rounding) plus its two cells' grid bound. Deterministic.
TEST(EnvironmentLight, RadianceOverPdfIsConstant) {
  const int w = 2048, h = 1024;
  auto img = std::make_shared<Image>(w, h, std::vector<std::string>{"R", "G", "B"});
  Pcg32 rng(85, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = std::pow(10.0f, 4 * rng.next_float() - 2);
      for (int c = 0; c < 3; ++c) img->at(x, y, c) = v;
    }
  const float rotation = 30.0f;
  const auto light = make_image_environment(img, 1.5f, rotation);
  double integral = 0;  // of luminance over the sphere: texel solid angle 2 pi / w x dcos
  std::vector<double> row_sum(h, 0.0), row_weight(h, 0.0);
  for (int y = 0; y < h; ++y) {
    const double dcos = std::cos(kPi * double(y) / h) - std::cos(kPi * double(y + 1) / h);
    for (int x = 0; x < w; ++x) row_sum[y] += img->at(x, y, 0);
    row_weight[y] = row_sum[y] * dcos;
    integral += row_sum[y] * dcos * 2 * kPi / w;
  }
  const double total_weight = std::accumulate(row_weight.begin(), row_weight.end(), 0.0);
  // The grid's bound on the relative pdf error of a sample in row y (either neighbour, for a direction on the edge)
  // whose texel has value v: 1 / (steps of the texel in its row) + 1 / (steps of the row).
  const auto grid_bound = [&](int y, double v) {
    double worst = 0;
    for (int r = std::max(y - 1, 0); r <= std::min(y + 1, h - 1); ++r) {
      const double e_column = 0x1p-24 * row_sum[r] / v, e_row = 0x1p-24 * total_weight / row_weight[r];
      worst = std::max(worst, e_column + e_row + e_column * e_row);
    }
    return worst;
  };
  const float c = std::cos(rotation * kPi / 180), sn = std::sin(rotation * kPi / 180);
  int off = 0, off_flat = 0;
  double worst = 0;
  for (int i = 0; i < 1'000'000; ++i) {
    const auto s = light->sample(kCtx, {rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s.has_value());
    const double dev = std::abs(luminance(s->le) / s->pdf / (1.5 * integral) - 1);
    const Vec3 d{c * s->wi.x - sn * s->wi.z, s->wi.y, sn * s->wi.x + c * s->wi.z};  // the map's frame
    const int y = std::clamp(static_cast<int>(std::acos(std::clamp(double(d.y), -1.0, 1.0)) / kPi * h), 0, h - 1);
    worst = std::max(worst, dev);
    off += dev > 1e-4 + grid_bound(y, luminance(s->le) / 1.5);
    off_flat += dev > 1e-4;
  }
  EXPECT_EQ(off, 0) << "worst relative deviation " << worst;
  std::printf("  worst relative deviation %.3g; %d of 10^6 samples beyond 1e-4, within the grid's bound\n", worst,
              off_flat);
}

}  // namespace
}  // namespace lumis
