// Spherical-triangle samples for many receivers side by side (MeshLight::sample_many): one plain loop over lanes
// of core/spherical_triangle.h's steps, vectorised. They use only exactly rounded operations (+, -, *, /, sqrt, min,
// max, abs, conversions, compares) and polynomials in place of atan2 and sin/cos; this file and
// core/spherical_polygons.cpp are compiled without floating-point contraction, so every kernel copy gives
// sample_spherical_triangle's numbers bit for bit (SphericalTriangleBatch tests).
#include "core/simd.h"
#include "core/spherical_triangle.h"
#include "core/spherical_triangle_batch.h"

namespace lumis::sph_tri {
namespace {

[[gnu::always_inline]] inline void kernel(Batch& b, int n) {
  for (int k = 0; k < n; ++k) {
    const Sample s = sample({b.px[k], b.py[k], b.pz[k]}, {b.ax[k], b.ay[k], b.az[k]}, {b.bx[k], b.by[k], b.bz[k]},
                            {b.cx[k], b.cy[k], b.cz[k]}, {b.ux[k], b.uy[k]});
    b.wx[k] = s.w.x, b.wy[k] = s.w.y, b.wz[k] = s.w.z, b.pdf[k] = s.pdf;
    b.ok[k] = s.ok;
  }
}

void run_baseline(Batch& b, int n) { kernel(b, n); }
#if LUMIS_SIMD_DISPATCH
LUMIS_TARGET_AVX2 void run_avx2(Batch& b, int n) { kernel(b, n); }
LUMIS_TARGET_AVX512 void run_avx512(Batch& b, int n) { kernel(b, n); }
#endif

}  // namespace

void run(Batch& b, int n, int level) {
#if LUMIS_SIMD_DISPATCH
  if (level >= 2) return run_avx512(b, n);
  if (level == 1) return run_avx2(b, n);
#endif
  (void)level;
  run_baseline(b, n);
}

}  // namespace lumis::sph_tri
