// Image I/O through OpenImageIO: round trips, the sRGB curve, errors, and atomic writes.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/image_io.h"
#include "tests/app/png_test_util.h"
#include "tests/support/file_size_limit.h"
#include "tests/support/test_dir.h"

namespace fs = std::filesystem;
using namespace lumis;

namespace {

/// A fresh, empty folder per test, removed afterwards.
class ImageIoTest : public test::FolderTest {
 protected:
  ImageIoTest() : FolderTest("lumis_image_io") {}
  /// Empty the folder again (each block of a test starts from nothing).
  void reset() {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
};

Image gradient(int w, int h, std::vector<std::string> names) {
  Image img(w, h, std::move(names));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < img.channels; ++c) img.at(x, y, c) = (x + 1) * 0.037f + y * 0.11f + c * 0.013f - 0.05f;
  return img;
}

}  // namespace

TEST(SrgbCurve, KnownValuesAndInverse) {
  EXPECT_FLOAT_EQ(linear_to_srgb(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(linear_to_srgb(1.0f), 1.0f);
  EXPECT_NEAR(linear_to_srgb(0.18f), 0.46135f, 1e-4f);   // mid grey encodes to about 118/255
  EXPECT_NEAR(srgb_to_linear(0.5f), 0.21404f, 1e-4f);
  EXPECT_NEAR(srgb_to_linear(0.04045f), 0.04045f / 12.92f, 1e-7f);  // end of the linear segment
  EXPECT_NEAR(linear_to_srgb(0.002f), 12.92f * 0.002f, 1e-7f);
  for (int i = 0; i <= 1000; ++i) {
    const float v = i / 1000.0f;
    EXPECT_NEAR(srgb_to_linear(linear_to_srgb(v)), v, 2e-6f) << v;
  }
  // Monotone and continuous across the segment joint.
  EXPECT_NEAR(linear_to_srgb(0.0031308f), linear_to_srgb(0.0031309f), 1e-5f);
}

// One test case per group: every process start loads OpenImageIO (~0.5 s).
TEST_F(ImageIoTest, RoundTrips) {
  {  // ExrRoundTripIsExactWithAllChannels
    reset();
    const Image img = gradient(7, 5, {"R", "G", "B", "albedo.R", "albedo.G", "albedo.B", "depth"});
    const std::string path = file("aov.exr");
    write_image(path, img);
    const Image back = read_image(path);
    ASSERT_EQ(back.width, 7);
    ASSERT_EQ(back.height, 5);
    ASSERT_EQ(back.channels, 7);
    for (const auto& name : img.channel_names) EXPECT_GE(back.channel_index(name), 0) << name;
    // OpenEXR may reorder channels alphabetically within layers: compare by name.
    for (int c = 0; c < img.channels; ++c) {
      const int bc = back.channel_index(img.channel_names[c]);
      for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x) EXPECT_EQ(back.at(x, y, bc), img.at(x, y, c));
    }
    EXPECT_EQ(listing(), std::vector<std::string>{"aov.exr"});
  }
  {  // PngRoundTripWithinQuantisation
    reset();
    Image img(16, 4, {"R", "G", "B", "extra"});
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 16; ++x)
        for (int c = 0; c < 4; ++c) img.at(x, y, c) = (x * 4 + y + c) / 70.0f;
    img.at(0, 0, 0) = 3.0f;   // clamps to 1
    img.at(1, 0, 0) = -1.0f;  // clamps to 0
    const std::string path = file("out.png");
    write_image(path, img);
    const Image raw = read_image(path);  // encoded values
    ASSERT_EQ(raw.channels, 3);          // only the first three channels are written
    EXPECT_EQ(raw.at(0, 0, 0), 1.0f);
    EXPECT_EQ(raw.at(1, 0, 0), 0.0f);
    const Image lin = read_image(path, true);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 16; ++x)
        for (int c = 0; c < 3; ++c) {
          if (y == 0 && x < 2 && c == 0) continue;
          // Half a code value in the encoded domain.
          EXPECT_NEAR(raw.at(x, y, c), linear_to_srgb(img.at(x, y, c)), 0.5f / 255 + 1e-6f);
          const float v = img.at(x, y, c);
          const float tol = srgb_to_linear(std::min(1.0f, linear_to_srgb(v) + 0.5f / 255)) - v + 1e-6f;
          EXPECT_NEAR(lin.at(x, y, c), v, tol);
        }
  }
  {  // PngExposureInStops
    reset();
    Image img(1, 1, {"R", "G", "B"});
    img.at(0, 0, 0) = 0.05f;
    img.at(0, 0, 1) = 0.1f;
    img.at(0, 0, 2) = 0.2f;
    const std::string path = file("exposed.png");
    write_image(path, img, WriteOptions{2.0f});  // x4
    const Image back = read_image(path, true);
    EXPECT_NEAR(back.at(0, 0, 0), 0.2f, 0.003f);
    EXPECT_NEAR(back.at(0, 0, 1), 0.4f, 0.004f);
    EXPECT_NEAR(back.at(0, 0, 2), 0.8f, 0.006f);
  }
  {  // SrgbDecodeLeavesAlphaAlone
    reset();
    Image img(2, 1, {"R", "G", "B", "A"});
    img.at(0, 0, 0) = 0.5f; img.at(0, 0, 3) = 0.5f;
    const std::string path = file("rgba.exr");
    write_image(path, img);
    // Float files are linear: the flag changes nothing.
    EXPECT_EQ(read_image(path, true).at(0, 0, 0), 0.5f);

    // An 8-bit RGBA PNG: colour 128, alpha 128.
    const std::string png_path = file("rgba.png");
    const unsigned char px[4] = {128, 128, 128, 128};
    ASSERT_TRUE(test::write_png(png_path, 1, 1, 4, px));  // write_image writes only RGB
    const Image raw = read_image(png_path);
    ASSERT_EQ(raw.channels, 4);
    EXPECT_NEAR(raw.at(0, 0, 0), 128 / 255.0f, 1e-6f);  // straight alpha: colour not premultiplied
    EXPECT_NEAR(raw.at(0, 0, 3), 128 / 255.0f, 1e-6f);
    const Image lin = read_image(png_path, true);
    EXPECT_NEAR(lin.at(0, 0, 0), srgb_to_linear(128 / 255.0f), 1e-6f);
    EXPECT_NEAR(lin.at(0, 0, 3), 128 / 255.0f, 1e-6f);  // alpha is never decoded
  }
  {  // SixteenBitPngDecodesColourNotAlpha (16-bit files take the float path, not the 8-bit lookup tables)
    reset();
    const std::string path = file("rgba16.png");
    const float code = 32768 / 65535.0f;
    const uint16_t px[4] = {32768, 32768, 32768, 32768};
    ASSERT_TRUE(test::write_png(path, 1, 1, 4, px, OIIO::TypeDesc::UINT16));
    const Image raw = read_image(path);
    ASSERT_EQ(raw.channels, 4);
    EXPECT_NEAR(raw.at(0, 0, 0), code, 1e-6f);
    const Image lin = read_image(path, true);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(lin.at(0, 0, c), srgb_to_linear(code), 1e-6f) << c;
    EXPECT_NEAR(lin.at(0, 0, 3), code, 1e-6f);  // alpha is never decoded
  }
  {  // HdrKeepsRadianceAboveOne
    reset();
    Image img(3, 2, {"R", "G", "B"});
    img.at(2, 1, 0) = 12.5f;
    img.at(2, 1, 1) = 0.25f;
    img.at(2, 1, 2) = 1.0f;
    const std::string path = file("env.hdr");
    write_image(path, img);
    const Image back = read_image(path);
    ASSERT_EQ(back.channels, 3);
    EXPECT_NEAR(back.at(2, 1, 0), 12.5f, 12.5f / 128);  // RGBE: 8-bit mantissa shared by the pixel
    EXPECT_NEAR(back.at(2, 1, 1), 0.25f, 12.5f / 128);
  }
  {  // HdrWritesNonFiniteAndHugeValuesAsFiniteOnes: NaN as 0, +Inf and 3e38 as 1e38 (the largest RGBE holds)
    reset();
    Image img(2, 1, {"R", "G", "B"});
    const float inf = std::numeric_limits<float>::infinity();
    img.at(0, 0, 0) = std::numeric_limits<float>::quiet_NaN(), img.at(0, 0, 1) = inf, img.at(0, 0, 2) = 1.0f;
    img.at(1, 0, 0) = 3e38f, img.at(1, 0, 1) = 0.5f, img.at(1, 0, 2) = -inf;
    const std::string path = file("extreme.hdr");
    write_image(path, img);
    const Image back = read_image(path);
    ASSERT_EQ(back.channels, 3);
    for (float v : back.data) EXPECT_TRUE(std::isfinite(v) && v >= 0) << v;
    EXPECT_EQ(back.at(0, 0, 0), 0.0f);
    EXPECT_NEAR(back.at(0, 0, 1), 1e38f, 1e38f / 128);
    EXPECT_NEAR(back.at(1, 0, 0), 1e38f, 1e38f / 128);
    EXPECT_EQ(back.at(1, 0, 2), 0.0f);
  }
  {  // JpgWrites
    reset();
    const Image img = gradient(8, 8, {"R", "G", "B"});
    write_image(file("a.jpg"), img);
    EXPECT_EQ(read_image(file("a.jpg")).width, 8);
    EXPECT_EQ(listing(), std::vector<std::string>{"a.jpg"});
  }
  {  // MemoryReadsDecodeAsFileReads (glTF's embedded images)
    reset();
    const Image img = gradient(9, 7, {"R", "G", "B"});
    for (const char* name : {"m.png", "m.jpg"}) {
      write_image(file(name), img);
      std::ifstream in(file(name), std::ios::binary);
      const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      const std::string format = std::string(name) == "m.png" ? "png" : "jpeg";
      for (bool srgb : {false, true}) {
        const Image a = read_image(file(name), srgb);
        const Image b = read_image_memory(bytes.data(), bytes.size(), format, "embedded", srgb);
        EXPECT_EQ(a.channel_names, b.channel_names) << name;
        EXPECT_EQ(a.data, b.data) << name << (srgb ? " sRGB" : " linear");
      }
    }
    const std::string junk = "this is not an image";
    try {
      read_image_memory(reinterpret_cast<const unsigned char*>(junk.data()), junk.size(), "png", "images[3]");
      FAIL() << "expected ImageError";
    } catch (const ImageError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("images[3]: ", 0), 0u) << e.what();
    }
  }
}

// A full disk (here a file-size limit, which fails writes the same way) once left a short PNG under the final name
// with success, and a JPEG's temporary file behind. Its own test, so that a machine where the limit cannot be set
// skips only this.
TEST_F(ImageIoTest, AWriteCutShortFailsInEveryFormatAndKeepsTheOldFile) {
  for (const char* ext : {"png", "jpg", "hdr", "exr"}) {
    reset();
    const std::string name = std::string("out.") + ext;
    write_image(file(name), gradient(2, 2, {"R", "G", "B"}));
    Image noise(256, 256, {"R", "G", "B"});  // noise, so that every format needs well over the limit
    uint32_t state = 12345;
    for (float& v : noise.data) v = ((state = state * 1664525u + 1013904223u) >> 8) * 0x1p-24f;
    std::string why;
    {
      test::FileSizeLimit limit(4096);
      if (!limit.ok()) GTEST_SKIP() << "cannot set a file-size limit here";
      try {
        write_image(file(name), noise);
      } catch (const ImageError& e) {
        why = e.what();
      }
    }
    EXPECT_EQ(why.rfind(file(name) + ": cannot write: File too large (after 4096 of ", 0), 0u) << ext << ": " << why;
    EXPECT_EQ(read_image(file(name)).width, 2) << ext;
    EXPECT_EQ(listing(), std::vector<std::string>{name}) << ext;
  }
}

// Failures name the file and leave no temporary behind.
TEST_F(ImageIoTest, ErrorsAndAtomicWrites) {
  {  // UnknownExtensionIsAnErrorAndWritesNothing
    reset();
    const Image img = gradient(2, 2, {"R", "G", "B"});
    try {
      write_image(file("out.bmpx"), img);
      FAIL() << "expected ImageError";
    } catch (const ImageError& e) {
      EXPECT_NE(std::string(e.what()).find(file("out.bmpx") + ": "), std::string::npos) << e.what();
    }
    EXPECT_TRUE(listing().empty());
  }
  {  // FailedWriteLeavesNoTemporary
    reset();
    const Image img = gradient(2, 2, {"R", "G", "B"});
    // The destination is an existing non-empty folder: the rename must fail after the temporary was written.
    fs::create_directories(dir_ / "taken.png" / "inside");
    EXPECT_THROW(write_image(file("taken.png"), img), ImageError);
    EXPECT_EQ(listing(), std::vector<std::string>{"taken.png"});
    // A missing folder fails at open.
    EXPECT_THROW(write_image(file("nofolder/x.exr"), img), ImageError);
    EXPECT_EQ(listing(), std::vector<std::string>{"taken.png"});
  }
  {  // OverwriteReplacesAtomically
    reset();
    write_image(file("x.exr"), gradient(2, 2, {"R", "G", "B"}));
    write_image(file("x.exr"), gradient(4, 3, {"R", "G", "B"}));
    EXPECT_EQ(read_image(file("x.exr")).width, 4);
    EXPECT_EQ(listing(), std::vector<std::string>{"x.exr"});
  }
  {  // ReadErrorsNameTheFile
    reset();
    const std::string missing = file("missing.png");
    try {
      read_image(missing);
      FAIL() << "expected ImageError";
    } catch (const ImageError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(missing + ": ", 0), 0u) << e.what();
    }
    const std::string junk = file("junk.png");
    std::ofstream(junk) << "this is not a png";
    try {
      read_image(junk);
      FAIL() << "expected ImageError";
    } catch (const ImageError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(junk + ": ", 0), 0u) << e.what();
    }
    // A header whose size field declares far more pixels than the file holds (20000x20000 from a 64x64 EXR's
    // bytes) is refused before 4.8 GB are allocated, from a file and from memory.
    {
      const std::string small = file("small.exr"), forged = file("forged.exr");
      write_image(small, gradient(64, 64, {"R", "G", "B"}));
      std::ifstream in(small, std::ios::binary);
      std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      const std::string attribute("dataWindow\0box2i\0", 17);
      const size_t at = bytes.find(attribute);
      ASSERT_NE(at, std::string::npos);
      const int32_t window[4] = {0, 0, 19999, 19999};
      bytes.replace(at + attribute.size() + 4, sizeof(window), reinterpret_cast<const char*>(window), sizeof(window));
      std::ofstream(forged, std::ios::binary) << bytes;
      const std::string expected = ": the header declares 20000x20000 with 3 channels (4.8 GB as float), but the "
                                   "file holds only " + std::to_string(bytes.size()) + " bytes: a corrupt header";
      try {
        read_image(forged);
        ADD_FAILURE() << "expected ImageError for a forged size";
      } catch (const ImageError& e) {
        EXPECT_EQ(std::string(e.what()), forged + expected);
      }
      try {
        read_image_memory(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "openexr", "embedded");
        ADD_FAILURE() << "expected ImageError for a forged size in memory";
      } catch (const ImageError& e) {
        EXPECT_EQ(std::string(e.what()), "embedded" + expected);
      }
    }
    // A pipe or a device would block or stream forever: refused by name, before any decoder opens it.
    const std::string pipe = file("pipe.png");
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    for (const std::string& path : {pipe, std::string("/dev/zero")}) {
      try {
        read_image(path);
        ADD_FAILURE() << "expected ImageError for " << path;
      } catch (const ImageError& e) {
        EXPECT_EQ(std::string(e.what()), path + ": is not a regular file (a pipe, device or socket), not an image");
      }
    }
    const std::string unknown = file("data.xyz");
    std::ofstream(unknown) << "plain text";
    EXPECT_THROW(read_image(unknown), ImageError);
    // An empty file is named as such in every format (PNG's decoder said "Not a PNG file", HDR's an RGBE error).
    for (const char* name : {"empty.png", "empty.exr", "empty.hdr", "empty.jpg"}) {
      const std::string empty = file(name);
      std::ofstream{empty};
      try {
        read_image(empty);
        ADD_FAILURE() << "expected ImageError for " << name;
      } catch (const ImageError& e) {
        EXPECT_EQ(std::string(e.what()), empty + ": the file is empty (0 bytes), not an image");
      }
    }
  }
  {  // TruncatedFilesAreErrors: libjpeg fills a cut-off JPEG with grey and only warns; that warning is an error,
     // from a file and from memory (glTF's embedded images), in one line (no stacked OpenImageIO messages).
     // A PNG cut anywhere after its signature never reaches libpng (core/png_chunks.h): nothing on stderr.
    reset();
    for (const char* ext : {".jpg", ".png"}) {
      const bool png = ext == std::string(".png");
      const std::string whole = file(std::string("whole") + ext), cut = file(std::string("cut") + ext);
      write_image(whole, gradient(64, 64, {"R", "G", "B"}));
      std::ifstream in(whole, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      ASSERT_GT(bytes.size(), 400u);
      EXPECT_EQ(read_image(whole).width, 64);  // the whole file reads, with no message left behind
      std::vector<size_t> lengths = {bytes.size() * 2 / 3};
      if (png)
        for (size_t n = 8; n < bytes.size(); n += n < 64 ? 1 : 37) lengths.push_back(n);
      testing::internal::CaptureStderr();
      for (const size_t length : lengths) {
        const std::string head = bytes.substr(0, length);
        std::ofstream(cut, std::ios::binary | std::ios::trunc) << head;
        for (int memory = 0; memory < 2; ++memory) {
          try {
            if (memory)
              read_image_memory(reinterpret_cast<const unsigned char*>(head.data()), head.size(), ext + 1,
                                "embedded");
            else
              read_image(cut);
            ADD_FAILURE() << "expected ImageError: " << ext << " cut at " << length << (memory ? " in memory" : "");
          } catch (const ImageError& e) {
            const std::string what = e.what(), name = memory ? std::string("embedded") : cut;
            EXPECT_EQ(what.rfind(name + (png ? ": truncated PNG: " : ": "), 0), 0u) << length << ": " << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
          }
        }
      }
      const std::string printed = testing::internal::GetCapturedStderr();
      if (png) {
        EXPECT_EQ(printed, "") << "libpng saw a truncated PNG";
      }
    }
  }
  {  // DamagedPngsAreErrorsBeforeLibpng: a flipped bit in the pixel data (a bad disk, a bad copy) fails the IDAT
     // chunk's CRC, which libpng reports by longjmp with its own line on stderr; core/png_chunks names it first.
    reset();
    const std::string whole = file("whole.png"), damaged = file("damaged.png");
    write_image(whole, gradient(64, 64, {"R", "G", "B"}));
    std::ifstream in(whole, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    int flips = 0;
    testing::internal::CaptureStderr();
    for (size_t at = 8; at + 12 <= bytes.size();) {  // each chunk: length, type, data, CRC
      const auto u = [&](size_t i) { return static_cast<size_t>(static_cast<unsigned char>(bytes[i])); };
      const size_t length = u(at) << 24 | u(at + 1) << 16 | u(at + 2) << 8 | u(at + 3);
      if (bytes.compare(at + 4, 4, "IDAT") == 0) {
        for (size_t i = at + 8; i < at + 8 + length; i += 53, ++flips) {
          std::string copy = bytes;
          copy[i] = static_cast<char>(copy[i] ^ 0x10);
          std::ofstream(damaged, std::ios::binary | std::ios::trunc) << copy;
          const std::string want = ": corrupt PNG: chunk IDAT at byte " + std::to_string(at) +
                                   " fails its CRC check: the file is damaged";
          try {
            read_image(damaged);
            ADD_FAILURE() << "expected ImageError: a bit flipped at byte " << i;
          } catch (const ImageError& e) {
            EXPECT_EQ(std::string(e.what()), damaged + want);
          }
          try {
            read_image_memory(reinterpret_cast<const unsigned char*>(copy.data()), copy.size(), "png", "embedded");
            ADD_FAILURE() << "expected ImageError: a bit flipped at byte " << i << " in memory";
          } catch (const ImageError& e) {
            EXPECT_EQ(std::string(e.what()), "embedded" + want);
          }
        }
      }
      at += 12 + length;
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << "libpng saw a damaged PNG";
    EXPECT_GT(flips, 5);
  }
}

