// A PNG's chunk layout, checked before libpng sees the file: libpng reports a file that ends early, or a critical
// chunk whose CRC fails, by longjmp, which prints its own stray line to stderr and leaks the message OpenImageIO was
// building. A cut-off PNG (an interrupted copy or download) or one with flipped bits is caught here instead, with
// the byte where it ends or the chunk that is damaged.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace lumis {

/// Reads `n` bytes at byte `offset` of the file into `out`; false when fewer than `n` are there.
using ByteReader = std::function<bool(size_t offset, unsigned char* out, size_t n)>;

/// Why a file of `size` bytes that starts with the PNG signature is cut short, has an impossible chunk length or a
/// critical chunk with data (IHDR, PLTE, IDAT) whose CRC does not match its bytes, as one line ("truncated PNG: ...",
/// "corrupt PNG: ..."); empty when every chunk fits and checks out and IEND is reached, or when the file is not a
/// PNG at all (the decoder says so). Reads the critical chunks whole, the ancillary ones' headers only.
std::string png_structure_error(size_t size, const ByteReader& read);

/// The same for bytes held in memory.
std::string png_structure_error(const unsigned char* bytes, size_t size);

/// CRC-32 as PNG defines it, continued from `crc` (0 to start) over `n` bytes: png_crc32(0, "123456789") is
/// 0xCBF43926.
uint32_t png_crc32(uint32_t crc, const unsigned char* bytes, size_t n);

}  // namespace lumis
