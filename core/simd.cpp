#include "core/simd.h"

namespace lumis {
namespace {

int detect_level() {
#if LUMIS_SIMD_DISPATCH
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw"))
    return 2;
  return __builtin_cpu_supports("avx2") ? 1 : 0;
#else
  return 0;
#endif
}

}  // namespace

int simd_level() {
  static const int level = detect_level();
  return level;
}

}  // namespace lumis
