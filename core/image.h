// A float image with named channels (R, G, B, then optional AOV channels), row-major, top row first.
#pragma once

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/math.h"

namespace lumis {

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> channel_names;  ///< size == channels
  std::vector<float> data;                 ///< width * height * channels
  std::string format;  ///< OpenImageIO's reader that decoded the file ("openexr", "hdr", "png"); "" if made here

  Image() = default;
  Image(int w, int h, std::vector<std::string> names)
      : width(w), height(h), channels(static_cast<int>(names.size())), channel_names(std::move(names)),
        data(static_cast<size_t>(w) * h * channels, 0.0f) {}

  float& at(int x, int y, int c) { return data[(static_cast<size_t>(y) * width + x) * channels + c]; }
  float at(int x, int y, int c) const { return data[(static_cast<size_t>(y) * width + x) * channels + c]; }
  /// First three channels as a colour (grey for one-channel images).
  Color rgb(int x, int y) const {
    if (channels >= 3) return {at(x, y, 0), at(x, y, 1), at(x, y, 2)};
    return Color(at(x, y, 0));
  }
  /// Index of a named channel, or -1.
  int channel_index(const std::string& name) const {
    for (int i = 0; i < channels; ++i)
      if (channel_names[i] == name) return i;
    return -1;
  }
};

/// Error reading or writing an image file; the message starts with the file name.
struct ImageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws ImageError "<path>: pixel (x, y) channel C is V: expected ..." at the first texel that is NaN or
/// infinite, or (unless allow_negative) negative: lights and colours read from files must be finite and >= 0.
inline void check_texels(const Image& img, const std::string& path, bool allow_negative) {
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < img.channels; ++c) {
        const float v = img.at(x, y, c);
        if (std::isfinite(v) && (allow_negative || v >= 0)) continue;
        char value[32];  // %g: std::to_string printed -1e-9 as "-0.000000", which reads as no error at all
        std::snprintf(value, sizeof(value), "%g", static_cast<double>(v));
        throw ImageError(path + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                         img.channel_names[c] + " is " + value + ": expected finite values" +
                         (allow_negative ? "" : " >= 0"));
      }
}

}  // namespace lumis
