// core/spherical_triangle.h: its atan2 and sin/cos polynomials against long double (a few double ulps, so the float
// results they feed are those of the library functions up to rare last-bit rounding), and the batch kernel at every
// instruction set this CPU runs against sample_spherical_triangle one receiver at a time, bit for bit, over
// receivers that reach every branch (solid angle, area fallback, degenerate). A lane that differed would make
// lockstep renders differ from single paths.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <numbers>
#include <string>

#include "core/rng.h"
#include "core/simd.h"
#include "core/spherical_triangle.h"
#include "core/spherical_triangle_batch.h"
#include "core/warp.h"

namespace lumis {
namespace {

// Distance in double ulps between a computed value and the long-double truth, with an absolute floor (near zero
// the bound is absolute: 1e-300 is 0 for every use).
double ulps(double got, long double truth) {
  const double t = static_cast<double>(truth);
  const double a = std::max(std::abs(t), 1e-300);
  const double ulp = std::nextafter(a, INFINITY) - a;
  return static_cast<double>(std::abs(static_cast<long double>(got) - truth) / ulp);
}

TEST(SphTriMath, Atan2UpperWithinFourUlps) {
  Pcg32 rng(3, 1);
  double worst = 0;
  auto check = [&](double y, double x) {
    const long double truth = std::atan2(static_cast<long double>(y), static_cast<long double>(x));
    const double e = ulps(sph_tri::atan2_upper(y, x), truth);
    worst = std::max(worst, e);
    ASSERT_LE(e, 4) << "atan2(" << y << ", " << x << ")";
  };
  for (int i = 0; i < 200000; ++i) {
    // Both signs of x, ratios from 1e-12 to 1e12, magnitudes from 1e-30 to 1e30.
    const double scale = std::pow(10.0, 60 * rng.next_float() - 30);
    const double ratio = std::pow(10.0, 24 * rng.next_float() - 12);
    const double x = (rng.next_float() < 0.5f ? -1 : 1) * scale;
    check(scale * ratio, x);
  }
  // Near the reduction's boundaries (|y/x| = tan(pi/8), 1) and the axes.
  for (double r : {0.41421356237309503, 0.41421356237309509, 0.4142135623730949, 1.0, 1 - 1e-16, 1 + 2e-16})
    for (double sx : {-1.0, 1.0}) check(r, sx), check(1, sx * r);
  check(0, 1), check(1, 0), check(0, -1), check(1e-300, 1), check(1, -1e-300);
  EXPECT_EQ(sph_tri::atan2_upper(0, 0), 0);
  EXPECT_EQ(sph_tri::atan2_upper(0, 2), 0);
  RecordProperty("worst_ulps", std::to_string(worst));
}

TEST(SphTriMath, SincosRadiansWithinTwoUlps) {
  Pcg32 rng(5, 2);
  auto check = [&](double x) {
    double s, c;
    sph_tri::sincos_radians(x, s, c);
    const long double lx = x;
    // Two ulps of the true value, or an absolute 1e-24 |x| where that is smaller: near a multiple of pi the error
    // is absolute, from pi / 2's two-part constant (about 1e-26 per quarter turn).
    auto bound = [&](long double truth) {
      const double t = std::abs(static_cast<double>(truth));
      return std::max(2 * (std::nextafter(t, INFINITY) - t), 1e-24 * std::max(1.0, std::abs(x)));
    };
    const long double st = std::sin(lx), ct = std::cos(lx);
    ASSERT_LE(static_cast<double>(std::abs(s - st)), bound(st)) << "sin " << x;
    ASSERT_LE(static_cast<double>(std::abs(c - ct)), bound(ct)) << "cos " << x;
  };
  for (int i = 0; i < 200000; ++i) check(2 * std::numbers::pi * rng.next_double());  // Arvo's range [0, 2 pi)
  for (int i = 0; i < 20000; ++i) check(200 * rng.next_double() - 100);
  for (int i = 0; i < 20000; ++i) check(std::pow(10.0, -20 * rng.next_double()));  // tiny sub-areas
  for (int k = -8; k <= 8; ++k) check(k * std::numbers::pi / 4);
  double s, c;
  sph_tri::sincos_radians(0, s, c);
  EXPECT_EQ(s, 0);
  EXPECT_EQ(c, 1);
}

bool same(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }

// A triangle and a receiver of one of several kinds: near, far (solid angles down to ~1e-8 sr, left to area
// sampling), almost in the triangle's plane (near 2 pi, also left to area), in its plane, at a corner, and
// degenerate triangles (collinear, one point).
struct Config {
  Vec3 p, a, b, c;
};
Config config(Pcg32& rng, int kind) {
  auto r3 = [&] { return Vec3{rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f}; };
  Config t{r3() * 4, r3(), r3(), r3()};
  switch (kind % 7) {
    case 1: t.p = t.p * 2000; break;                                   // tiny solid angle
    case 2: t.p = (t.a + t.b + t.c) * (1.0f / 3) + normalize(cross(t.b - t.a, t.c - t.a)) * 1e-4f; break;
    case 3: t.p = t.a + (t.b - t.a) * 0.3f + (t.c - t.a) * 1.5f; break;  // in the plane, outside
    case 4: t.p = t.b; break;                                          // at a corner
    case 5: t.c = t.a + (t.b - t.a) * 2.0f; break;                      // collinear
    case 6: t.b = t.c = t.a; break;                                    // one point
    default: break;
  }
  return t;
}

TEST(SphericalTriangleBatch, EveryKernelEqualsSampleOneReceiverAtATime) {
  constexpr int n = 61;  // not a multiple of any vector width
  int sampled = 0, failed = 0;
  for (int level = 0; level <= simd_level(); ++level)
    for (uint64_t seed = 1; seed <= 30; ++seed) {
      Pcg32 rng(seed, 7);
      sph_tri::Batch b;
      Config cfg[n];
      Vec2 u[n];
      for (int k = 0; k < n; ++k) {
        cfg[k] = config(rng, k);
        u[k] = {rng.next_float(), rng.next_float()};
        if (k == 0) u[k] = {0, 0};
        if (k == 7) u[k] = {0.99999994f, 0.99999994f};
        const Config& t = cfg[k];
        b.px[k] = t.p.x, b.py[k] = t.p.y, b.pz[k] = t.p.z, b.ax[k] = t.a.x, b.ay[k] = t.a.y, b.az[k] = t.a.z;
        b.bx[k] = t.b.x, b.by[k] = t.b.y, b.bz[k] = t.b.z, b.cx[k] = t.c.x, b.cy[k] = t.c.y, b.cz[k] = t.c.z;
        b.ux[k] = u[k].x, b.uy[k] = u[k].y;
      }
      sph_tri::run(b, n, level);
      for (int k = 0; k < n; ++k) {
        const std::string at = "kernel " + std::to_string(level) + " seed " + std::to_string(seed) + " lane " +
                               std::to_string(k);
        const Config& t = cfg[k];
        const std::optional<SphericalSample> s = sample_spherical_triangle(t.p, t.a, t.b, t.c, u[k]);
        ASSERT_EQ(b.ok[k] != 0, s.has_value()) << at;
        if (!s) {
          ++failed;
          continue;
        }
        ++sampled;
        ASSERT_TRUE(same(s->w.x, b.wx[k]) && same(s->w.y, b.wy[k]) && same(s->w.z, b.wz[k])) << at;
        ASSERT_TRUE(same(s->pdf, b.pdf[k])) << at;
      }
    }
  // Both outcomes are reached at every level.
  EXPECT_GT(sampled, 500 * (simd_level() + 1));
  EXPECT_GT(failed, 500 * (simd_level() + 1));
}

}  // namespace
}  // namespace lumis
