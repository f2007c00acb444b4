// Image files through OpenImageIO. Every image lumis reads or writes goes through here.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace lumis {

/// Read an image with all its channels as float. With srgb_to_linear, 8-bit colour channels (not alpha) are
/// decoded from the sRGB transfer curve. Throws ImageError naming the file on failure.
Image read_image(const std::string& path, bool srgb_to_linear = false);

/// Read an encoded image held in memory (a glTF image in a buffer or a data: URI), decoded exactly as read_image
/// decodes the same bytes from a file. `format` is OpenImageIO's reader ("png", "jpeg"); `name` starts the
/// ImageError's message.
Image read_image_memory(const unsigned char* bytes, size_t size, const std::string& format, const std::string& name,
                        bool srgb_to_linear = false);

struct WriteOptions {
  float exposure = 0;  ///< stops, applied to display formats (png/jpg) only
  /// String attributes stored in the file's header ("lumis:spp" = "64", ...): EXR keeps them all; other formats
  /// keep what their writer supports (PNG text chunks) and drop the rest.
  std::vector<std::pair<std::string, std::string>> metadata;
};

/// Write an image, format by extension: .exr (linear half/float, all channels), .hdr, .png/.jpg (first three
/// channels, exposure, sRGB transfer, clamp to [0,1]). Encoded in memory, then written whole or not at all
/// (write_file_atomically). Throws ImageError naming the file on failure (a full disk included).
void write_image(const std::string& path, const Image& image, const WriteOptions& options = {});

/// sRGB transfer (linear -> encoded) and its inverse.
float linear_to_srgb(float v);
float srgb_to_linear(float v);

}  // namespace lumis
