#include "core/film.h"

#include <algorithm>
#include <limits>

namespace lumis {

Film::Film(int width, int height, FilmOptions options)
    : width_(width), height_(height), options_(options), px_(static_cast<size_t>(width) * height) {}

void Film::add(int x, int y, Color radiance, const AovSample* aov) {
  Pixel& p = px_[index(x, y)];
  if (!is_finite(radiance)) {
    ++p.dropped;
    return;
  }
  for (int c = 0; c < 3; ++c) {
    p.sum[c] += radiance[c];
    p.sum_sq[c] += static_cast<double>(radiance[c]) * radiance[c];
  }
  ++p.n;
  // Running means of the auxiliary values, over the samples whose AOVs are all finite: a sample with a non-finite
  // value is left out of every AOV's mean (and its count), not averaged in as zero.
  if (aov && is_finite(aov->albedo) && is_finite(aov->normal) && std::isfinite(aov->depth)) {
    ++p.aov_n;
    const float w = 1.0f / static_cast<float>(p.aov_n);
    for (int c = 0; c < 3; ++c) {
      p.albedo[c] += (aov->albedo[c] - p.albedo[c]) * w;
      p.normal[c] += (aov->normal[c] - p.normal[c]) * w;
    }
    p.depth += (aov->depth - p.depth) * w;
  }
}

Color Film::mean(int x, int y) const {
  const Pixel& p = px_[index(x, y)];
  if (p.n == 0) return {};
  return {static_cast<float>(p.sum[0] / p.n), static_cast<float>(p.sum[1] / p.n), static_cast<float>(p.sum[2] / p.n)};
}

Color Film::variance_of_mean(int x, int y) const {
  const Pixel& p = px_[index(x, y)];
  if (p.n < 2) return {};
  Color v;
  for (int c = 0; c < 3; ++c) {
    const double m = p.sum[c] / p.n;
    const double var = std::max(0.0, (p.sum_sq[c] - p.n * m * m) / (p.n - 1));
    // Finite samples near float's range have a variance beyond it: written as the largest float, never Inf.
    v[c] = static_cast<float>(std::min(var / p.n, static_cast<double>(std::numeric_limits<float>::max())));
  }
  return v;
}

uint64_t Film::dropped() const {
  uint64_t d = 0;
  for (const Pixel& p : px_) d += p.dropped;
  return d;
}

Image Film::to_image() const {
  std::vector<std::string> names{"R", "G", "B"};
  if (options_.variance) names.insert(names.end(), {"variance.R", "variance.G", "variance.B"});
  if (options_.albedo) names.insert(names.end(), {"albedo.R", "albedo.G", "albedo.B"});
  if (options_.normal) names.insert(names.end(), {"N.X", "N.Y", "N.Z"});
  if (options_.depth) names.push_back("Z");
  Image img(width_, height_, names);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const Pixel& p = px_[index(x, y)];
      int c = 0;
      const Color m = mean(x, y);
      for (int k = 0; k < 3; ++k) img.at(x, y, c++) = m[k];
      if (options_.variance) {
        const Color v = variance_of_mean(x, y);
        for (int k = 0; k < 3; ++k) img.at(x, y, c++) = v[k];
      }
      if (options_.albedo)
        for (int k = 0; k < 3; ++k) img.at(x, y, c++) = p.albedo[k];
      if (options_.normal)
        for (int k = 0; k < 3; ++k) img.at(x, y, c++) = p.normal[k];
      if (options_.depth) img.at(x, y, c++) = p.depth;
    }
  return img;
}

}  // namespace lumis
