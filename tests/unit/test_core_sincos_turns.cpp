// sincos_turns (core/math.h) against sin and cos in long double: within one float ulp of the true value at every
// angle tried, exact at the quarter turns; and sincos_turns_many (core/sincos_batch.h), every kernel copy the CPU
// runs, equal to it bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <bit>
#include <numbers>
#include <vector>

#include "core/math.h"
#include "core/simd.h"
#include "core/sincos_batch.h"
#include "core/rng.h"

namespace lumis {
namespace {

// One float ulp at the magnitude of v, with a floor for values near zero (there the bound is absolute: a unit
// vector's component of 1e-9 is zero for every use).
float ulp_at(long double v) {
  const float a = std::max(std::abs(static_cast<float>(v)), 1e-9f);
  return std::nextafter(a, INFINITY) - a;
}

void expect_close(float t) {
  float s, c;
  sincos_turns(t, s, c);
  const long double angle = 2 * std::numbers::pi_v<long double> * static_cast<long double>(t);
  const long double s_true = std::sin(angle), c_true = std::cos(angle);
  ASSERT_LE(std::abs(s - s_true), ulp_at(s_true)) << "sin, t = " << t;
  ASSERT_LE(std::abs(c - c_true), ulp_at(c_true)) << "cos, t = " << t;
}

TEST(SincosTurns, WithinOneUlpEverywhere) {
  Pcg32 rng(7, 1);
  for (int i = 0; i < 200000; ++i) expect_close(rng.next_float() - 0.5f);  // the cap's range [-0.5, 0.5)
  for (int i = 0; i < 20000; ++i) expect_close(8 * rng.next_float() - 4);  // several turns, both signs
  for (int i = -64; i <= 64; ++i) expect_close(static_cast<float>(i) / 64);  // near every octant boundary
  for (float t : {1e-8f, -1e-8f, 0.24999999f, 0.25000001f, 0.49999997f, -0.5f}) expect_close(t);
}

TEST(SincosTurns, QuarterTurnsAreExact) {
  const float expect[4][2] = {{0, 1}, {1, 0}, {0, -1}, {-1, 0}};  // sin, cos at 0, 1/4, 1/2, 3/4 turn
  for (int q = -8; q <= 8; ++q) {
    float s, c;
    sincos_turns(static_cast<float>(q) / 4, s, c);
    const int k = ((q % 4) + 4) % 4;
    EXPECT_EQ(s, expect[k][0]) << q << " quarter turns";
    EXPECT_EQ(c, expect[k][1]) << q << " quarter turns";
  }
}

// The BSDF azimuths of a path batch go through the vectorised copies; a lane's direction must be the one the
// scalar call gives (the path traced alone), so every copy must agree bit for bit, at every length (vector body
// and remainder) and for inputs in the samplers' [0, 1) and beyond.
TEST(SincosTurnsMany, EveryKernelEqualsTheScalarCall) {
  Pcg32 rng(11, 3);
  std::vector<float> t(1000);
  for (size_t i = 0; i < t.size(); ++i) t[i] = i < 900 ? rng.next_float() : 16 * rng.next_float() - 8;
  t[0] = 0, t[1] = kOneMinusEpsilon, t[2] = 0.25f, t[3] = 0.5f, t[4] = -0.75f, t[5] = 1e-30f;
  for (int level = 0; level <= simd_level(); ++level)
    for (const int n : {0, 1, 7, 16, 17, 63, 256, 1000}) {
      std::vector<float> s(n + 1, 42.0f), c(n + 1, 42.0f);
      sincos_turns_many(t.data(), n, s.data(), c.data(), level);
      for (int i = 0; i < n; ++i) {
        float s1, c1;
        sincos_turns(t[i], s1, c1);
        ASSERT_EQ(std::bit_cast<uint32_t>(s[i]), std::bit_cast<uint32_t>(s1)) << "level " << level << " t " << t[i];
        ASSERT_EQ(std::bit_cast<uint32_t>(c[i]), std::bit_cast<uint32_t>(c1)) << "level " << level << " t " << t[i];
      }
      EXPECT_EQ(s[n], 42.0f) << "wrote past n";  // nothing beyond the n asked for
      EXPECT_EQ(c[n], 42.0f) << "wrote past n";
    }
}

}  // namespace
}  // namespace lumis
