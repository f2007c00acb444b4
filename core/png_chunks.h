// A PNG's chunk layout, checked before libpng sees the file: libpng reports a file that ends early by longjmp,
// which prints its own stray line to stderr and leaks the message OpenImageIO was building. A cut-off PNG (an
// interrupted copy or download) is caught here instead, with the byte where it ends.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace lumis {

/// Reads `n` bytes at byte `offset` of the file into `out`; false when fewer than `n` are there.
using ByteReader = std::function<bool(size_t offset, unsigned char* out, size_t n)>;

/// Why a file of `size` bytes that starts with the PNG signature is cut short or has an impossible chunk length,
/// as one line ("truncated PNG: ..."); empty when every chunk fits and IEND is reached, or when the file is not a
/// PNG at all (the decoder says so). Reads only the 8-byte chunk headers, never the pixel data.
std::string png_structure_error(size_t size, const ByteReader& read);

/// The same for bytes held in memory.
std::string png_structure_error(const unsigned char* bytes, size_t size);

}  // namespace lumis
