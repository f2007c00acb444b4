// `lumis diff A B`: error metrics of A against the reference B, an optional statistical z-test and heatmap.
// Exit codes: 0 passed (or nothing to check), 1 threshold or z-test failed, 2 error (usage, unreadable or
// incomparable images).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/diff.h"
#include "core/file_ext.h"
#include "core/image_io.h"

namespace lumis {

namespace {

nlohmann::json metrics_json(const DiffMetrics& m) {
  return {{"width", m.width},       {"height", m.height},   {"mse", m.mse},
          {"rmse", m.rmse},         {"relmse", m.rel_mse},  {"mae", m.mae},
          {"psnr", m.psnr},         {"psnr_peak", m.psnr_peak}, {"maxabs", m.max_abs},
          {"tolerance", m.tolerance}, {"over", m.over_tolerance_percent}, {"nonfinite", m.nonfinite}};
}

nlohmann::json z_json(const ZTestResult& z, double alpha) {
  return {{"alpha", alpha},
          {"per_test_alpha", z.per_test_alpha},
          {"tested", z.tested},
          {"rejected", z.rejected},
          {"failing_fraction", z.failing_fraction()},
          {"zero_variance", z.zero_variance},
          {"zero_variance_rejected", z.zero_variance_rejected},
          {"nonfinite", z.nonfinite},
          {"scored", z.scored()},
          {"min_p", z.min_p},
          {"worst", {{"x", z.worst_x}, {"y", z.worst_y}, {"channel", z.worst_channel}}},
          {"first_unscored", {{"x", z.unscored_x}, {"y", z.unscored_y}, {"channel", z.unscored_channel}}},
          {"used_test_variance", z.used_a_variance},
          {"passed", z.passed}};
}

}  // namespace

int run_diff(const DiffArgs& args) {
  // Options that only qualify another one: named when that one is absent, as they then change nothing.
  if (args.metric_given && !args.threshold)
    std::cerr << "lumis diff: warning: --metric chooses what --threshold tests; ignored without --threshold (every "
                 "metric is printed)\n";
  if (args.alpha_given && !args.z_test)
    std::cerr << "lumis diff: warning: --alpha is the z-test's significance level; ignored without --z-test\n";
  DiffOptions opt;
  opt.name_a = args.a;
  opt.name_b = args.b;
  opt.tolerance = args.tolerance;
  if (args.psnr_peak == "max") {
    opt.psnr_peak = 0;
  } else {
    try {
      size_t used = 0;
      opt.psnr_peak = std::stod(args.psnr_peak, &used);
      if (used != args.psnr_peak.size() || !(opt.psnr_peak > 0) || !std::isfinite(opt.psnr_peak))
        throw std::invalid_argument("");
    } catch (const std::exception&) {
      std::cerr << "lumis diff: --psnr-peak: expected a positive number or 'max', got '" << args.psnr_peak << "'\n";
      return 2;
    }
  }
  if (!args.heatmap.empty()) {
    // Before the images are read.
    if (const std::string problem = image_output_problem(args.heatmap, "heatmap.png"); !problem.empty()) {
      std::cerr << "lumis diff: " << args.heatmap << ": " << problem << "\n";
      return 2;
    }
    std::error_code ec;
    for (const std::string& input : {args.a, args.b})
      if (std::filesystem::equivalent(args.heatmap, input, ec)) {
        std::cerr << "lumis diff: --heatmap " << args.heatmap << " is the input image " << input
                  << "; give another file name\n";
        return 2;
      }
  }
  Image a, b;
  DiffMetrics m;
  std::optional<ZTestResult> z;
  try {
    // 8- and 16-bit files hold sRGB-encoded values: compare linear radiance, as in EXR files.
    a = read_image(args.a, true);
    b = read_image(args.b, true);
    m = compute_metrics(a, b, opt);
    if (args.z_test) z = z_test(a, b, ZTestOptions{args.alpha}, opt);
    if (!args.heatmap.empty()) {
      const std::vector<float> e = abs_error_map(a, b, opt);
      float lo = INFINITY, hi = -INFINITY;
      for (float v : e)
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
      if (!(lo <= hi)) lo = hi = 0;
      write_image(args.heatmap, error_heatmap(e, a.width, a.height, lo, hi, "MEAN |A-B| OF R,G,B"));
    }
  } catch (const std::exception& e) {
    std::cerr << "lumis diff: " << e.what() << "\n";
    return 2;
  }

  // Which channels were compared: a grey image's Y stands for R, G and B.
  const bool grey_a = is_grey(a), grey_b = is_grey(b);
  const std::string channels = grey_a && grey_b ? "Y (as R, G, B)"
                               : grey_a         ? "Y of A (as R, G, B) and R G B of B"
                               : grey_b         ? "R G B of A and Y of B (as R, G, B)"
                                                : "R G B";
  const double value = metric_value(m, args.metric);
  const bool threshold_ok = !args.threshold || metric_passes(args.metric, value, *args.threshold);
  const bool passed = threshold_ok && (!z || z->passed);
  if (args.json) {
    nlohmann::json j = metrics_json(m);
    j["a"] = args.a;
    j["b"] = args.b;
    j["channels"] = channels;
    if (args.threshold)
      j["threshold"] = {{"metric", args.metric}, {"value", value}, {"threshold", *args.threshold},
                        {"passed", threshold_ok}};
    if (z) j["z_test"] = z_json(*z, args.alpha);
    if (!args.heatmap.empty()) j["heatmap"] = args.heatmap;
    j["passed"] = passed;
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("A: %s\nB (reference): %s\n%dx%d, %s compared\n", args.a.c_str(), args.b.c_str(), m.width,
                m.height, channels.c_str());
    std::printf("  mse     %.6g\n  rmse    %.6g\n  relmse  %.6g\n  mae     %.6g\n", m.mse, m.rmse, m.rel_mse, m.mae);
    std::printf("  psnr    %.3f dB (peak %.6g)\n  maxabs  %.6g\n", m.psnr, m.psnr_peak, m.max_abs);
    std::printf("  over    %.4g%% of pixels have |A-B| > %g in some channel\n", m.over_tolerance_percent,
                m.tolerance);
    if (m.nonfinite) std::printf("  %llu pixel-channels are NaN or infinite\n",
                                 static_cast<unsigned long long>(m.nonfinite));
    if (z) {
      std::printf("z-test: %llu of %llu pixel-channels rejected (%.4g%%)",
                  static_cast<unsigned long long>(z->rejected), static_cast<unsigned long long>(z->tested),
                  100 * z->failing_fraction());
      if (z->scored() == 0) std::printf(", none has a p-value");  // every one had zero or non-finite variance
      else std::printf(", min p %.3g", z->min_p);
      if (z->worst_x >= 0) std::printf(" at (%d, %d) %c", z->worst_x, z->worst_y, "RGB"[z->worst_channel]);
      std::printf(", Sidak level %.3g for alpha %g, variance of %s: %s\n", z->per_test_alpha, args.alpha,
                  z->used_a_variance ? "A + B" : "B", z->passed ? "pass" : "FAIL");
      if (z->nonfinite)
        std::printf("  %llu pixel-channels rejected without a p-value: a value or variance is NaN, infinite or "
                    "negative\n", static_cast<unsigned long long>(z->nonfinite));
      if (z->zero_variance)
        std::printf("  %llu pixel-channels with zero variance compared to 1e-5 relative: %llu rejected\n",
                    static_cast<unsigned long long>(z->zero_variance),
                    static_cast<unsigned long long>(z->zero_variance_rejected));
      if (z->unscored_x >= 0)
        std::printf("  first rejected without a p-value at (%d, %d) %c\n", z->unscored_x, z->unscored_y,
                    "RGB"[z->unscored_channel]);
    }
    if (args.threshold)
      std::printf("threshold: %s %.6g %s %g: %s\n", args.metric.c_str(), value, args.metric == "psnr" ? ">=" : "<=",
                  *args.threshold, threshold_ok ? "pass" : "FAIL");
  }
  return passed ? 0 : 1;
}

}  // namespace lumis
