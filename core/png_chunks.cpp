#include "core/png_chunks.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>

namespace lumis {

namespace {

constexpr unsigned char kSignature[8] = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
constexpr size_t kHeader = 8;  // length + type before a chunk's data
constexpr size_t kCrc = 4;     // after it

bool is_letter(unsigned char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

/// CRC-32 of one byte per entry (reflected polynomial 0xEDB88320, as PNG and zlib use).
constexpr std::array<uint32_t, 256> kCrcTable = [] {
  std::array<uint32_t, 256> t{};
  for (uint32_t n = 0; n < 256; ++n) {
    uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[n] = c;
  }
  return t;
}();

/// Whether the critical chunk at `offset` (type `head[4..7]`, `length` bytes of data) fails its CRC. Reads the data
/// in blocks; false when the reader fails (the caller has already checked that the chunk fits in the file).
bool crc_fails(size_t offset, unsigned long length, const unsigned char* head, const ByteReader& read) {
  uint32_t crc = png_crc32(0, head + 4, 4);
  unsigned char block[1 << 16];
  for (size_t done = 0; done < length;) {
    const size_t n = std::min<size_t>(sizeof block, length - done);
    if (!read(offset + kHeader + done, block, n)) return false;
    crc = png_crc32(crc, block, n);
    done += n;
  }
  unsigned char stored[kCrc];
  if (!read(offset + kHeader + length, stored, kCrc)) return false;
  const uint32_t want = (uint32_t{stored[0]} << 24) | (uint32_t{stored[1]} << 16) | (uint32_t{stored[2]} << 8) |
                        uint32_t{stored[3]};
  return crc != want;
}

}  // namespace

uint32_t png_crc32(uint32_t crc, const unsigned char* bytes, size_t n) {
  crc = ~crc;
  for (size_t i = 0; i < n; ++i) crc = kCrcTable[(crc ^ bytes[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

std::string png_structure_error(size_t size, const ByteReader& read) {
  unsigned char head[kHeader];
  if (size < sizeof(kSignature) || !read(0, head, sizeof(kSignature)) ||
      std::memcmp(head, kSignature, sizeof(kSignature)) != 0)
    return {};  // not a PNG: the decoder's own message is the right one
  const std::string at = " at byte ";
  std::string previous = "the signature";
  for (size_t offset = sizeof(kSignature);;) {
    if (offset == size) return "truncated PNG: the file ends after " + previous + ", before the IEND chunk";
    if (size - offset < kHeader || !read(offset, head, kHeader))
      return "truncated PNG: the file ends inside the chunk header" + at + std::to_string(offset);
    const unsigned long length = (static_cast<unsigned long>(head[0]) << 24) | (head[1] << 16) | (head[2] << 8) |
                                 static_cast<unsigned long>(head[3]);
    for (int k = 4; k < 8; ++k)
      if (!is_letter(head[k]))
        return "corrupt PNG: the chunk" + at + std::to_string(offset) + " has no valid type (4 ASCII letters)";
    const std::string type(reinterpret_cast<const char*>(head + 4), 4);
    if (length > 0x7fffffffUL)
      return "corrupt PNG: chunk " + type + at + std::to_string(offset) + " declares " + std::to_string(length) +
             " bytes (the limit is 2^31-1)";
    if (size - offset < kHeader + length + kCrc)
      return "truncated PNG: chunk " + type + at + std::to_string(offset) + " declares " + std::to_string(length) +
             " bytes of data, but the file ends at byte " + std::to_string(size);
    // Critical chunks (an upper-case first letter) only: libpng fails on their CRC by longjmp, as on a truncated
    // file (PLTE too, in a true-colour image as in a palette one), but merely warns about an ancillary chunk's and
    // drops it, which is not worth refusing a file for. IEND is not checked either: it holds no data, and
    // OpenImageIO never reads it, so a file damaged only there reads.
    const bool critical = head[4] <= 'Z' && type != "IEND";
    if (critical && crc_fails(offset, length, head, read))
      return "corrupt PNG: chunk " + type + at + std::to_string(offset) +
             " fails its CRC check: the file is damaged";
    if (type == "IEND") return {};
    previous = "chunk " + type;
    offset += kHeader + length + kCrc;
  }
}

std::string png_structure_error(const unsigned char* bytes, size_t size) {
  return png_structure_error(size, [bytes, size](size_t offset, unsigned char* out, size_t n) {
    if (offset > size || size - offset < n) return false;
    std::memcpy(out, bytes + offset, n);
    return true;
  });
}

}  // namespace lumis
