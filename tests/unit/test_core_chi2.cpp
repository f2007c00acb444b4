// Self-tests of the statistics every other sampling test relies on: the chi-square survival function against closed
// forms, pooling, and the directional test accepting exact samplers and rejecting slightly wrong densities.
// Generators here are written inline so that this file tests core/chi2.cpp alone.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/chi2.h"

namespace lumis {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// For even dof = 2k the survival function is a Poisson sum: exp(-x/2) sum_{j<k} (x/2)^j / j!, evaluated in logs.
double even_dof_sf(double x, int dof) {
  const double h = 0.5 * x;
  double sum = 0;
  for (int j = 0; j < dof / 2; ++j) sum += std::exp(-h + j * std::log(h) - std::lgamma(j + 1.0));
  return sum;
}

TEST(Chi2, SurvivalFunctionKnownQuantiles) {
  EXPECT_NEAR(chi_square_sf(3.841458820694124, 1), 0.05, 1e-12);
  EXPECT_NEAR(chi_square_sf(18.307038053275146, 10), 0.05, 1e-12);
  EXPECT_NEAR(chi_square_sf(6.634896601021214, 1), 0.01, 1e-12);
  EXPECT_DOUBLE_EQ(chi_square_sf(0.0, 5), 1.0);
  EXPECT_TRUE(std::isnan(chi_square_sf(1.0, 0)));
}

TEST(Chi2, SurvivalFunctionMatchesPoissonSumForLargeDof) {
  for (int dof : {2, 4, 40, 400, 3198}) {
    for (double ratio : {0.5, 0.9, 1.0, 1.05, 1.2, 2.0}) {
      const double x = ratio * dof, expect = even_dof_sf(x, dof), got = chi_square_sf(x, dof);
      // Relative accuracy matters in the far tail, where p-values are compared with a Sidak level of ~1e-5.
      EXPECT_NEAR(got, expect, 1e-9 * std::max(expect, 1e-300) + 1e-14) << "dof " << dof << " x " << x;
    }
  }
}

TEST(Chi2, PoolingAndDecisions) {
  // Perfect agreement: statistic 0, p = 1.
  const std::vector<double> e = {100, 200, 300, 400};
  ChiSquareResult r = chi_square_test(e, e);
  EXPECT_TRUE(r.passed) << r.message;
  EXPECT_EQ(r.dof, 3);
  EXPECT_DOUBLE_EQ(r.p_value, 1.0);
  // Cells below 5 expected are pooled into one cell (here 2 + 2 + 1 = 5 -> one extra cell).
  const std::vector<double> e2 = {100, 100, 2, 2, 1}, o2 = {100, 100, 1, 3, 1};
  r = chi_square_test(o2, e2);
  EXPECT_EQ(r.dof, 2);
  EXPECT_NEAR(r.statistic, 0.0, 1e-12);
  // A pooled remainder below 5 is merged into the smallest kept cell.
  const std::vector<double> e3 = {100, 50, 1, 1}, o3 = {100, 52, 0, 0};
  r = chi_square_test(o3, e3);
  EXPECT_EQ(r.dof, 1);
  EXPECT_NEAR(r.statistic, 0.0, 1e-12);
  // A sample where the density integrates to zero is an immediate rejection.
  const std::vector<double> e4 = {100, 0, 100}, o4 = {100, 1, 99};
  r = chi_square_test(o4, e4);
  EXPECT_FALSE(r.passed);
  // A 10% deficit in 1000 expected counts is far outside the noise (statistic ~ 20 for 1 dof).
  const std::vector<double> e5 = {1000, 1000}, o5 = {900, 1100};
  EXPECT_FALSE(chi_square_test(o5, e5).passed);
  // Sidak: 1 - (1 - 0.01)^(1/10).
  r = chi_square_test(e, e, 0.01, 10);
  EXPECT_NEAR(r.significance, 1.0 - std::pow(0.99, 0.1), 1e-15);
}

std::optional<Vec3> uniform_sphere(Pcg32& rng) {
  const double z = 1 - 2 * rng.next_double(), phi = 2 * kPiD * rng.next_double();
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return Vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
}

// 1e6 samples (the default), alpha = 0.01 per test: an exact sampler fails at most 1% of seeds; the seed is fixed.
TEST(Chi2, DirectionsAcceptUniformSphere) {
  DirectionalTest cfg;
  const ChiSquareResult r = chi_square_directions(uniform_sphere, [](Vec3) { return 1.0 / (4 * kPiD); }, cfg);
  EXPECT_TRUE(r.passed) << r.message;
  EXPECT_EQ(r.dof, cfg.cos_theta_bins * cfg.phi_bins - 1);
}

TEST(Chi2, DirectionsRejectSlightlyWrongPdf) {
  // Density (1 + 0.05 z) / (4 pi) also integrates to 1 but is not what uniform_sphere draws.
  const ChiSquareResult r = chi_square_directions(
      uniform_sphere, [](Vec3 w) { return (1.0 + 0.05 * w.z) / (4 * kPiD); }, DirectionalTest{});
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(Chi2, DirectionsHandlePoleSingularity) {
  // Uniform in (theta, phi) on the upper hemisphere: solid-angle density 1/(pi^2 sin theta), infinite at the pole.
  auto sample = [](Pcg32& rng) -> std::optional<Vec3> {
    const double theta = 0.5 * kPiD * rng.next_double(), phi = 2 * kPiD * rng.next_double();
    return Vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                float(std::cos(theta)));
  };
  auto pdf = [](Vec3 w) {
    const double s = std::sqrt(double(w.x) * w.x + double(w.y) * w.y);
    return w.z > 0 ? 1.0 / (kPiD * kPiD * s) : 0.0;
  };
  const ChiSquareResult r = chi_square_directions(sample, pdf, DirectionalTest{});
  EXPECT_TRUE(r.passed) << r.message;
  EXPECT_NEAR(integrate_over_sphere(pdf), 1.0, 1e-3);
}

TEST(Chi2, DirectionsHandleDiscontinuityInsideCells) {
  // A uniform cap whose rim (cos 0.73) falls inside a cos(theta) bin: the expected counts must still be exact.
  const double cos_max = 0.73;
  auto sample = [&](Pcg32& rng) -> std::optional<Vec3> {
    const double z = 1 - (1 - cos_max) * rng.next_double(), phi = 2 * kPiD * rng.next_double();
    const double s = std::sqrt(1 - z * z);
    return Vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
  };
  auto pdf = [&](Vec3 w) { return w.z >= cos_max ? 1.0 / (2 * kPiD * (1 - cos_max)) : 0.0; };
  const ChiSquareResult r = chi_square_directions(sample, pdf, DirectionalTest{});
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Chi2, DirectionsBinSamplesOnAFloatRimWithThePdf) {
  // A cap with cos_max = 0.9f (just below the bin edge 0.9): samples exactly on the rim are inside the support for
  // the float pdf and must be binned with the cap, not in the empty row below (found by `lumis warptest`).
  const float cos_max = 0.9f;
  auto sample = [&](Pcg32& rng) -> std::optional<Vec3> {
    const bool rim = rng.next_float() < 0.001f;
    const double z = rim ? double(cos_max) : 1 - (1 - double(cos_max)) * rng.next_double();
    const double phi = 2 * kPiD * rng.next_double(), s = std::sqrt(1 - z * z);
    return Vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
  };
  auto pdf = [&](Vec3 w) { return w.z >= cos_max ? 1.0 / (2 * kPiD * (1 - double(cos_max))) : 0.0; };
  const ChiSquareResult r = chi_square_directions(sample, pdf, DirectionalTest{});
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Chi2, DirectionsCountFailedSamplesAsMissing) {
  // Dropping 2% of samples while claiming a normalised pdf must be rejected.
  auto lossy = [](Pcg32& rng) -> std::optional<Vec3> {
    if (rng.next_float() < 0.02f) return std::nullopt;
    return uniform_sphere(rng);
  };
  const ChiSquareResult r = chi_square_directions(lossy, [](Vec3) { return 1.0 / (4 * kPiD); }, DirectionalTest{});
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(Chi2, IntegrateOverSphere) {
  EXPECT_NEAR(integrate_over_sphere([](Vec3) { return 1.0 / (4 * kPiD); }), 1.0, 1e-5);
  EXPECT_NEAR(integrate_over_sphere([](Vec3 w) { return w.z > 0 ? w.z / kPiD : 0.0; }), 1.0, 1e-4);
  EXPECT_NEAR(integrate_over_sphere([](Vec3 w) { return w.z > 0 ? 1.0 / (2 * kPiD) : 0.0; }), 1.0, 1e-4);
}

}  // namespace
}  // namespace lumis
