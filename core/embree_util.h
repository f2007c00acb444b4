// Embree glue shared by the renderer (core/geometry.cpp, integrators/render.cpp) and the raw-throughput benchmark
// (app/bench_raw.cpp): lumis rays as Embree ray records, and the floating-point mode rays are traced in.
#pragma once

#include <embree3/rtcore.h>
#include <xmmintrin.h>

#include "core/geometry.h"

namespace lumis {

/// A ray as Embree's single-ray record, with no hit yet.
inline RTCRayHit to_embree(const Ray& ray) {
  RTCRayHit rh;
  rh.ray.org_x = ray.o.x;
  rh.ray.org_y = ray.o.y;
  rh.ray.org_z = ray.o.z;
  rh.ray.dir_x = ray.d.x;
  rh.ray.dir_y = ray.d.y;
  rh.ray.dir_z = ray.d.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.time = 0;
  rh.ray.mask = ~0u;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

/// The same ray as lane i of a 16-wide packet.
inline void to_embree16(const Ray& ray, RTCRayHit16& p, int i) {
  p.ray.org_x[i] = ray.o.x;
  p.ray.org_y[i] = ray.o.y;
  p.ray.org_z[i] = ray.o.z;
  p.ray.dir_x[i] = ray.d.x;
  p.ray.dir_y[i] = ray.d.y;
  p.ray.dir_z[i] = ray.d.z;
  p.ray.tnear[i] = ray.tmin;
  p.ray.tfar[i] = ray.tmax;
  p.ray.time[i] = 0;
  p.ray.mask[i] = ~0u;
  p.ray.id[i] = 0;
  p.ray.flags[i] = 0;
  p.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
  p.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
}

/// rays[0..n) (n <= 16) as a 16-wide packet: valid[i] = -1 for each valid ray, 0 for invalid and unused lanes, which
/// still get a finite ray (Embree may read them).
inline void to_embree16(const Ray* rays, int n, RTCRayHit16& p, int* valid) {
  for (int i = 0; i < 16; ++i) {
    const bool ok = i < n && ray_is_valid(rays[i]);
    valid[i] = ok ? -1 : 0;
    to_embree16(ok ? rays[i] : Ray{{0, 0, 0}, {0, 0, 1}, 0, 0}, p, i);
  }
}

/// The floating-point mode every ray query and shading computation of a render runs in, whatever the caller's: the
/// default SSE mode (round to nearest, every exception masked, flush-to-zero and denormals-are-zero off, MXCSR
/// 0x1F80); the caller's is restored at the end of the scope. Set on the thread that starts the parallel work, before
/// its arena's first execute(): a TBB arena takes the mode of the thread that initializes it and runs every task in
/// it, on every worker (oneTBB's "Floating-point Settings"). Not Embree's advice (flush-to-zero, for speed): at scene
/// scales near 1e-11, Embree's products of three lengths are denormals, and flushed to zero they let 39,032 of
/// 560,469 rays meet the surface they leave (Geometry.SpawnedRaysNeverMeetTheirSurfaceAgain; 25,999 with stop 58's 8
/// times larger bound), and rendered the 1e-11 box 46 % too dark. No slower on the shipped scenes, which make no
/// denormals (docs/performance.md).
class TracingFloatMode {
 public:
  TracingFloatMode() : saved_(_mm_getcsr()) { _mm_setcsr(kDefault); }
  ~TracingFloatMode() { _mm_setcsr(saved_); }
  TracingFloatMode(const TracingFloatMode&) = delete;
  TracingFloatMode& operator=(const TracingFloatMode&) = delete;

 private:
  static constexpr unsigned kDefault = 0x1F80;
  unsigned saved_;
};

}  // namespace lumis
