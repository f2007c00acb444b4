// Geometry's queries at the edges of float: the branch-free rounding of ray origins against next_float_up /
// next_float_down, hit points on triangles down to 1e-12 units, and shadow rays that see a triangle at every scale
// the loader accepts (1e-12 to 1e12), by single, packet and one-by-one queries. Deterministic: no statistics.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

#include "core/geometry.h"
#include "core/ray.h"
#include "core/rng.h"

namespace lumis {
namespace {

// offset_ray_origin rounds each coordinate one float away from the surface with next_float_toward, which must be
// next_float_up / next_float_down exactly: on every special value (zeros, denormals, the largest finite floats,
// infinities) and on random bit patterns of every exponent, for both directions and for none.
TEST(Geometry, NextFloatTowardIsNextFloatUpOrDown) {
  const auto check = [](float v) {
    if (std::isnan(v)) return;
    for (const float dir : {1.0f, -1.0f, 0.0f, -0.0f, 1e-30f, -INFINITY}) {
      const float expect = dir > 0 ? next_float_up(v) : dir < 0 ? next_float_down(v) : v;
      ASSERT_EQ(std::bit_cast<uint32_t>(next_float_toward(v, dir)), std::bit_cast<uint32_t>(expect))
          << "v = " << v << " (bits " << std::bit_cast<uint32_t>(v) << "), dir = " << dir;
    }
  };
  for (const uint32_t bits : {0x00000000u, 0x80000000u, 0x00000001u, 0x80000001u, 0x007fffffu, 0x807fffffu,
                              0x00800000u, 0x80800000u, 0x3f800000u, 0xbf800000u, 0x7f7fffffu, 0xff7fffffu,
                              0x7f800000u, 0xff800000u})
    check(std::bit_cast<float>(bits));
  Pcg32 rng(5, 9);
  for (int i = 0; i < 1'000'000; ++i) check(std::bit_cast<float>(rng.next_u32()));
}

// Hit points on tiny triangles: Embree's barycentrics go wrong when its triple products fall below 1e-18 (its
// reciprocal clamps there; at 1e-10 units they were off by more than the triangle), so fill_hit recomputes them
// from o + t d. Every query kind must put the hit where the ray meets the triangle, at any scale.
TEST(Geometry, TinyTrianglesHitWhereTheRayMeetsThem) {
  for (float s : {1.0f, 1e-8f, 1e-10f, 1e-12f}) {
    Geometry g;
    TriangleMesh m;
    m.positions = {Vec3{-1, 0, -1} * s, Vec3{1, 0, -1} * s, Vec3{1, 0, 1} * s, Vec3{-1, 0, 1} * s};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.material = 0;
    g.add_mesh(m);
    g.commit();
    Ray rays[16];
    Vec3 targets[16];
    for (int i = 0; i < 16; ++i) {
      targets[i] = Vec3{0.3f - 0.05f * i, 0, -0.4f + 0.04f * i} * s;
      const Vec3 o = Vec3{-0.7f + 0.09f * i, 2.0f, 0.3f} * s;
      rays[i] = {o, normalize(targets[i] - o), 0, INFINITY};
    }
    Hit packet[16], each[16];
    bool found_packet[16], found_each[16];
    g.intersect16(rays, 16, packet, found_packet);
    int lanes[16];
    for (int i = 0; i < 16; ++i) lanes[i] = i;
    g.intersect_each(rays, lanes, 16, each, found_each);
    for (int i = 0; i < 16; ++i) {
      Hit single;
      ASSERT_TRUE(g.intersect(rays[i], single)) << s << " " << i;
      ASSERT_TRUE(found_packet[i] && found_each[i]) << s << " " << i;
      for (const Hit* h : {&single, &packet[i], &each[i]})
        EXPECT_LT(length(h->p - targets[i]), 1e-5f * s) << "scale " << s << ", ray " << i;
    }
  }
}

// A triangle between a point and a light point casts its shadow at every scene scale the loader accepts (up to
// kMaxCoordinate, 1e12; here points reach 3e12): by single and packet shadow queries, through shadow_ray. At 1e13
// Embree's triangle test overflows float and a finite ray misses (shadows vanished while the limit was 1e15).
TEST(Geometry, ShadowRaysSeeTrianglesAtEveryScale) {
  for (const float s : {1e-12f, 1.0f, 1e4f, 1e12f}) {
    SCOPED_TRACE(s);
    Geometry g;
    TriangleMesh m;
    m.positions = {{-1 * s, 0.5f * s, 0}, {-0.2f * s, 0.5f * s, 0}, {-0.6f * s, 1.5f * s, 0}};
    m.indices = {0, 1, 2};
    g.add_mesh(m);
    g.commit();
    const Vec3 from{-0.6f * s, 0.8f * s, -2 * s}, to{-0.6f * s, 0.8f * s, 3 * s};
    Ray rays[16];
    for (Ray& r : rays) r = shadow_ray(from, to, {0, 0, -1}, 0);
    EXPECT_TRUE(g.occluded(rays[0]));
    bool packed[16];
    g.occluded16(rays, 16, packed);
    EXPECT_TRUE(packed[0] && packed[15]);
    Hit h;
    EXPECT_TRUE(g.intersect({from, normalize(to - from), 0, INFINITY}, h));
    EXPECT_TRUE(g.occluded({from, normalize(to - from), 0, 5 * s}));  // a finite segment of unit direction
  }
}

}  // namespace
}  // namespace lumis
