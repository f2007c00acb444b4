// Spherical-cap samples of a sphere light for many receivers side by side (SphereLight::sample_many): one plain
// loop over lanes, vectorised (the azimuth's sine and cosine are sincos_turns, not a library call). It uses
// only exactly rounded operations (+, -, *, /, sqrt, min, max, conversions, compares), and this file and
// sphere_light.cpp are compiled without floating-point contraction (no fused multiply-add, which AVX-512 would
// otherwise allow), so every kernel gives SphereLight::sample's numbers bit for bit (SphereLightBatch tests).
#include "core/simd.h"
#include "lights/sphere_cap.h"

namespace lumis::sphere_cap {
namespace {

[[gnu::always_inline]] inline void kernel(Batch& b, int n) {
  const float r = b.r, r2 = r * r;
  for (int k = 0; k < n; ++k) {
    const Vec3 p{b.px[k], b.py[k], b.pz[k]};
    const Vec3 to_c = b.c - p;
    const float d2 = length_squared(to_c);
    const Setup s = setup(r2, d2, {b.ux[k], b.uy[k]});
    const Point q = finish(p, to_c, r, s);
    b.wx[k] = q.wi.x, b.wy[k] = q.wi.y, b.wz[k] = q.wi.z, b.t[k] = q.t;
    b.lx[k] = q.p.x, b.ly[k] = q.p.y, b.lz[k] = q.p.z;
    b.nx[k] = q.n.x, b.ny[k] = q.n.y, b.nz[k] = q.n.z;
    b.one_minus_cos_max[k] = s.one_minus_cos_max;
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

}  // namespace lumis::sphere_cap
