// core/png_chunks: a PNG cut anywhere after its signature is named as truncated, with the byte where it ends; a
// whole file, a non-PNG and trailing bytes after IEND pass. The image-level test (a real PNG cut at every length,
// from a file and from memory, with nothing printed by libpng) is ImageIoTest.ErrorsAndAtomicWrites.
#include "core/png_chunks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace lumis {
namespace {

using Bytes = std::vector<unsigned char>;

void chunk(Bytes& out, const char* type, size_t length) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>(length >> shift));
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), length + 4, 0);  // data and a CRC that is not checked here
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

}  // namespace
}  // namespace lumis
