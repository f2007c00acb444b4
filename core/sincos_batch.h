// sin and cos of many angles in turns at once (sincos_turns of core/math.h, vectorised): the BSDF samplers'
// azimuths of a path batch's lanes, computed side by side before the lanes are shaded one by one.
#pragma once

namespace lumis {

/// sin_out[i], cos_out[i] = sin and cos of 2 pi t[i] for i < n, bit for bit what sincos_turns gives (|t| <= 1e6).
/// Runs the widest kernel copy (baseline x86-64, AVX2, AVX-512) allowed by max_level and the CPU (core/simd.h).
void sincos_turns_many(const float* t, int n, float* sin_out, float* cos_out, int max_level = 2);

}  // namespace lumis
