// Writing images through OpenImageIO (core/image_io.h): encoded in memory, then written whole or not at all; and
// the sRGB transfer curve that 8-bit files use both ways.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "core/atomic_write.h"
#include "core/file_ext.h"
#include "core/image_io.h"

namespace lumis {

namespace OIIO = OIIO_NAMESPACE;

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& reason) { throw ImageError(path + ": " + reason); }

// Display formats hold encoded values; HDR formats hold linear radiance. The extension decides which.
enum class Kind { Exr, Hdr, Png, Jpg };

Kind kind_of(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".exr") return Kind::Exr;
  if (ext == ".hdr") return Kind::Hdr;
  if (ext == ".png") return Kind::Png;
  if (ext == ".jpg" || ext == ".jpeg") return Kind::Jpg;
  fail(path, output_format_problem(path));
}

/// Colour (first three channels, grey replicated) of pixel i, for formats that store only RGB.
Color pixel_rgb(const Image& img, size_t i) {
  const float* p = &img.data[i * img.channels];
  if (img.channels >= 3) return {p[0], p[1], p[2]};
  return Color(p[0]);
}

/// The file's bytes, encoded in memory: the writers never touch the disk, so none of their ways of failing there
/// applies (libpng ignoring a short write, libjpeg calling exit()); write_file_atomically checks every step instead.
std::vector<unsigned char> encode(const std::string& final_path, const Image& image, Kind kind,
                                  const WriteOptions& options) {
  const size_t n = static_cast<size_t>(image.width) * image.height;
  const char* format = kind == Kind::Exr ? "openexr" : kind == Kind::Hdr ? "hdr" : kind == Kind::Png ? "png" : "jpeg";
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto out = OIIO::ImageOutput::create(format);
  if (!out) fail(final_path, "no " + std::string(format) + " writer: " + OIIO::geterror());
  if (!out->set_ioproxy(&memory)) fail(final_path, "the " + std::string(format) + " writer cannot write to memory");
  auto add_metadata = [&](OIIO::ImageSpec& spec) {
    for (const auto& [key, value] : options.metadata) spec.attribute(key, value);
  };

  if (kind == Kind::Exr) {
    OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
    spec.channelnames = image.channel_names;
    spec.alpha_channel = image.channel_index("A");
    spec.attribute("compression", "zip");
    add_metadata(spec);
    if (!out->open(final_path, spec)) fail(final_path, out->geterror());
    if (!out->write_image(OIIO::TypeDesc::FLOAT, image.data.data())) fail(final_path, out->geterror());
  } else if (kind == Kind::Hdr) {
    std::vector<float> rgb(n * 3);
    for (size_t i = 0; i < n; ++i) {
      const Color c = pixel_rgb(image, i);
      // RGBE holds neither negatives, NaN nor infinity, and its exponent byte wraps above 2^127: NaN is written
      // as 0 (as in PNG), +Inf and anything above 1e38 as 1e38.
      for (int k = 0; k < 3; ++k) rgb[i * 3 + k] = std::isnan(c[k]) ? 0.0f : std::clamp(c[k], 0.0f, 1e38f);
    }
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
    add_metadata(spec);
    if (!out->open(final_path, spec)) fail(final_path, out->geterror());
    if (!out->write_image(OIIO::TypeDesc::FLOAT, rgb.data())) fail(final_path, out->geterror());
  } else {
    // OIIO quantises float to 8 bits without any transfer curve, so the sRGB encoding is ours.
    const float scale = std::exp2(options.exposure);
    std::vector<unsigned char> rgb(n * 3);
    for (size_t i = 0; i < n; ++i) {
      const Color c = pixel_rgb(image, i);
      for (int k = 0; k < 3; ++k) {
        float v = c[k] * scale;
        v = std::isnan(v) ? 0.0f : clamp(linear_to_srgb(clamp(v, 0.0f, 1.0f)), 0.0f, 1.0f);
        rgb[i * 3 + k] = static_cast<unsigned char>(std::lround(v * 255.0f));
      }
    }
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    add_metadata(spec);
    if (kind == Kind::Jpg) spec.attribute("Compression", "jpeg:95");
    if (!out->open(final_path, spec)) fail(final_path, out->geterror());
    if (!out->write_image(OIIO::TypeDesc::UINT8, rgb.data())) fail(final_path, out->geterror());
  }
  if (!out->close()) fail(final_path, out->geterror());
  out.reset();  // the writer lets go of `memory` before `bytes` leaves
  return bytes;
}

}  // namespace

float linear_to_srgb(float v) {
  if (v <= 0.0031308f) return 12.92f * v;
  return 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgb_to_linear(float v) {
  if (v <= 0.04045f) return v / 12.92f;
  return std::pow((v + 0.055f) / 1.055f, 2.4f);
}

void write_image(const std::string& path, const Image& image, const WriteOptions& options) {
  const Kind kind = kind_of(path);
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0)
    fail(path, "cannot write an empty image");
  if (image.data.size() != static_cast<size_t>(image.width) * image.height * image.channels ||
      image.channel_names.size() != static_cast<size_t>(image.channels))
    fail(path, "image data does not match its size and channel count");

  const std::vector<unsigned char> bytes = encode(path, image, kind, options);
  const std::string why =
      write_file_atomically(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
  if (!why.empty()) fail(path, why);
}

}  // namespace lumis
