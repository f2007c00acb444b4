// Warps of core/warp.cpp (all but GGX and spherical polygons): chi-square goodness of fit of every warp against its
// own density, normalisation of the densities, and inverse(sample(u)) == u.
//
// Statistics: 10 chi-square tests in this file, each with 400k samples (seeded 1..10), Sidak-corrected so that
// the family-wise false-failure rate of an exact warp is alpha = 0.01. The seeds are fixed, so a pass is repeatable.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/chi2.h"
#include "core/warp.h"

namespace lumis {
namespace {

constexpr int kNumChiSquareTests = 10;
constexpr uint64_t kSamples = 400'000;
constexpr double kPiD = 3.14159265358979323846;

ChiSquareResult directions(Vec3 (*warp)(Vec2), const std::function<double(Vec3)>& pdf, uint64_t seed) {
  DirectionalTest cfg;
  cfg.samples = kSamples;
  cfg.seed = seed;
  cfg.num_tests = kNumChiSquareTests;
  const ChiSquareResult r = chi_square_directions(
      [&](Pcg32& rng) -> std::optional<Vec3> {
        const float a = rng.next_float(), b = rng.next_float();
        return warp(Vec2(a, b));
      },
      pdf, cfg);
  std::printf("  %s\n", r.message.c_str());
  return r;
}

TEST(Warp, UniformThetaPhiChiSquare) {
  const auto r = directions(
      sample_uniform_theta_phi_hemisphere, [](Vec3 w) { return uniform_theta_phi_hemisphere_pdf(w); }, 1);
  EXPECT_TRUE(r.passed) << r.message;
}
TEST(Warp, UniformHemisphereChiSquare) {
  const auto r = directions(sample_uniform_hemisphere, [](Vec3 w) { return uniform_hemisphere_pdf(w); }, 2);
  EXPECT_TRUE(r.passed) << r.message;
}
TEST(Warp, CosineHemisphereChiSquare) {
  const auto r = directions(sample_cosine_hemisphere, [](Vec3 w) { return cosine_hemisphere_pdf(w); }, 3);
  EXPECT_TRUE(r.passed) << r.message;
}
TEST(Warp, UniformSphereChiSquare) {
  const auto r = directions(sample_uniform_sphere, [](Vec3) { return uniform_sphere_pdf(); }, 4);
  EXPECT_TRUE(r.passed) << r.message;
}

// Cap sizes: rim on a bin edge (0.9), inside a bin (0.37), and larger than a hemisphere (-0.55).
float g_cos_max = 0;
Vec3 cap_warp(Vec2 u) { return sample_spherical_cap(u, g_cos_max); }
TEST(Warp, SphericalCapChiSquare) {
  uint64_t seed = 5;
  for (float cos_max : {0.9f, 0.37f, -0.55f}) {
    g_cos_max = cos_max;
    const auto r = directions(cap_warp, [=](Vec3 w) { return spherical_cap_pdf(w, cos_max); }, seed++);
    EXPECT_TRUE(r.passed) << "cos_max " << cos_max << ": " << r.message;
  }
}

// Power check: the same test must reject cosine-weighted directions declared as uniform.
TEST(Warp, ChiSquareRejectsMismatchedPdf) {
  const auto r = directions(sample_cosine_hemisphere, [](Vec3 w) { return uniform_hemisphere_pdf(w); }, 8);
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(Warp, DirectionPdfsIntegrateToOne) {
  EXPECT_NEAR(integrate_over_sphere([](Vec3 w) { return uniform_theta_phi_hemisphere_pdf(w); }), 1.0, 1e-3);
  EXPECT_NEAR(integrate_over_sphere([](Vec3 w) { return uniform_hemisphere_pdf(w); }), 1.0, 1e-3);
  EXPECT_NEAR(integrate_over_sphere([](Vec3 w) { return cosine_hemisphere_pdf(w); }), 1.0, 1e-3);
  EXPECT_NEAR(integrate_over_sphere([](Vec3) { return uniform_sphere_pdf(); }), 1.0, 1e-3);
  for (float cos_max : {0.95f, 0.37f, -0.55f})
    EXPECT_NEAR(integrate_over_sphere([=](Vec3 w) { return spherical_cap_pdf(w, cos_max); }), 1.0, 2e-3)
        << cos_max;
}

// u on a grid strictly inside (0,1)^2 (u.x = 0 and 1 are the same azimuth, so the inverse may return either).
template <typename Sample, typename Invert>
void expect_round_trip(Sample sample, Invert invert, float tol, const char* name) {
  for (int i = 1; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const Vec2 u((i + 0.37f) / 64.5f, (j + 0.61f) / 64.5f);
      const Vec2 v = invert(sample(u));
      ASSERT_NEAR(v.x, u.x, tol) << name << " u = (" << u.x << ", " << u.y << ")";
      ASSERT_NEAR(v.y, u.y, tol) << name << " u = (" << u.x << ", " << u.y << ")";
    }
}

TEST(Warp, InversesUndoSamples) {
  expect_round_trip(sample_uniform_theta_phi_hemisphere, invert_uniform_theta_phi_hemisphere, 2e-6f, "theta_phi");
  expect_round_trip(sample_uniform_hemisphere, invert_uniform_hemisphere, 2e-6f, "hemisphere");
  expect_round_trip(static_cast<Vec3 (*)(Vec2)>(sample_cosine_hemisphere), invert_cosine_hemisphere, 2e-6f, "cosine");
  expect_round_trip(sample_uniform_sphere, invert_uniform_sphere, 2e-6f, "sphere");
  for (float cos_max : {0.9f, 0.37f, -0.55f, 0.999999f})
    expect_round_trip([=](Vec2 u) { return sample_spherical_cap(u, cos_max); },
                      [=](Vec3 w) { return invert_spherical_cap(w, cos_max); }, 2e-5f, "cap");
  expect_round_trip(sample_uniform_disk, invert_uniform_disk, 2e-6f, "disk");
  expect_round_trip(sample_uniform_triangle, invert_uniform_triangle, 2e-6f, "triangle");
}

TEST(Warp, SamplesAreUnitAndInsideTheirSupport) {
  Pcg32 rng(99, 1);
  for (int i = 0; i < 10000; ++i) {
    const Vec2 u(rng.next_float(), rng.next_float());
    for (Vec3 w : {sample_uniform_theta_phi_hemisphere(u), sample_uniform_hemisphere(u), sample_cosine_hemisphere(u),
                   sample_uniform_sphere(u), sample_spherical_cap(u, 0.3f)})
      ASSERT_NEAR(length(w), 1.0f, 1e-6f);
    EXPECT_GE(sample_spherical_cap(u, 0.3f).z, 0.3f);
    EXPECT_GE(sample_cosine_hemisphere(u).z, 0.0f);
    const Vec2 d = sample_uniform_disk(u);
    EXPECT_LE(d.x * d.x + d.y * d.y, 1.0f + 1e-6f);
    const Vec2 b = sample_uniform_triangle(u);
    EXPECT_GE(b.x, 0.0f);
    EXPECT_GE(b.y, 0.0f);
    EXPECT_LE(b.x + b.y, 1.0f + 1e-6f);
  }
  // The endpoints of [0,1)^2 map to valid points.
  EXPECT_TRUE(is_finite(sample_cosine_hemisphere(Vec2(0, 0))));
  EXPECT_TRUE(is_finite(sample_cosine_hemisphere(Vec2(kOneMinusEpsilon, kOneMinusEpsilon))));
  EXPECT_EQ(sample_uniform_disk(Vec2(0.5f, 0.5f)).x, 0.0f);
}

TEST(Warp, OneMinusCosFromSinIsStableForTinyCaps) {
  for (double s = 1e-6; s < 1.0; s *= 1.7) {
    const double ref = s * s / (1.0 + std::sqrt(1.0 - s * s));  // exact in double
    EXPECT_NEAR(one_minus_cos_from_sin(static_cast<float>(s)), ref, 1e-6 * ref) << s;
  }
  EXPECT_FLOAT_EQ(one_minus_cos_from_sin(1.0f), 1.0f);
  // A cap of angular radius 1e-2 rad (a small distant light): samples spread inside it rather than collapsing onto
  // the pole. (cos_max is a float, so caps much below ~1e-3 rad cannot be described by this signature at all.)
  const float cos_max = 1.0f - one_minus_cos_from_sin(1e-2f);
  const Vec3 w = sample_spherical_cap(Vec2(0.3f, 0.5f), cos_max);
  const float sin_theta = std::sqrt(w.x * w.x + w.y * w.y);
  EXPECT_NEAR(sin_theta, 1e-2f * std::sqrt(0.5f), 1e-2f * 0.01f);
  EXPECT_GE(w.z, cos_max);
}

// Planar warps by a 2D histogram with exact expected counts.
ChiSquareResult planar(const std::vector<double>& obs, const std::vector<double>& exp) {
  const ChiSquareResult r = chi_square_test(obs, exp, 0.01, kNumChiSquareTests);
  std::printf("  %s\n", r.message.c_str());
  return r;
}

TEST(Warp, UniformDiskChiSquare) {
  // Cells equal in area: 40 bins of r^2 times 80 bins of angle, each with probability 1/3200 under the uniform disk.
  const int nr = 40, np = 80;
  std::vector<double> obs(nr * np, 0.0), exp(nr * np, double(kSamples) / (nr * np));
  Pcg32 rng(9, 0x5eed);
  for (uint64_t i = 0; i < kSamples; ++i) {
    const Vec2 p = sample_uniform_disk(Vec2(rng.next_float(), rng.next_float()));
    const double r2 = double(p.x) * p.x + double(p.y) * p.y;
    double phi = std::atan2(double(p.y), double(p.x));
    if (phi < 0) phi += 2 * kPiD;
    const int ir = std::min(int(r2 * nr), nr - 1), ip = std::min(int(phi / (2 * kPiD) * np), np - 1);
    obs[ir * np + ip] += 1;
  }
  EXPECT_TRUE(planar(obs, exp).passed);
}

TEST(Warp, UniformTriangleChiSquare) {
  // Grid over (b0, b1) in [0,1)^2: cells below the diagonal have probability 2 / n^2, cells it halves 1 / n^2.
  const int n = 50;
  std::vector<double> obs(n * n, 0.0), exp(n * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      exp[i * n + j] = (i + j < n - 1 ? 2.0 : i + j == n - 1 ? 1.0 : 0.0) / (n * n) * double(kSamples);
  Pcg32 rng(10, 0x5eed);
  for (uint64_t s = 0; s < kSamples; ++s) {
    const Vec2 b = sample_uniform_triangle(Vec2(rng.next_float(), rng.next_float()));
    const int i = std::min(int(b.x * n), n - 1), j = std::min(int(b.y * n), n - 1);
    obs[i * n + j] += 1;
  }
  EXPECT_TRUE(planar(obs, exp).passed);
}

TEST(Warp, DiskPdf) {
  EXPECT_FLOAT_EQ(uniform_disk_pdf(Vec2(0.3f, -0.4f)), kInvPi);
  EXPECT_EQ(uniform_disk_pdf(Vec2(0.8f, 0.8f)), 0.0f);
  EXPECT_EQ(uniform_hemisphere_pdf(Vec3(0, 0, -1)), 0.0f);
  EXPECT_EQ(cosine_hemisphere_pdf(Vec3(1, 0, 0)), 0.0f);
  EXPECT_EQ(spherical_cap_pdf(Vec3(0, 0.6f, 0.8f), 0.9f), 0.0f);
}

}  // namespace
}  // namespace lumis
