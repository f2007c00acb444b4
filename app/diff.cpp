#include "app/diff.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "app/montage.h"

namespace lumis {

namespace {

std::string size_of(const Image& img) { return std::to_string(img.width) + "x" + std::to_string(img.height); }

// Variance channels named by the film (core/film.h): the variance of each pixel's mean.
const char* const kVarianceNames[3] = {"variance.R", "variance.G", "variance.B"};

std::vector<int> variance_channels(const Image& img) {
  std::vector<int> idx;
  for (const char* n : kVarianceNames) {
    const int i = img.channel_index(n);
    if (i < 0) return {};
    idx.push_back(i);
  }
  return idx;
}

}  // namespace

bool is_grey(const Image& img) {
  // OpenImageIO names a greyscale PNG's one channel Y (and its alpha A). Y beside R, G, B or X is not grey: in an
  // XYZ image it is one of three colour channels, and R, G, B taken as Y three times would compare the wrong thing.
  // Other channels (a depth Z, normals, variance) are ignored, as they are beside R, G, B.
  if (img.channel_index("Y") < 0) return false;
  for (const char* c : {"R", "G", "B", "X"})
    if (img.channel_index(c) >= 0) return false;
  return true;
}

std::vector<int> rgb_channels(const Image& img, const std::string& name) {
  // A grey image compares as R = G = B = Y.
  if (is_grey(img)) {
    const int y = img.channel_index("Y");
    return {y, y, y};
  }
  std::vector<int> idx;
  std::string missing;
  for (const char* n : {"R", "G", "B"}) {
    const int i = img.channel_index(n);
    if (i < 0) missing += std::string(missing.empty() ? "" : ", ") + n;
    idx.push_back(i);
  }
  if (!missing.empty()) {
    std::string have;
    for (const std::string& c : img.channel_names) have += (have.empty() ? "" : ", ") + c;
    throw DiffError(name + ": no " + missing + " channel (has " + have +
                    "); R, G, B (or the Y of a grey image: Y alone or with A) are compared");
  }
  return idx;
}

void check_comparable(const Image& a, const Image& b, const DiffOptions& options) {
  if (a.width != b.width || a.height != b.height)
    throw DiffError("images differ in size: " + options.name_a + " is " + size_of(a) + ", " + options.name_b +
                    " is " + size_of(b));
  if (a.width <= 0 || a.height <= 0) throw DiffError(options.name_a + " and " + options.name_b + " have no pixels");
  rgb_channels(a, options.name_a);
  rgb_channels(b, options.name_b);
}

DiffMetrics compute_metrics(const Image& a, const Image& b, const DiffOptions& options) {
  check_comparable(a, b, options);
  const std::vector<int> ca = rgb_channels(a, options.name_a), cb = rgb_channels(b, options.name_b);
  DiffMetrics m;
  m.width = a.width;
  m.height = a.height;
  m.tolerance = options.tolerance;
  double sum_sq = 0, sum_rel = 0, sum_abs = 0, peak = 0;
  uint64_t over = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      bool pixel_over = false;
      for (int k = 0; k < 3; ++k) {
        const double va = a.at(x, y, ca[k]), vb = b.at(x, y, cb[k]);
        if (!std::isfinite(va) || !std::isfinite(vb)) {
          ++m.nonfinite;
          pixel_over = true;
          continue;
        }
        const double d = va - vb;
        sum_sq += d * d;
        sum_rel += d * d / (vb * vb + 1e-2);
        sum_abs += std::abs(d);
        m.max_abs = std::max(m.max_abs, std::abs(d));
        peak = std::max(peak, vb);
        pixel_over |= std::abs(d) > options.tolerance;
      }
      over += pixel_over;
    }
  const double n = 3.0 * a.width * a.height;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool ok = m.nonfinite == 0;
  m.mse = ok ? sum_sq / n : nan;
  m.rmse = std::sqrt(m.mse);
  m.rel_mse = ok ? sum_rel / n : nan;
  m.mae = ok ? sum_abs / n : nan;
  if (!ok) m.max_abs = nan;
  m.psnr_peak = options.psnr_peak > 0 ? options.psnr_peak : peak;
  m.psnr = !ok                ? nan
           : m.mse == 0       ? std::numeric_limits<double>::infinity()
           : m.psnr_peak <= 0 ? -std::numeric_limits<double>::infinity()
                              : 20.0 * std::log10(m.psnr_peak) - 10.0 * std::log10(m.mse);  // peak^2 may overflow
  // NaN too when a value is not finite, so that no threshold on it passes such an image.
  m.over_tolerance_percent = ok ? 100.0 * static_cast<double>(over) / (static_cast<double>(a.width) * a.height) : nan;
  return m;
}

const std::vector<std::string>& metric_names() {
  static const std::vector<std::string> names = {"mse", "rmse", "relmse", "mae", "psnr", "maxabs", "over"};
  return names;
}

double metric_value(const DiffMetrics& m, const std::string& name) {
  if (name == "mse") return m.mse;
  if (name == "rmse") return m.rmse;
  if (name == "relmse") return m.rel_mse;
  if (name == "mae") return m.mae;
  if (name == "psnr") return m.psnr;
  if (name == "maxabs") return m.max_abs;
  if (name == "over") return m.over_tolerance_percent;
  std::string valid;
  for (const std::string& n : metric_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown metric '" + name + "' (valid: " + valid + ")");
}

bool metric_passes(const std::string& name, double value, double threshold) {
  // NaN compares false both ways, so an image with non-finite pixels never passes.
  return name == "psnr" ? value >= threshold : value <= threshold;
}

ZTestResult z_test(const Image& a, const Image& b, const ZTestOptions& options, const DiffOptions& names) {
  check_comparable(a, b, names);
  const std::vector<int> vb = variance_channels(b);
  if (vb.empty())
    throw DiffError(names.name_b + ": the z-test needs the reference's variance.R, variance.G, variance.B channels "
                    "(EXR written by lumis render); " + names.name_a + " is the image tested against it");
  const std::vector<int> va = variance_channels(a);
  const std::vector<int> ca = rgb_channels(a, names.name_a), cb = rgb_channels(b, names.name_b);
  ZTestResult r;
  r.used_a_variance = !va.empty();
  r.tested = 3ull * a.width * a.height;
  // Sidak: the per-test level that keeps the family-wise false-rejection rate at alpha for independent tests.
  r.per_test_alpha = -std::expm1(std::log1p(-options.alpha) / static_cast<double>(r.tested));
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int k = 0; k < 3; ++k) {
        const double xa = a.at(x, y, ca[k]), xb = b.at(x, y, cb[k]);
        // Each variance checked on its own: a negative one is corrupt data even where the other's would hide it.
        const double var_b = b.at(x, y, vb[k]), var_a = r.used_a_variance ? a.at(x, y, va[k]) : 0.0;
        const double var = var_a + var_b;
        const auto reject_unscored = [&] {  // rejected without a p-value: remember the first such place
          ++r.rejected;
          if (r.unscored_x >= 0) return;
          r.unscored_x = x;
          r.unscored_y = y;
          r.unscored_channel = k;
        };
        if (!std::isfinite(xa) || !std::isfinite(xb) || !std::isfinite(var) || var_a < 0 || var_b < 0) {
          ++r.nonfinite;
          reject_unscored();
          continue;
        }
        const double d = xa - xb;
        if (var == 0) {
          // No noise estimate (e.g. a pixel that saw only background): demand agreement to float precision.
          ++r.zero_variance;
          if (std::abs(d) > 1e-5 * std::max(std::abs(xa), std::abs(xb))) {
            ++r.zero_variance_rejected;
            reject_unscored();
          }
          continue;
        }
        const double p = std::erfc(std::abs(d) / std::sqrt(2.0 * var));
        if (p < r.min_p) {
          r.min_p = p;
          r.worst_x = x;
          r.worst_y = y;
          r.worst_channel = k;
        }
        if (p < r.per_test_alpha) ++r.rejected;
      }
  r.passed = r.rejected == 0;
  return r;
}

std::vector<float> abs_error_map(const Image& a, const Image& b, const DiffOptions& options) {
  check_comparable(a, b, options);
  const std::vector<int> ca = rgb_channels(a, options.name_a), cb = rgb_channels(b, options.name_b);
  std::vector<float> e(static_cast<size_t>(a.width) * a.height);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      float s = 0;
      for (int k = 0; k < 3; ++k) s += std::abs(a.at(x, y, ca[k]) - b.at(x, y, cb[k]));
      e[static_cast<size_t>(y) * a.width + x] = s / 3.0f;
    }
  return e;
}

Image error_heatmap(const std::vector<float>& error, int width, int height, double lo, double hi,
                    const std::string& caption) {
  return false_colour_with_bar(error, width, height, lo, hi, caption);
}

}  // namespace lumis
