// core/png_chunks: a PNG cut anywhere after its signature is named as truncated, with the byte where it ends; a
// critical chunk with a flipped bit as corrupt; a whole file, a non-PNG, trailing bytes after IEND and a damaged
// ancillary chunk pass. The image-level test (a real PNG cut at every length and damaged, from a file and from
// memory, with nothing printed by libpng) is ImageIoTest.ErrorsAndAtomicWrites.
#include "core/png_chunks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace lumis {
namespace {

using Bytes = std::vector<unsigned char>;

void put32(Bytes& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>(v >> shift));
}

/// A chunk of `length` bytes of data (0, 1, 2, ...; `first` in place of the first ones) and its CRC over type and
/// data.
void chunk(Bytes& out, const char* type, size_t length, const Bytes& first = {}) {
  put32(out, static_cast<uint32_t>(length));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  for (size_t i = 0; i < length; ++i) out.push_back(i < first.size() ? first[i] : static_cast<unsigned char>(i));
  put32(out, png_crc32(0, out.data() + start, 4 + length));
}

/// Signature, IHDR (13 bytes), two IDAT chunks, IEND: 8 + 25 + 112 + 12 + 12 = 169 bytes.
Bytes minimal_png() {
  Bytes b = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
  chunk(b, "IHDR", 13);
  chunk(b, "IDAT", 100);
  chunk(b, "IDAT", 0);
  chunk(b, "IEND", 0);
  return b;
}

std::string check(const Bytes& b, size_t size) { return png_structure_error(b.data(), size); }

TEST(PngChunks, WholeFileAndNonPngPass) {
  const Bytes png = minimal_png();
  ASSERT_EQ(png.size(), 169u);
  EXPECT_EQ(check(png, png.size()), "");
  Bytes trailing = png;
  trailing.push_back(7);  // bytes after IEND are libpng's business, not truncation
  EXPECT_EQ(check(trailing, trailing.size()), "");
  const Bytes text = {'n', 'o', 't', ' ', 'a', ' ', 'p', 'n', 'g', '!'};
  EXPECT_EQ(check(text, text.size()), "");
  for (size_t cut = 0; cut < 8; ++cut) EXPECT_EQ(check(png, cut), "") << cut;  // too short to be a PNG
}

TEST(PngChunks, EveryCutAfterTheSignatureIsTruncation) {
  const Bytes png = minimal_png();
  for (size_t cut = 8; cut < png.size(); ++cut) {
    const std::string why = check(png, cut);
    EXPECT_EQ(why.rfind("truncated PNG: ", 0), 0u) << cut << ": " << why;
  }
  EXPECT_EQ(check(png, 8), "truncated PNG: the file ends after the signature, before the IEND chunk");
  EXPECT_EQ(check(png, 12), "truncated PNG: the file ends inside the chunk header at byte 8");
  EXPECT_EQ(check(png, 60), "truncated PNG: chunk IDAT at byte 33 declares 100 bytes of data, but the file ends "
                            "at byte 60");
  EXPECT_EQ(check(png, 157), "truncated PNG: the file ends after chunk IDAT, before the IEND chunk");
  EXPECT_EQ(check(png, 168), "truncated PNG: chunk IEND at byte 157 declares 0 bytes of data, but the file ends "
                             "at byte 168");
}

TEST(PngChunks, ImpossibleChunksAreCorrupt) {
  Bytes png = minimal_png();
  png[33] = 0x80;  // IDAT's length over 2^31-1
  EXPECT_EQ(check(png, png.size()), "corrupt PNG: chunk IDAT at byte 33 declares 2147483748 bytes (the limit is "
                                    "2^31-1)");
  png = minimal_png();
  png[38] = '1';  // IDAT -> I1AT
  EXPECT_EQ(check(png, png.size()), "corrupt PNG: the chunk at byte 33 has no valid type (4 ASCII letters)");
}

TEST(PngChunks, ReaderFailureIsTruncation) {
  // A file that shrinks while it is read (the reader returns fewer bytes than the size promised).
  const Bytes png = minimal_png();
  const std::string why = png_structure_error(png.size(), [&](size_t offset, unsigned char* out, size_t n) {
    if (offset + n > 40) return false;
    std::copy(png.begin() + static_cast<long>(offset), png.begin() + static_cast<long>(offset + n), out);
    return true;
  });
  EXPECT_EQ(why, "truncated PNG: the file ends inside the chunk header at byte 33");
}

TEST(PngChunks, Crc32MatchesTheStandardsCheckValues) {
  const std::string check_input = "123456789";
  EXPECT_EQ(png_crc32(0, reinterpret_cast<const unsigned char*>(check_input.data()), 9), 0xCBF43926u);
  // Continued over two parts as over one.
  const uint32_t first = png_crc32(0, reinterpret_cast<const unsigned char*>(check_input.data()), 4);
  EXPECT_EQ(png_crc32(first, reinterpret_cast<const unsigned char*>(check_input.data()) + 4, 5), 0xCBF43926u);
  // Every PNG ends with the same 12 bytes: an empty IEND and its CRC, AE 42 60 82.
  const Bytes png = minimal_png();
  EXPECT_EQ(Bytes(png.end() - 4, png.end()), (Bytes{0xAE, 0x42, 0x60, 0x82}));
}

// A flipped bit in a critical chunk's data or CRC is named with the chunk; in an ancillary chunk libpng only warns
// and drops it, and IEND is never read, so those files pass here too.
TEST(PngChunks, DamagedCriticalChunksAreCorruptAncillaryOnesPass) {
  const Bytes png = minimal_png();
  for (size_t i = 41; i < 41 + 100 + 4; ++i) {  // IDAT's data and CRC
    Bytes damaged = png;
    damaged[i] ^= 0x04;
    EXPECT_EQ(check(damaged, damaged.size()), "corrupt PNG: chunk IDAT at byte 33 fails its CRC check: the file is "
                                              "damaged") << i;
  }
  Bytes damaged = png;
  damaged[20] ^= 0x80;  // IHDR's data
  EXPECT_EQ(check(damaged, damaged.size()), "corrupt PNG: chunk IHDR at byte 8 fails its CRC check: the file is "
                                            "damaged");
  damaged = png;
  damaged.back() ^= 1;  // IEND's CRC: OpenImageIO never reads IEND, so neither does this check
  EXPECT_EQ(check(damaged, damaged.size()), "");
  Bytes with_text(png.begin(), png.begin() + 33);
  chunk(with_text, "tEXt", 20);
  with_text.insert(with_text.end(), png.begin() + 33, png.end());
  EXPECT_EQ(check(with_text, with_text.size()), "");
  with_text[33 + 8 + 5] ^= 1;  // the tEXt chunk's data
  EXPECT_EQ(check(with_text, with_text.size()), "");
}

// PLTE is critical in a true-colour image (where it only suggests colours) as in a palette image: Debian's libpng
// 1.6.39 fails on its CRC in both (measured through OpenImageIO), so both are caught here.
TEST(PngChunks, ADamagedPaletteIsCorruptInEveryColourType) {
  for (const unsigned char colour_type : {3, 2}) {
    Bytes png = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
    chunk(png, "IHDR", 13, {0, 0, 0, 4, 0, 0, 0, 4, 8, colour_type});
    chunk(png, "PLTE", 6);  // at byte 33, data from 41
    chunk(png, "IDAT", 10);
    chunk(png, "IEND", 0);
    ASSERT_EQ(check(png, png.size()), "");
    png[43] ^= 1;
    EXPECT_EQ(check(png, png.size()), "corrupt PNG: chunk PLTE at byte 33 fails its CRC check: the file is damaged")
        << int(colour_type);
  }
}

}  // namespace
}  // namespace lumis
