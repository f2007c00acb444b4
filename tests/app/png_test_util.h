// Writes small PNG files straight through OpenImageIO, for tests that need what lumis's own write_image does not
// write: an alpha channel, grey or grey + alpha, 16 bits (test_image_io.cpp, test_gltf_files.cpp).
#pragma once

#include <OpenImageIO/imageio.h>

#include <string>

namespace lumis::test {

/// Writes a width x height PNG from `px`: `channels` interleaved values of `type` (UINT8 or UINT16) per pixel, rows
/// top to bottom; with 2 or 4 channels the last one is straight (unassociated) alpha, as glTF textures hold it.
/// False when OpenImageIO cannot create, write or close the file.
inline bool write_png(const std::string& path, int width, int height, int channels, const void* px,
                      OIIO::TypeDesc type = OIIO::TypeDesc::UINT8) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return false;
  OIIO::ImageSpec spec(width, height, channels, type);
  if (channels == 2 || channels == 4) {
    spec.alpha_channel = channels - 1;
    spec.attribute("oiio:UnassociatedAlpha", 1);
  }
  return out->open(path, spec) && out->write_image(type, px) && out->close();
}

}  // namespace lumis::test
