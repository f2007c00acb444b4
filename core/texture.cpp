// Texture lookups by the glTF 2.0 sampler rules. UV (0, 0) is the top-left corner of the image and image row 0 is
// its top row, so v maps to rows directly (no flip). Texel (i, j) has its centre at ((i + 0.5) / W, (j + 0.5) / H).
// KHR_texture_transform is applied to the uv first; wrapping then acts on the transformed uv.
#include "core/texture.h"

#include <cmath>

namespace lumis {

namespace {

/// Brings a texture coordinate (in units of the image size) into a small range with the same wrapped texels,
/// so that the integer texel indices below cannot overflow for huge or far-away uvs.
double reduce(double x, WrapMode mode) {
  if (!std::isfinite(x)) return 0.0;
  switch (mode) {
    case WrapMode::Repeat: return x - std::floor(x);                     // period 1
    case WrapMode::MirroredRepeat: return x - 2.0 * std::floor(0.5 * x);  // period 2
    case WrapMode::ClampToEdge: return std::clamp(x, -1.0, 2.0);          // beyond the edge all reads clamp
  }
  return x;
}

/// Integer texel index i (any value) wrapped into [0, n).
int wrap_index(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::Repeat: {
      const int m = i % n;
      return m < 0 ? m + n : m;
    }
    case WrapMode::MirroredRepeat: {
      // Period 2n: texels 0..n-1 forward, then n-1..0 mirrored (the edge texel repeats once at the seam).
      int m = i % (2 * n);
      if (m < 0) m += 2 * n;
      return m < n ? m : 2 * n - 1 - m;
    }
    case WrapMode::ClampToEdge: return std::clamp(i, 0, n - 1);
  }
  return 0;
}

/// RGBA of texel (x, y) with glTF's implicit channels: grey images spread to RGB, alpha defaults to 1.
Vec4 texel(const Image& img, int x, int y) {
  switch (img.channels) {
    case 1: {
      const float v = img.at(x, y, 0);
      return {v, v, v, 1.0f};
    }
    case 2: {
      const float v = img.at(x, y, 0);
      return {v, v, v, img.at(x, y, 1)};
    }
    case 3: return {img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2), 1.0f};
    default: return {img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2), img.at(x, y, 3)};
  }
}

Vec4 madd(Vec4 acc, Vec4 v, float w) {
  return {acc.x + w * v.x, acc.y + w * v.y, acc.z + w * v.z, acc.w + w * v.w};
}

}  // namespace

/// RGBA at glTF uv (after transform and wrapping); bilinear between the four nearest texel centres.
Vec4 Texture::sample(Vec2 uv_in) const {
  // A texture without pixels is neutral under multiplication (factors then act alone).
  if (!image || image->width <= 0 || image->height <= 0 || image->channels <= 0) return {1, 1, 1, 1};
  const Image& img = *image;
  const Vec2 uv = transform.apply(uv_in);
  const double s = reduce(uv.x, wrap_s) * img.width;
  const double t = reduce(uv.y, wrap_t) * img.height;

  if (nearest) {
    const int x = wrap_index(static_cast<int>(std::floor(s)), img.width, wrap_s);
    const int y = wrap_index(static_cast<int>(std::floor(t)), img.height, wrap_t);
    return texel(img, x, y);
  }
  // Texel centres sit at half-integers: shift so that the integer part names the lower-left neighbour.
  const double xs = s - 0.5, ys = t - 0.5;
  const double fx0 = std::floor(xs), fy0 = std::floor(ys);
  const float fx = static_cast<float>(xs - fx0), fy = static_cast<float>(ys - fy0);
  const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  const int xa = wrap_index(x0, img.width, wrap_s), xb = wrap_index(x0 + 1, img.width, wrap_s);
  const int ya = wrap_index(y0, img.height, wrap_t), yb = wrap_index(y0 + 1, img.height, wrap_t);
  Vec4 r;
  r = madd(r, texel(img, xa, ya), (1 - fx) * (1 - fy));
  r = madd(r, texel(img, xb, ya), fx * (1 - fy));
  r = madd(r, texel(img, xa, yb), (1 - fx) * fy);
  r = madd(r, texel(img, xb, yb), fx * fy);
  return r;
}

}  // namespace lumis
