// Helpers for statistical image tests: render a scene into a Film and test pixel or region means against an
// expected value with z-tests whose per-test level is Sidak-corrected.
#pragma once

#include <cmath>
#include <string>

#include "core/film.h"

namespace lumis::test {

/// Two-sided z threshold for significance alpha split over num_tests tests (Sidak).
inline double sidak_z(double alpha, double num_tests) {
  const double per_test = 1 - std::pow(1 - alpha, 1 / num_tests);
  // Inverse of the two-sided normal tail by bisection on erfc (precise enough for thresholds).
  double lo = 0, hi = 40;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > per_test ? lo : hi) = mid;
  }
  return hi;
}

struct RegionMean {
  double mean[3] = {0, 0, 0};
  double var[3] = {0, 0, 0};  ///< variance of the mean
  int pixels = 0;
};

/// Mean over the pixels (x, y) with mask(x, y) true, and the variance of that mean from the film's per-pixel
/// variance of the mean (pixels are independent).
template <class Mask>
RegionMean region_mean(const Film& film, Mask mask) {
  RegionMean r;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      if (!mask(x, y)) continue;
      const Color m = film.mean(x, y), v = film.variance_of_mean(x, y);
      for (int c = 0; c < 3; ++c) {
        r.mean[c] += m[c];
        r.var[c] += v[c];
      }
      ++r.pixels;
    }
  for (int c = 0; c < 3; ++c) {
    r.mean[c] /= std::max(1, r.pixels);
    r.var[c] /= static_cast<double>(std::max(1, r.pixels)) * std::max(1, r.pixels);
  }
  return r;
}

}  // namespace lumis::test
