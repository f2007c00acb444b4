// Reading images through OpenImageIO (core/image_io.h): files and encoded bytes in memory, checked before and
// while they are decoded. Writing is in core/image_write.cpp.
#include "core/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <new>
#include <system_error>

#include "core/png_chunks.h"

namespace lumis {

namespace OIIO = OIIO_NAMESPACE;
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& reason) { throw ImageError(path + ": " + reason); }

/// A reader's message, first line only: OpenImageIO stacks the same failure as seen by each layer (libpng's,
/// then its own summary) on further lines.
std::string first_line(const std::string& message) {
  const size_t start = message.find_first_not_of("\n");
  if (start == std::string::npos) return {};
  return message.substr(start, message.find('\n', start) - start);
}

/// Reads the whole image as `type` into `data`, or fails. A read that succeeds but left a message behind is a
/// damaged file whose missing part the decoder filled in (libjpeg's "Premature end of JPEG file" warning): an error.
void read_pixels(OIIO::ImageInput& in, const std::string& name, OIIO::TypeDesc type, void* data) {
  const int channels = in.spec().nchannels;
  const bool ok = in.read_image(0, 0, 0, channels, type, data);
  const std::string why = first_line(in.geterror());
  if (!ok) fail(name, why.empty() ? "unreadable image data" : why);
  if (!why.empty()) fail(name, why);
}

bool is_alpha_name(const std::string& name) { return name == "A" || name == "a" || name == "alpha" || name == "Alpha"; }

/// The pixels of an opened, checked image as float (see decode).
Image decode_pixels(OIIO::ImageInput& in, const std::string& name, bool srgb_to_linear_colour) {
  const OIIO::ImageSpec& spec = in.spec();

  std::vector<std::string> names = spec.channelnames;
  names.resize(spec.nchannels);
  for (int c = 0; c < spec.nchannels; ++c)
    if (names[c].empty()) names[c] = std::string("C").append(std::to_string(c));
  Image img(spec.width, spec.height, names);
  img.format = in.format_name();
  const bool eight_bit = spec.format == OIIO::TypeDesc::UINT8 && spec.channelformats.empty();
  const bool integer_encoded = spec.format.basetype == OIIO::TypeDesc::UINT8 ||
                               spec.format.basetype == OIIO::TypeDesc::UINT16;
  auto decode_channel = [&](int c) {
    return srgb_to_linear_colour && integer_encoded && c != spec.alpha_channel && !is_alpha_name(names[c]);
  };
  if (eight_bit) {
    // The common texture case, through lookup tables: several times faster than converting floats afterwards.
    std::vector<unsigned char> raw(img.data.size());
    read_pixels(in, name, OIIO::TypeDesc::UINT8, raw.data());
    float linear[256], decoded[256];
    for (int i = 0; i < 256; ++i) {
      linear[i] = i / 255.0f;
      decoded[i] = srgb_to_linear(i / 255.0f);
    }
    std::vector<const float*> lut(img.channels);
    for (int c = 0; c < img.channels; ++c) lut[c] = decode_channel(c) ? decoded : linear;
    for (size_t i = 0; i < raw.size(); ++i) img.data[i] = lut[i % img.channels][raw[i]];
  } else {
    read_pixels(in, name, OIIO::TypeDesc::FLOAT, img.data.data());
    // Integer-encoded files (16 bit here) carry the sRGB curve; float files are already linear.
    for (int c = 0; c < img.channels; ++c)
      if (decode_channel(c))
        for (size_t i = static_cast<size_t>(c); i < img.data.size(); i += img.channels)
          img.data[i] = srgb_to_linear(img.data[i]);
  }
  in.close();
  return img;
}

/// "4096x2048 with 3 channels (0.1 GB as float)": what a header asks lumis to allocate.
std::string declared_size(const OIIO::ImageSpec& spec, double float_bytes) {
  char gigabytes[32];
  std::snprintf(gigabytes, sizeof(gigabytes), "%.1f GB", float_bytes / 1e9);
  return std::to_string(spec.width) + "x" + std::to_string(spec.height) + " with " + std::to_string(spec.nchannels) +
         " channels (" + gigabytes + " as float)";
}

/// Every channel of an opened image as float (see read_image); `name` starts the messages, `encoded_bytes` is the
/// size of the file (or of the bytes in memory).
Image decode(OIIO::ImageInput& in, const std::string& name, bool srgb_to_linear_colour, uint64_t encoded_bytes) {
  const OIIO::ImageSpec& spec = in.spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) fail(name, "image has no pixels");
  if (spec.depth > 1) fail(name, "volume images are not supported");
  // A header that declares far more pixels than its file could hold (a corrupt or hostile size field) is refused
  // before gigabytes are allocated and zeroed. Deflate (PNG, EXR's zip) compresses at most about 1032:1: a flat
  // 8-bit 16k x 8k PNG decodes to 3,900 float bytes per file byte (measured), a flat 1-bit one to about 33,000. The
  // bound is 65536 per byte, applied only above 1 GB of floats (a 16k x 8k RGB map is 1.6 GB); only a flat 1-bit
  // palette image, expanded to RGBA, could exceed it.
  const double float_bytes = double(spec.width) * double(spec.height) * double(spec.nchannels) * sizeof(float);
  if (float_bytes > 1e9 && float_bytes > 65536.0 * double(encoded_bytes))
    fail(name, "the header declares " + declared_size(spec, float_bytes) + ", but the file holds only " +
                   std::to_string(encoded_bytes) + " bytes: a corrupt header");
  try {
    return decode_pixels(in, name, srgb_to_linear_colour);
  } catch (const std::bad_alloc&) {
    fail(name, declared_size(spec, float_bytes) + " needs more memory than is available");
  }
}

/// Straight (unassociated) alpha: glTF textures store colour and coverage independently.
OIIO::ImageSpec read_config() {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  return config;
}

/// Fails when the file is a PNG cut short (see core/png_chunks.h); other files pass untouched.
void check_png_chunks(const std::string& path) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) return;  // OpenImageIO reports an unreadable file
  const auto size = static_cast<size_t>(file.tellg());
  const std::string why = png_structure_error(size, [&file](size_t offset, unsigned char* out, size_t n) {
    file.seekg(static_cast<std::streamoff>(offset));
    return static_cast<bool>(file.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n)));
  });
  if (!why.empty()) fail(path, why);
}

}  // namespace

Image read_image(const std::string& path, bool srgb_to_linear_colour) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(path, "no such file");
  if (fs::is_directory(path, ec)) fail(path, "is a directory, not an image");
  // A pipe or device would block or stream forever (/dev/zero): decoders need a file they can seek in.
  if (!fs::is_regular_file(path, ec)) fail(path, "is not a regular file (a pipe, device or socket), not an image");
  if (fs::file_size(path, ec) == 0 && !ec) fail(path, "the file is empty (0 bytes), not an image");
  check_png_chunks(path);
  const OIIO::ImageSpec config = read_config();
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) {
    const std::string why = first_line(OIIO::geterror());
    fail(path, why.empty() ? "unreadable or unsupported image format" : why);
  }
  std::error_code size_error;
  return decode(*in, path, srgb_to_linear_colour, fs::file_size(path, size_error));
}

Image read_image_memory(const unsigned char* bytes, size_t size, const std::string& format, const std::string& name,
                        bool srgb_to_linear_colour) {
  if (const std::string why = png_structure_error(bytes, size); !why.empty()) fail(name, why);
  // The reader takes its bytes from the proxy named in the open hints (declared first: it outlives the reader).
  OIIO::Filesystem::IOMemReader memory(bytes, size);
  auto in = OIIO::ImageInput::create(format);
  if (!in || !in->supports("ioproxy")) fail(name, "no " + format + " reader that reads from memory");
  OIIO::ImageSpec config = read_config();
  OIIO::Filesystem::IOProxy* proxy = &memory;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  OIIO::ImageSpec spec;
  if (!in->open(name, spec, config)) {
    const std::string why = first_line(in->geterror());
    fail(name, why.empty() ? "unreadable " + format + " data" : why);
  }
  return decode(*in, name, srgb_to_linear_colour, size);
}

}  // namespace lumis
