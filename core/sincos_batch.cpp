// sincos_turns over arrays: one loop, compiled for three instruction sets and picked at run time (core/simd.h).
// sincos_turns uses exactly rounded operations only and this file is compiled without contraction, so every copy
// returns the scalar function's values bit for bit (SincosBatch tests).
#include "core/sincos_batch.h"

#include <algorithm>

#include "core/math.h"
#include "core/simd.h"

namespace lumis {
namespace {

[[gnu::always_inline]] inline void kernel(const float* t, int n, float* s, float* c) {
  for (int i = 0; i < n; ++i) sincos_turns(t[i], s[i], c[i]);
}

void run_baseline(const float* t, int n, float* s, float* c) { kernel(t, n, s, c); }
#if LUMIS_SIMD_DISPATCH
LUMIS_TARGET_AVX2 void run_avx2(const float* t, int n, float* s, float* c) { kernel(t, n, s, c); }
LUMIS_TARGET_AVX512 void run_avx512(const float* t, int n, float* s, float* c) { kernel(t, n, s, c); }
#endif

}  // namespace

void sincos_turns_many(const float* t, int n, float* sin_out, float* cos_out, int max_level) {
  const int level = std::min(max_level, simd_level());
#if LUMIS_SIMD_DISPATCH
  if (level >= 2) return run_avx512(t, n, sin_out, cos_out);
  if (level == 1) return run_avx2(t, n, sin_out, cos_out);
#endif
  (void)level;
  run_baseline(t, n, sin_out, cos_out);
}

}  // namespace lumis
