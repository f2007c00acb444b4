// Image comparison for `lumis diff` and `lumis compare`: error metrics over the R, G, B channels, a per-pixel
// statistical z-test against a reference that carries the variance of its mean, and a false-colour error picture.
// All functions are pure functions of in-memory images; `a` is the test image and `b` the reference.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/image.h"

namespace lumis {

/// Images that cannot be compared (size, missing channels); the message names both images.
struct DiffError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct DiffOptions {
  std::string name_a = "A", name_b = "B";  ///< for error messages
  double tolerance = 0.01;  ///< absolute per-channel error above which a pixel counts as "over tolerance"
  double psnr_peak = 1.0;   ///< peak value for PSNR; <= 0 means the largest R, G or B value of the reference
};

struct DiffMetrics {
  int width = 0, height = 0;
  double mse = 0;        ///< mean over pixels and R, G, B of (a - b)^2
  double rmse = 0;       ///< sqrt(mse)
  double rel_mse = 0;    ///< mean of (a - b)^2 / (b^2 + 1e-2)
  double mae = 0;        ///< mean of |a - b|
  double psnr = 0;       ///< 10 log10(peak^2 / mse) in dB; +inf for identical images
  double psnr_peak = 1;  ///< the peak actually used
  double max_abs = 0;    ///< largest |a - b| over pixels and channels
  double tolerance = 0;
  double over_tolerance_percent = 0;  ///< pixels with |a - b| > tolerance in any channel, in percent
  uint64_t nonfinite = 0;  ///< pixel-channels where a or b is NaN or infinite (every metric then is NaN)
};

/// Whether an image is grey: a Y channel and no other but an alpha channel A (not X, Y, Z, nor R, G, B with Y).
bool is_grey(const Image& img);
/// Indices of the R, G and B channels (a grey image's Y channel three times); throws DiffError naming `name` when
/// one is missing.
std::vector<int> rgb_channels(const Image& img, const std::string& name);
/// Throws DiffError when the sizes differ (naming both images) or one lacks R, G or B (naming that one).
void check_comparable(const Image& a, const Image& b, const DiffOptions& options);

DiffMetrics compute_metrics(const Image& a, const Image& b, const DiffOptions& options = {});

/// Names accepted by metric_value (and `lumis diff --metric`).
const std::vector<std::string>& metric_names();
/// The value of a metric by name; throws std::invalid_argument listing the valid names.
double metric_value(const DiffMetrics& m, const std::string& name);
/// Whether a metric passes a threshold: value <= threshold, except psnr, which passes when value >= threshold.
bool metric_passes(const std::string& name, double value, double threshold);

struct ZTestOptions {
  double alpha = 0.01;  ///< family-wise significance over all pixel-channels (Sidak-corrected per test)
};

struct ZTestResult {
  uint64_t tested = 0;          ///< pixel-channels (width * height * 3)
  uint64_t rejected = 0;        ///< pixel-channels rejected (statistically, zero-variance or non-finite)
  uint64_t zero_variance = 0;   ///< pixel-channels with variance 0 (compared with a relative tolerance of 1e-5)
  uint64_t nonfinite = 0;       ///< pixel-channels with a non-finite value or variance (always rejected)
  double min_p = 1;             ///< smallest two-sided p-value over pixel-channels with variance > 0
  int worst_x = -1, worst_y = -1, worst_channel = -1;  ///< where min_p occurred
  uint64_t zero_variance_rejected = 0;  ///< of zero_variance, those rejected (|a - b| beyond 1e-5 relative)
  int unscored_x = -1, unscored_y = -1, unscored_channel = -1;  ///< first rejection without a p-value (row order)
  double per_test_alpha = 0;    ///< Sidak: 1 - (1 - alpha)^(1 / tested)
  bool used_a_variance = false; ///< the test image's variance was added to the reference's
  bool passed = true;
  double failing_fraction() const { return tested ? static_cast<double>(rejected) / tested : 0.0; }
  /// Pixel-channels with a p-value (variance > 0 and finite values); min_p is 1 when there are none.
  uint64_t scored() const { return tested - zero_variance - nonfinite; }
};

/// Per pixel and channel z = (a - b) / sqrt(var), var = b's variance.R/G/B (+ a's when a has all three), two-sided
/// p = erfc(|z| / sqrt 2), rejected when p < the Sidak level. Throws DiffError when b lacks variance channels.
ZTestResult z_test(const Image& a, const Image& b, const ZTestOptions& options = {}, const DiffOptions& names = {});

/// Per-pixel mean over R, G, B of |a - b| (row-major, width * height).
std::vector<float> abs_error_map(const Image& a, const Image& b, const DiffOptions& options = {});
/// False-colour picture of an error map over [lo, hi] with a colour bar labelled lo and hi.
Image error_heatmap(const std::vector<float>& error, int width, int height, double lo, double hi,
                    const std::string& caption = "");

}  // namespace lumis
