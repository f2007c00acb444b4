// A float image with named channels (R, G, B, then optional AOV channels), row-major, top row first.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "core/math.h"

namespace lumis {

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> channel_names;  ///< size == channels
  std::vector<float> data;                 ///< width * height * channels

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

}  // namespace lumis
