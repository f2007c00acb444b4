// Film: per-pixel mean of radiance samples, the variance of that mean, and optional AOVs (albedo, shading normal,
// depth of the first hit). Each pixel is written by one thread only and samples arrive in index order, so the
// result is bitwise identical for any thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/math.h"

namespace lumis {

struct FilmOptions {
  bool albedo = false, normal = false, depth = false, variance = true;
};

/// First-hit auxiliary values of one sample.
struct AovSample {
  Color albedo;
  Vec3 normal;
  float depth = 0;
};

class Film {
 public:
  Film(int width, int height, FilmOptions options = {});

  int width() const { return width_; }
  int height() const { return height_; }
  /// Whether any AOV is kept (when not, renderers need not compute AovSamples).
  bool has_aovs() const { return options_.albedo || options_.normal || options_.depth; }
  /// Add one radiance sample to pixel (x, y). Non-finite samples are dropped and counted; an AOV sample with any
  /// non-finite value is left out of the AOV means.
  void add(int x, int y, Color radiance, const AovSample* aov = nullptr);
  /// Samples accumulated in pixel (x, y).
  uint32_t count(int x, int y) const { return px_[index(x, y)].n; }
  /// Mean radiance of pixel (x, y).
  Color mean(int x, int y) const;
  /// Variance of the mean (sample variance / n) of pixel (x, y).
  Color variance_of_mean(int x, int y) const;
  /// Number of non-finite samples dropped so far.
  uint64_t dropped() const;
  /// R, G, B, then (when enabled) variance.R/G/B, albedo.R/G/B, N.X/Y/Z, Z.
  Image to_image() const;

 private:
  struct Pixel {
    double sum[3] = {0, 0, 0};
    double sum_sq[3] = {0, 0, 0};
    float albedo[3] = {0, 0, 0}, normal[3] = {0, 0, 0};
    float depth = 0;
    uint32_t n = 0, dropped = 0;
    uint32_t aov_n = 0;  // samples in the AOV means
  };
  size_t index(int x, int y) const { return static_cast<size_t>(y) * width_ + x; }
  int width_, height_;
  FilmOptions options_;
  std::vector<Pixel> px_;
};

}  // namespace lumis
