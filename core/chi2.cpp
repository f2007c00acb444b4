// Pearson chi-square goodness of fit, its survival function, and the directional histogram test used for warps and
// BSDFs. Everything is accumulated in double: a million samples in float counts would lose the statistic.
#include "core/chi2.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace lumis {

namespace {

constexpr double kPiD = 3.14159265358979323846;

// Regularised lower incomplete gamma P(a, x) by its power series; converges quickly for x < a + 1.
double gamma_p_series(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 1'000'000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-16) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Regularised upper incomplete gamma Q(a, x) by its continued fraction (modified Lentz); for x >= a + 1, where it
// converges in O(sqrt(a)) steps, and where computing 1 - P would lose the small tail to cancellation.
double gamma_q_fraction(double a, double x) {
  constexpr double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1'000'000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

// Composite Simpson weights 1, 4, 2, 4, ..., 4, 1 for an even number of intervals n.
double simpson_weight(int i, int n) { return (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0); }

// Integral of pdf over the solid angle of theta in [t0, t1], phi in [p0, p1]. Integrating in theta (dw = sin(theta)
// dtheta dphi) rather than in cos(theta) keeps integrands like 1/sin(theta) bounded at the poles.
double simpson_cell(const std::function<double(Vec3)>& pdf, double t0, double t1, double p0, double p1, int n) {
  const double ht = (t1 - t0) / n, hp = (p1 - p0) / n;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double theta = t0 + i * ht, st = std::sin(theta), ct = std::cos(theta);
    double row = 0;
    for (int j = 0; j <= n; ++j) {
      const double phi = p0 + j * hp;
      const Vec3 w(static_cast<float>(st * std::cos(phi)), static_cast<float>(st * std::sin(phi)),
                   static_cast<float>(ct));
      const double f = pdf(w);
      row += simpson_weight(j, n) * (std::isfinite(f) ? f : 0.0);
    }
    sum += simpson_weight(i, n) * row * st;
  }
  return sum * ht * hp / 9.0;
}

// Adaptive refinement on top of Simpson: a cell whose quadrants disagree with the whole (a discontinuity such as a
// cap's rim crossing the cell) is split, so that a sharp edge does not bias the expected count by percents.
double integrate_cell(const std::function<double(Vec3)>& pdf, double t0, double t1, double p0, double p1, int n,
                      double whole, int depth) {
  const double tm = 0.5 * (t0 + t1), pm = 0.5 * (p0 + p1);
  const double q[4] = {simpson_cell(pdf, t0, tm, p0, pm, n), simpson_cell(pdf, t0, tm, pm, p1, n),
                       simpson_cell(pdf, tm, t1, p0, pm, n), simpson_cell(pdf, tm, t1, pm, p1, n)};
  const double parts = q[0] + q[1] + q[2] + q[3];
  if (depth <= 0 || std::abs(parts - whole) <= 1e-5 * std::abs(parts) + 1e-13) return parts;
  return integrate_cell(pdf, t0, tm, p0, pm, n, q[0], depth - 1) +
         integrate_cell(pdf, t0, tm, pm, p1, n, q[1], depth - 1) +
         integrate_cell(pdf, tm, t1, p0, pm, n, q[2], depth - 1) +
         integrate_cell(pdf, tm, t1, pm, p1, n, q[3], depth - 1);
}

}  // namespace

double chi_square_sf(double statistic, int dof) {
  if (dof <= 0 || std::isnan(statistic)) return std::numeric_limits<double>::quiet_NaN();
  if (statistic <= 0) return 1.0;
  if (std::isinf(statistic)) return 0.0;
  const double a = 0.5 * dof, x = 0.5 * statistic;
  if (x < a + 1.0) return std::clamp(1.0 - gamma_p_series(a, x), 0.0, 1.0);
  return std::clamp(gamma_q_fraction(a, x), 0.0, 1.0);
}

ChiSquareResult chi_square_test(std::span<const double> observed, std::span<const double> expected, double alpha,
                                int num_tests, double min_expected) {
  ChiSquareResult r;
  r.significance = 1.0 - std::pow(1.0 - alpha, 1.0 / std::max(num_tests, 1));
  std::ostringstream msg;
  if (observed.size() != expected.size()) {
    r.message = "chi-square: observed and expected have different sizes";
    return r;
  }
  // Sort kept cells so the smallest is at hand if the pooled remainder is too small to stand alone.
  std::vector<std::pair<double, double>> kept;  // (expected, observed)
  double pooled_exp = 0, pooled_obs = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] == 0 && observed[i] > 0) {
      msg << "chi-square: " << observed[i] << " samples in cell " << i << " where the pdf integrates to 0";
      r.statistic = std::numeric_limits<double>::infinity();
      r.message = msg.str();
      return r;
    }
    if (expected[i] < min_expected) {
      pooled_exp += expected[i];
      pooled_obs += observed[i];
    } else {
      kept.emplace_back(expected[i], observed[i]);
    }
  }
  if (pooled_exp > 0 || pooled_obs > 0) {
    if (pooled_exp >= min_expected || kept.empty()) {
      kept.emplace_back(pooled_exp, pooled_obs);
    } else {
      auto smallest = std::min_element(kept.begin(), kept.end());
      smallest->first += pooled_exp;
      smallest->second += pooled_obs;
    }
  }
  if (kept.size() < 2 || kept.front().first <= 0) {
    r.message = "chi-square: fewer than two cells with enough expected samples; the test cannot decide";
    return r;
  }
  for (const auto& [e, o] : kept) r.statistic += (o - e) * (o - e) / e;
  r.dof = static_cast<int>(kept.size()) - 1;
  r.p_value = chi_square_sf(r.statistic, r.dof);
  r.passed = r.p_value >= r.significance;
  msg << "chi-square = " << r.statistic << ", dof = " << r.dof << ", p-value = " << r.p_value
      << ", significance level = " << r.significance << " (" << kept.size() << " cells after pooling): "
      << (r.passed ? "accepted" : "REJECTED");
  r.message = msg.str();
  return r;
}

DirectionalHistogram directional_histogram(const std::function<std::optional<Vec3>(Pcg32&)>& sample,
                                           const std::function<double(Vec3)>& pdf, const DirectionalTest& config) {
  const int nz = config.cos_theta_bins, np = config.phi_bins;
  DirectionalHistogram h;
  h.observed.assign(static_cast<size_t>(nz) * np, 0.0);
  h.expected.assign(h.observed.size(), 0.0);
  std::vector<float> edge(nz + 1);
  for (int i = 0; i <= nz; ++i) edge[i] = static_cast<float>(-1.0 + 2.0 * i / nz);
  Pcg32 rng(config.seed, 0x5eedULL);
  for (uint64_t s = 0; s < config.samples; ++s) {
    const std::optional<Vec3> w = sample(rng);
    if (!w || !is_finite(*w)) continue;
    const double len = std::sqrt(double(w->x) * w->x + double(w->y) * w->y + double(w->z) * w->z);
    if (!(len > 0)) continue;
    // Bin by the float z the pdf sees, against float bin edges: a support boundary written as a float literal
    // (a cap with cos_max = 0.9f) then falls on the same side of the edge for the samples as for the pdf.
    // Only directions that are not unit to float precision are renormalised.
    const float z = std::abs(len - 1.0) > 1e-6 ? static_cast<float>(std::clamp(w->z / len, -1.0, 1.0)) : w->z;
    int iz = std::clamp(static_cast<int>((double(z) + 1) * 0.5 * nz), 0, nz - 1);
    if (iz + 1 < nz && z >= edge[iz + 1]) ++iz;
    if (iz > 0 && z < edge[iz]) --iz;
    double phi = std::atan2(double(w->y), double(w->x));
    if (phi < 0) phi += 2 * kPiD;
    const int ip = std::clamp(static_cast<int>(phi / (2 * kPiD) * np), 0, np - 1);
    h.observed[static_cast<size_t>(iz) * np + ip] += 1;
  }
  const int n = std::max(2, config.integration_resolution + config.integration_resolution % 2);
  for (int iz = 0; iz < nz; ++iz) {
    // Row iz spans cos(theta) in [z0, z1], i.e. theta in [acos(z1), acos(z0)].
    const double z0 = -1.0 + 2.0 * iz / nz, z1 = -1.0 + 2.0 * (iz + 1) / nz;
    const double t0 = std::acos(z1), t1 = std::acos(z0);
    for (int ip = 0; ip < np; ++ip) {
      const double p0 = 2 * kPiD * ip / np, p1 = 2 * kPiD * (ip + 1) / np;
      // Evaluate strictly inside the cell and rescale: a density that jumps exactly on a cell edge (a hemisphere
      // at the equator, a cap whose rim is a bin edge) or is singular at a pole must not be sampled on the edge.
      const double dt = 1e-5 * (t1 - t0), dp = 1e-5 * (p1 - p0);
      const double scale = (t1 - t0) * (p1 - p0) / ((t1 - t0 - 2 * dt) * (p1 - p0 - 2 * dp));
      const double ta = t0 + dt, tb = t1 - dt, pa = p0 + dp, pb = p1 - dp;
      const double whole = simpson_cell(pdf, ta, tb, pa, pb, n);
      h.expected[static_cast<size_t>(iz) * np + ip] =
          scale * integrate_cell(pdf, ta, tb, pa, pb, n, whole, 6) * static_cast<double>(config.samples);
    }
  }
  return h;
}

ChiSquareResult chi_square_directions(const std::function<std::optional<Vec3>(Pcg32&)>& sample,
                                      const std::function<double(Vec3)>& pdf, const DirectionalTest& config) {
  const DirectionalHistogram h = directional_histogram(sample, pdf, config);
  return chi_square_test(h.observed, h.expected, config.alpha, config.num_tests);
}

double integrate_over_sphere(const std::function<double(Vec3)>& pdf, int resolution) {
  // One jittered point per stratum (fixed seed): no point lands exactly on a pole or an edge where pdfs are singular
  // or discontinuous, and stratification keeps the error near O(1/N) for smooth pdfs. The strata are uniform in
  // theta (dw = sin(theta) dtheta dphi) so that densities like 1/sin(theta) have bounded integrands at the poles.
  const int nt = std::max(resolution, 1), np = 2 * nt;
  Pcg32 rng(0x1234567ULL, 0x89abcdefULL);
  double sum = 0;
  for (int it = 0; it < nt; ++it) {
    double row = 0;
    for (int ip = 0; ip < np; ++ip) {
      const double theta = kPiD * (it + rng.next_double()) / nt;
      const double phi = 2 * kPiD * (ip + rng.next_double()) / np;
      const double s = std::sin(theta);
      const double f = pdf(Vec3(static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
                                static_cast<float>(std::cos(theta))));
      row += (std::isfinite(f) ? f : 0.0) * s;
    }
    sum += row;
  }
  return sum * (2 * kPiD * kPiD) / (static_cast<double>(nt) * np);
}

}  // namespace lumis
