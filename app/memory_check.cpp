// Memory checks before a large allocation (app/memory_check.h).
#include "app/memory_check.h"

#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <limits>

namespace lumis {

// What a render of w x h pixels still allocates after the scene is loaded: the film's accumulators (88 bytes of
// sums, AOVs and counts per pixel, rounded up) plus the float image handed to the writer, the writer's copy and
// the encoded file, which is held in memory until it is written whole (at most as large as the floats).
uint64_t render_memory_estimate(int width, int height, int channels) {
  const uint64_t pixels = static_cast<uint64_t>(width) * static_cast<uint64_t>(height);
  return pixels * (100 + 3 * 4 * static_cast<uint64_t>(channels));
}

// Bytes this process may still allocate: MemAvailable from /proc/meminfo, lowered by an address-space limit
// (ulimit -v) minus what is already mapped. Unknown parts count as unlimited.
uint64_t available_memory(std::string& source) {
  uint64_t avail = std::numeric_limits<uint64_t>::max();
  source = "";
  std::ifstream meminfo("/proc/meminfo");
  for (std::string key; meminfo >> key;) {
    uint64_t kb = 0;
    meminfo >> kb;
    if (key == "MemAvailable:") {
      avail = kb * 1024;
      source = "MemAvailable in /proc/meminfo";
    }
    meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  rlimit lim{};
  if (getrlimit(RLIMIT_AS, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY) {
    uint64_t mapped = 0;
    std::ifstream status("/proc/self/status");
    for (std::string key; status >> key;) {
      if (key == "VmSize:") status >> mapped;
      status.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    const uint64_t limit = lim.rlim_cur, used = mapped * 1024;
    const uint64_t left = limit > used ? limit - used : 0;
    if (left < avail) {
      avail = left;
      source = "the address-space limit (ulimit -v) less what is mapped";
    }
  }
  return avail;
}

std::string format_bytes(uint64_t b) {
  char buf[32];
  if (b >= (uint64_t(1) << 30)) std::snprintf(buf, sizeof buf, "%.1f GiB", b / double(uint64_t(1) << 30));
  else std::snprintf(buf, sizeof buf, "%.1f MiB", b / double(uint64_t(1) << 20));
  return buf;
}

std::string memory_problem(uint64_t need, int width, int height, const std::string& what, const std::string& parts) {
  std::string source;
  const uint64_t have = available_memory(source);
  if (need <= have) return "";
  return "a " + std::to_string(width) + " x " + std::to_string(height) + " " + what + " needs about " +
         format_bytes(need) + " of memory (" + parts + "), but only " + format_bytes(have) + " is available (" +
         source + "); lower --width/--height";
}

}  // namespace lumis
