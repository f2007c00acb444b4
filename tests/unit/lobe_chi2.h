// Chi-square test helpers for sharp directional lobes (tests only).
//
// core/chi2.h bins directions in cells uniform in (cos theta, phi). A GGX lobe with alpha = 0.0025 is about 0.3
// degrees wide, so with such cells nearly every sample lands in one or two cells and the test can see almost
// nothing. Here the same directions are binned on a warped grid: cell edges are uniform in (A(cos theta), B(phi))
// where A and B are fixed CDFs (a uniform part plus a truncated Cauchy part centred on the lobe). The warp only
// depends on the lobe's nominal centre and width, never on the sampler under test, so the hypothesis tested is the
// same (samples distributed with the pdf); the expected count of each cell is the pdf integrated over the cell's
// solid angle (d omega = d cos(theta) d phi), by composite Simpson in the warped coordinates where the integrand
// pdf / (A' B') is smooth at cell scale. The statistic and the Sidak level come from core/chi2.h.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/chi2.h"
#include "core/rng.h"

namespace lumis::lobe {

inline constexpr double kLobePi = 3.14159265358979323846;

/// Monotone map of [lo, hi] onto [0, 1]: CDF of (1 - weight) uniform + weight truncated Cauchy(center, width).
struct AxisWarp {
  double lo = 0, hi = 1, center = 0, width = 1, weight = 0;

  double atan_at(double x) const { return std::atan((x - center) / width); }
  double cdf(double x) const {
    x = std::clamp(x, lo, hi);
    const double uniform = (x - lo) / (hi - lo);
    if (weight <= 0) return uniform;
    const double cauchy = (atan_at(x) - atan_at(lo)) / (atan_at(hi) - atan_at(lo));
    return (1 - weight) * uniform + weight * cauchy;
  }
  double density(double x) const {
    const double uniform = 1 / (hi - lo);
    if (weight <= 0) return uniform;
    const double t = (x - center) / width;
    return (1 - weight) * uniform + weight / (width * (1 + t * t) * (atan_at(hi) - atan_at(lo)));
  }
  /// cdf^-1 by bisection (the cdf is strictly increasing).
  double inverse(double u) const {
    double a = lo, b = hi;
    for (int i = 0; i < 80; ++i) {
      const double m = 0.5 * (a + b);
      (cdf(m) < u ? a : b) = m;
    }
    return 0.5 * (a + b);
  }
};

/// Grid over x1 = cos(theta) in [cos_warp.lo, cos_warp.hi] and x2 = phi - phi0 in [-pi, pi].
struct LobeBinning {
  AxisWarp cos_warp{-1, 1};
  AxisWarp phi_warp{-kLobePi, kLobePi};
  double phi0 = 0;
  int cos_bins = 32, phi_bins = 64;
  int resolution = 8;      ///< Simpson intervals per cell side in phi (even)
  int cos_resolution = 8;  ///< the same in cos theta (even; finer for a lobe against the pole, see below)
};

struct LobeHistogram {
  std::vector<double> observed, expected;  ///< cells, then one last cell for failed samples
};

inline Vec3 direction_at(double cos_theta, double dphi, double phi0) {
  const double s = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  return Vec3(static_cast<float>(s * std::cos(dphi + phi0)), static_cast<float>(s * std::sin(dphi + phi0)),
              static_cast<float>(cos_theta));
}

inline int cell_of(double u, int n) { return std::clamp(static_cast<int>(u * n), 0, n - 1); }

/// Draws `samples` directions (nullopt = failure) and integrates pdf (solid angle) over the warped cells.
inline LobeHistogram lobe_histogram(const std::function<std::optional<Vec3>(Pcg32&)>& sample,
                                    const std::function<double(Vec3)>& pdf, const LobeBinning& b, uint64_t samples,
                                    uint64_t seed) {
  const int n1 = b.cos_bins, n2 = b.phi_bins;
  LobeHistogram h;
  h.observed.assign(static_cast<size_t>(n1) * n2 + 1, 0.0);
  h.expected.assign(h.observed.size(), 0.0);
  Pcg32 rng(seed, 0x10beULL);
  for (uint64_t i = 0; i < samples; ++i) {
    const std::optional<Vec3> w = sample(rng);
    if (!w) {
      h.observed.back() += 1;
      continue;
    }
    const double len = std::sqrt(double(w->x) * w->x + double(w->y) * w->y + double(w->z) * w->z);
    double dphi = std::atan2(double(w->y), double(w->x)) - b.phi0;
    dphi = std::remainder(dphi, 2 * kLobePi);
    const int i1 = cell_of(b.cos_warp.cdf(w->z / len), n1), i2 = cell_of(b.phi_warp.cdf(dphi), n2);
    h.observed[static_cast<size_t>(i1) * n2 + i2] += 1;
  }
  // Simpson nodes per axis in warped coordinates; nodes on the domain edge move inward by a hair so that a pdf
  // that jumps there (a hemisphere's rim) is read from inside. The hair is also small against the lobe: at normal
  // incidence a lobe of alpha = 1e-3 sits against cos theta = 1 and is 2e-6 wide there, and a shift of 2e-7 (a
  // tenth of that) failed the correct sampler at p ~ 1e-116.
  const int r1 = b.cos_resolution, r2 = b.resolution;
  auto nodes = [](const AxisWarp& warp, int n, int r, std::vector<double>& x, std::vector<double>& inv_density) {
    const double eps = 1e-7 * std::min(warp.hi - warp.lo, warp.width);
    for (int k = 0; k <= n * r; ++k) {
      const double xv = std::clamp(warp.inverse(static_cast<double>(k) / (n * r)), warp.lo + eps, warp.hi - eps);
      x.push_back(xv);
      inv_density.push_back(1 / warp.density(xv));
    }
  };
  std::vector<double> x1, j1, x2, j2;
  nodes(b.cos_warp, n1, r1, x1, j1);
  nodes(b.phi_warp, n2, r2, x2, j2);
  std::vector<double> values(x1.size() * x2.size());
  for (size_t a = 0; a < x1.size(); ++a)
    for (size_t c = 0; c < x2.size(); ++c) {
      const double p = pdf(direction_at(x1[a], x2[c], b.phi0));
      values[a * x2.size() + c] = (std::isfinite(p) ? p : 0.0) * j1[a] * j2[c];
    }
  auto weight = [](int k, int r) { return (k == 0 || k == r) ? 1.0 : (k % 2 ? 4.0 : 2.0); };
  const double cell_area = (1.0 / (n1 * r1)) * (1.0 / (n2 * r2)) / 9.0;
  double total = 0;
  for (int i1 = 0; i1 < n1; ++i1)
    for (int i2 = 0; i2 < n2; ++i2) {
      double s = 0;
      for (int k1 = 0; k1 <= r1; ++k1)
        for (int k2 = 0; k2 <= r2; ++k2)
          s += weight(k1, r1) * weight(k2, r2) *
               values[static_cast<size_t>(i1 * r1 + k1) * x2.size() + (i2 * r2 + k2)];
      const double e = s * cell_area * static_cast<double>(samples);
      h.expected[static_cast<size_t>(i1) * n2 + i2] = e;
      total += e;
    }
  // What the pdf does not cover is the expected number of failures (zero for a sampler that never fails).
  h.expected.back() = std::max(0.0, static_cast<double>(samples) - total);
  return h;
}

/// Chi-square of a lobe histogram (core/chi2.h pooling and Sidak level).
inline ChiSquareResult lobe_chi_square(const std::function<std::optional<Vec3>(Pcg32&)>& sample,
                                       const std::function<double(Vec3)>& pdf, const LobeBinning& b,
                                       uint64_t samples, uint64_t seed, double alpha, int num_tests) {
  const LobeHistogram h = lobe_histogram(sample, pdf, b, samples, seed);
  return chi_square_test(h.observed, h.expected, alpha, num_tests);
}

/// Two-sample (homogeneity) chi-square between two histograms of equal sample counts: sum (a - b)^2 / (a + b)
/// over cells with a + b >= min_count (the rest pooled), dof = cells - 1. Returns the p-value.
inline double two_sample_p_value(const std::vector<double>& a, const std::vector<double>& b, int* dof_out = nullptr,
                                 double min_count = 10) {
  double stat = 0, pa = 0, pb = 0;
  int cells = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i] + b[i] >= min_count) {
      stat += (a[i] - b[i]) * (a[i] - b[i]) / (a[i] + b[i]);
      ++cells;
    } else {
      pa += a[i];
      pb += b[i];
    }
  }
  if (pa + pb > 0) {
    stat += (pa - pb) * (pa - pb) / (pa + pb);
    ++cells;
  }
  if (dof_out) *dof_out = cells - 1;
  return chi_square_sf(stat, cells - 1);
}

/// Binning around a GGX reflection lobe: mirror direction of wo (local frame), nominal width ~ 2 alpha.
/// On the upper hemisphere only (cos theta in [0, 1]) when `hemisphere`, so that the horizon is a cell edge.
inline LobeBinning ggx_reflection_binning(Vec3 wo, double alpha, bool hemisphere, double weight = 0.6) {
  LobeBinning b;
  const double cos_o = wo.z, sin_o = std::sqrt(std::max(0.0, 1 - cos_o * cos_o));
  b.phi0 = std::atan2(-double(wo.y), -double(wo.x));
  b.cos_warp = {hemisphere ? 0.0 : -1.0, 1.0, cos_o, 2 * alpha * sin_o + 2 * alpha * alpha, weight};
  b.phi_warp = {-kLobePi, kLobePi, 0.0, std::min(kLobePi, 2 * alpha / std::max(sin_o, 2 * alpha)), weight};
  // A lobe against the pole is narrow in cos theta (2 alpha^2), and where the warp's uniform part takes over from
  // its Cauchy part (about the square root of that width) the integrand falls by orders of magnitude within one
  // cell: 8 Simpson intervals per cell overestimated the integral by 4e-4 (alpha 0.0025) to 7e-4 (alpha 1e-3) at
  // normal incidence, more than the mass a GGX reflection loses below the horizon (alpha^2 / (1 + alpha^2)), so
  // the failed-sample cell expected nothing and one failure failed the test. 32 intervals leave errors of 3e-7
  // and -4e-5 (an underestimate: the failed cell then expects about 8 of 200,000 samples instead of 0.2, which
  // adds about 8 to a statistic of about 1,300 degrees of freedom).
  if (b.cos_warp.width < 1e-4) b.cos_resolution = 32;
  return b;
}

}  // namespace lumis::lobe
