// Run-time choice of instruction set for the batch kernels (core/sampler_batch.cpp, core/sincos_batch.cpp,
// core/spherical_triangle_batch.cpp, lights/sphere_light_batch.cpp):
// each is a plain loop over lanes compiled three times, for baseline x86-64, AVX2 and AVX-512, with the attributes
// below; the default build runs on any x86-64 and the widest copy the CPU can run is called.
#pragma once

namespace lumis {

/// The widest kernel copy this CPU runs: 0 baseline x86-64 (SSE2), 1 AVX2, 2 AVX-512 (F, DQ, VL, BW). Detected once.
int simd_level();

}  // namespace lumis

#if defined(__x86_64__) && defined(__GNUC__)
#define LUMIS_SIMD_DISPATCH 1
#define LUMIS_TARGET_AVX2 [[gnu::target("avx2")]]
#define LUMIS_TARGET_AVX512 [[gnu::target("avx512f,avx512dq,avx512vl,avx512bw")]]
#else
#define LUMIS_SIMD_DISPATCH 0
#endif
