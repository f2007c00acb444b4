// Memory checks before a large allocation: `render` and `compare` refuse an image that cannot fit, up front and with
// the numbers, instead of dying in an allocation half-way.
#pragma once

#include <cstdint>
#include <string>

namespace lumis {

/// Bytes a render of width x height pixels still allocates once the scene is loaded (film with `channels` float
/// channels, the image handed to the writer, its copy and the encoded file).
uint64_t render_memory_estimate(int width, int height, int channels);
/// Bytes this process may still allocate (MemAvailable, lowered by ulimit -v); *source names where that came from.
uint64_t available_memory(std::string& source);
/// "12.3 GiB" or "45.6 MiB".
std::string format_bytes(uint64_t bytes);
/// Empty when `need` bytes fit in available_memory(); else "a W x H WHAT needs about X of memory (PARTS), but only
/// Y is available (SOURCE); lower --width/--height".
std::string memory_problem(uint64_t need, int width, int height, const std::string& what, const std::string& parts);

}  // namespace lumis
