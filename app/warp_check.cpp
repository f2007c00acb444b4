// check_warp (warptest.h): the chi-square test of one warp against its density, its report, and the picture of the
// observed histogram beside the expected one.
#include <algorithm>
#include <cmath>
#include <iomanip>

#include "app/warptest.h"
#include "core/chi2.h"
#include "core/image_io.h"

namespace lumis {

namespace {

// A black-purple-red-orange-yellow ramp, defined in display (sRGB) values and decoded so that the PNG writer's
// sRGB encoding reproduces it.
Color colormap(double t) {
  static const Color stops[] = {{0, 0, 0}, {0.25f, 0.05f, 0.45f}, {0.85f, 0.2f, 0.3f}, {0.98f, 0.6f, 0.1f},
                                {1.0f, 1.0f, 0.75f}};
  const double x = std::clamp(t, 0.0, 1.0) * 4.0;
  const int i = std::min(static_cast<int>(x), 3);
  const Color c = lerp(static_cast<float>(x - i), stops[i], stops[i + 1]);
  return {srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z)};
}

// Observed (left) and expected (right) counts, phi left to right, cos(theta) = 1 at the top, one colour scale
// (square root of the count, so that the tails of peaked densities stay visible).
Image histogram_picture(const DirectionalHistogram& h, int nz, int np) {
  constexpr int kCell = 8, kGap = 16;
  const int pw = np * kCell, ph = nz * kCell;
  Image img(2 * pw + kGap, ph, {"R", "G", "B"});
  double vmax = 0;
  for (size_t i = 0; i < h.observed.size(); ++i) vmax = std::max({vmax, h.observed[i], h.expected[i]});
  if (vmax <= 0) vmax = 1;
  for (int y = 0; y < ph; ++y)
    for (int x = 0; x < img.width; ++x) {
      Color c(srgb_to_linear(0.5f));
      const int panel = x < pw ? 0 : (x >= pw + kGap ? 1 : -1);
      if (panel >= 0) {
        const int ip = (x - panel * (pw + kGap)) / kCell, iz = nz - 1 - y / kCell;
        const std::vector<double>& v = panel == 0 ? h.observed : h.expected;
        c = colormap(std::sqrt(v[static_cast<size_t>(iz) * np + ip] / vmax));
      }
      for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[k];
    }
  return img;
}

// The fewest samples the chi-square test decides with, from the expected counts at `samples`; 0 when no number does
// (the pdf lies in one cell) or only one beyond 10^18. The test needs two bins expecting 5 or more after pooling the
// cells that expect less: the fullest cell, and all the others together (on their own or pooled), each expecting 5.
uint64_t samples_to_decide(const std::vector<double>& expected, uint64_t samples) {
  if (expected.empty()) return 0;
  const size_t top_cell = static_cast<size_t>(std::max_element(expected.begin(), expected.end()) - expected.begin());
  double rest = 0;
  for (size_t i = 0; i < expected.size(); ++i)
    if (i != top_cell) rest += expected[i];
  const double top = expected[top_cell];
  const double least = std::min(top, rest);
  if (!(least > 0)) return 0;
  const double per_sample = least / static_cast<double>(samples);
  if (!(5.0 / per_sample < 1e18)) return 0;  // beyond any count a run could draw (and uint64_t)
  auto n = static_cast<uint64_t>(std::ceil(5.0 / per_sample));
  while (static_cast<double>(n) * per_sample < 5.0 * (1 + 1e-9)) ++n;  // a margin for the counts' own rounding
  return n;
}

}  // namespace

int check_warp(const Warp& warp, const std::string& title, const std::string& cells_note, uint64_t samples,
               const std::string& out_png, std::ostream& out, std::ostream& err) {
  DirectionalTest cfg;
  if (samples > 0) cfg.samples = samples;
  const DirectionalHistogram h = directional_histogram(
      [&](Pcg32& rng) -> std::optional<Vec3> {
        const float u0 = rng.next_float(), u1 = rng.next_float();
        return warp.sample(Vec2(u0, u1));
      },
      warp.pdf, cfg);
  const ChiSquareResult r = chi_square_test(h.observed, h.expected, cfg.alpha, cfg.num_tests);
  // No statistic (dof 0) without an impossible sample (infinite statistic): too few samples for any verdict on
  // the sampler, a usage error.
  if (r.dof == 0 && !std::isinf(r.statistic)) {
    err << "lumis: warptest: " << cfg.samples << " samples are too few for " << title << ": " << r.message;
    if (const uint64_t need = samples_to_decide(h.expected, cfg.samples))
      err << "; use --samples " << need << " or more";
    err << '\n';
    return 2;
  }

  out << "warptest " << title << ": " << cfg.samples << " samples in " << cfg.cos_theta_bins << " x " << cfg.phi_bins
      << " (cos theta, phi) cells" << cells_note << ", seed " << cfg.seed << '\n';
  out << std::setprecision(6) << "  chi-square statistic " << r.statistic << ", dof " << r.dof << ", p-value "
      << r.p_value << ", alpha " << r.significance << '\n';
  out << "  " << (r.passed ? "PASSED" : "FAILED") << ": " << r.message << '\n';

  if (!out_png.empty()) {
    try {
      write_image(out_png, histogram_picture(h, cfg.cos_theta_bins, cfg.phi_bins));
      out << "  wrote " << out_png << " (left: observed, right: expected)\n";
    } catch (const std::exception& e) {
      err << "lumis: warptest: " << e.what() << '\n';
      return 3;
    }
  }
  return r.passed ? 0 : 1;
}

}  // namespace lumis
