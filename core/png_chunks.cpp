#include "core/png_chunks.h"

#include <cstring>

namespace lumis {

namespace {

constexpr unsigned char kSignature[8] = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
constexpr size_t kHeader = 8;  // length + type before a chunk's data
constexpr size_t kCrc = 4;     // after it

bool is_letter(unsigned char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

}  // namespace

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
