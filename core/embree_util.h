// Embree glue shared by the renderer (core/geometry.cpp, integrators/render.cpp) and the raw-throughput benchmark
// (app/bench_raw.cpp): lumis rays as Embree ray records, and the floating-point mode Embree wants on its threads.
#pragma once

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>
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

/// Embree wants flush-to-zero and denormals-are-zero on every thread that traces rays: set on each worker of the
/// arena when it enters.
class FtzObserver : public tbb::task_scheduler_observer {
 public:
  explicit FtzObserver(tbb::task_arena& arena) : tbb::task_scheduler_observer(arena) { observe(true); }
  ~FtzObserver() override { observe(false); }
  void on_scheduler_entry(bool) override {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  }
};

}  // namespace lumis
