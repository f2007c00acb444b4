// Statistical helpers (tests and `lumis warptest`): Pearson chi-square goodness of fit with pooling of small cells and
// Sidak correction (as pbrt-v4 and Nori do), and a directional version that bins sphere directions.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/rng.h"

namespace lumis {

struct ChiSquareResult {
  bool passed = false;
  double statistic = 0;
  int dof = 0;
  double p_value = 0;
  double significance = 0;  ///< Sidak-corrected per-test alpha
  std::string message;      ///< human-readable summary (for EXPECT_TRUE(r.passed) << r.message)
};

/// Pearson chi-square test. Cells with expected count < min_expected are pooled into one cell (which itself must
/// reach min_expected or is merged into the smallest kept one). The null hypothesis is rejected when
/// p < 1 - (1 - alpha)^(1 / num_tests) (Sidak correction for num_tests tests run together).
ChiSquareResult chi_square_test(std::span<const double> observed, std::span<const double> expected, double alpha = 0.01,
                                int num_tests = 1, double min_expected = 5.0);

/// Upper tail probability of the chi-square distribution with dof degrees of freedom.
double chi_square_sf(double statistic, int dof);

struct DirectionalTest {
  int cos_theta_bins = 40;   ///< cells uniform in cos(theta) in [-1, 1]
  int phi_bins = 80;         ///< cells uniform in phi in [0, 2 pi)
  uint64_t samples = 1'000'000;
  uint64_t seed = 1;
  double alpha = 0.01;
  int num_tests = 1;         ///< for the Sidak correction
  int integration_resolution = 8;  ///< sub-cells per cell side for integrating the pdf (Simpson)
};

/// Draws `samples` directions with `sample` (nullopt = a failed sample, counted as no direction) and compares the
/// histogram against the integral of `pdf` (solid-angle density) over each cell, in the frame where z is the pole.
ChiSquareResult chi_square_directions(const std::function<std::optional<Vec3>(Pcg32&)>& sample,
                                      const std::function<double(Vec3)>& pdf, const DirectionalTest& config);

/// Observed and expected counts per cell of a DirectionalTest, row-major: [cos_theta_bin * phi_bins + phi_bin].
struct DirectionalHistogram {
  std::vector<double> observed, expected;
};
/// The two histograms that chi_square_directions compares (for pictures such as `lumis warptest`).
DirectionalHistogram directional_histogram(const std::function<std::optional<Vec3>(Pcg32&)>& sample,
                                           const std::function<double(Vec3)>& pdf, const DirectionalTest& config);

/// Monte Carlo integral of pdf over the sphere (should be <= 1, == 1 for a sampler that never fails), by
/// stratified quadrature in (cos theta, phi).
double integrate_over_sphere(const std::function<double(Vec3)>& pdf, int resolution = 512);

}  // namespace lumis
