// sincos_turns (core/math.h) against sin and cos in long double: within one float ulp of the true value at every
// angle tried, exact at the quarter turns, and sin^2 + cos^2 = 1 to float precision.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/math.h"
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

}  // namespace
}  // namespace lumis
