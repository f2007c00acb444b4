// Samplers: range, determinism, stratification (jittered strata; Sobol (0,2)-nets in elementary intervals), a
// uniformity chi-square, and lower integration error than independent sampling on smooth integrands.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "core/chi2.h"
#include "core/sampler.h"

namespace lumis {
namespace {

constexpr SamplerType kTypes[] = {SamplerType::Independent, SamplerType::Stratified, SamplerType::Sobol};

TEST(Sampler, ParseAndNames) {
  for (SamplerType t : kTypes) EXPECT_EQ(parse_sampler_type(sampler_type_name(t)), t);
  EXPECT_FALSE(parse_sampler_type("halton").has_value());
  EXPECT_FALSE(parse_sampler_type("").has_value());
}

TEST(Sampler, ValuesInUnitIntervalAndDeterministic) {
  for (SamplerType t : kTypes) {
    Sampler a(t, 16, 7), b(t, 16, 7);
    for (uint32_t px : {0u, 3u, 1000u})
      for (uint32_t i = 0; i < 40; ++i) {  // past spp, too
        a.start(px, 5, i);
        std::vector<float> va;
        for (int d = 0; d < 6; ++d) {
          const Vec2 v = a.get2d();
          const float w = a.get1d();
          va.insert(va.end(), {v.x, v.y, w});
        }
        for (float v : va) {
          ASSERT_GE(v, 0.0f) << sampler_type_name(t);
          ASSERT_LT(v, 1.0f) << sampler_type_name(t);
        }
        // Another sampler, started out of order, gives the same numbers: no state survives start().
        b.start(px + 1, 2, i + 3);
        b.get2d();
        b.start(px, 5, i);
        for (int d = 0; d < 6; ++d) {
          const Vec2 v = b.get2d();
          const float w = b.get1d();
          ASSERT_EQ(v.x, va[3 * d]);
          ASSERT_EQ(v.y, va[3 * d + 1]);
          ASSERT_EQ(w, va[3 * d + 2]);
        }
      }
    // A different seed or pixel gives different numbers.
    a.start(1, 1, 0);
    const Vec2 x = a.get2d();
    Sampler c(t, 16, 8);
    c.start(1, 1, 0);
    EXPECT_NE(c.get2d().x, x.x);
    a.start(2, 1, 0);
    EXPECT_NE(a.get2d().x, x.x);
  }
}

// get_vertex() is the five calls of one path vertex in one: the same numbers bit for bit, at every vertex of a
// path, for every type and for spp whose grid is square, oblong, prime, and too large for the division shortcut.
TEST(Sampler, VertexDimsEqualTheFiveSeparateCalls) {
  for (SamplerType t : kTypes)
    for (uint32_t spp : {1u, 4u, 6u, 7u, 16u, 48u, 1u << 17}) {
      Sampler a(t, spp, 3), b(t, spp, 3);
      for (uint32_t i : {0u, 1u, spp - 1, spp, 3 * spp + 2}) {
        a.start(9, 4, i);
        b.start(9, 4, i);
        for (int vertex = 0; vertex < 4; ++vertex) {
          const float lead = a.get1d();  // camera dimensions before the first vertex shift the dimension index
          ASSERT_EQ(lead, b.get1d());
          const VertexDims v = a.get_vertex();
          const float choice = b.get1d();
          const Vec2 light = b.get2d();
          const float lobe = b.get1d();
          const Vec2 dir = b.get2d();
          const float rr = b.get1d();
          const auto where = [&] {
            return std::string(sampler_type_name(t)) + " spp " + std::to_string(spp) + " index " +
                   std::to_string(i) + " vertex " + std::to_string(vertex);
          };
          ASSERT_EQ(v.choice, choice) << where();
          ASSERT_EQ(v.light.x, light.x) << where();
          ASSERT_EQ(v.light.y, light.y) << where();
          ASSERT_EQ(v.lobe, lobe) << where();
          ASSERT_EQ(v.dir.x, dir.x) << where();
          ASSERT_EQ(v.dir.y, dir.y) << where();
          ASSERT_EQ(v.rr, rr) << where();
        }
      }
    }
}

TEST(Sampler, ExtremeValuesStayBelowOne) {
  // Many samples of every type: never 1.0 (a warp given u = 1 may leave its domain).
  for (SamplerType t : kTypes) {
    Sampler s(t, 1024, 1);
    float hi = 0;
    for (uint32_t i = 0; i < 4096; ++i) {
      s.start(0, 0, i);
      for (int d = 0; d < 4; ++d) {
        const Vec2 v = s.get2d();
        hi = std::max({hi, v.x, v.y, s.get1d()});
      }
    }
    EXPECT_LT(hi, 1.0f) << sampler_type_name(t);
    EXPECT_GT(hi, 0.999f) << sampler_type_name(t);
  }
}

TEST(Sampler, StratifiedOneSamplePerStratum) {
  for (uint32_t spp : {1u, 7u, 12u, 16u, 64u}) {
    Sampler s(SamplerType::Stratified, spp, 3);
    uint32_t sx = 1;  // the near-square grid: largest divisor <= sqrt(spp)
    for (uint32_t y = 1; y * y <= spp; ++y)
      if (spp % y == 0) sx = spp / y;
    const uint32_t sy = spp / sx;
    for (uint32_t block = 0; block < 2; ++block)  // the second block of spp samples is stratified again
      for (uint32_t px = 0; px < 4; ++px) {
        // Dimensions: 1D at 0, 2D at 1-2, 1D at 3, 2D at 4-5.
        std::vector<int> c0(spp, 0), c3(spp, 0), c12(spp, 0), c45(spp, 0);
        for (uint32_t i = block * spp; i < (block + 1) * spp; ++i) {
          s.start(px, 9, i);
          c0[static_cast<int>(s.get1d() * spp)]++;
          const Vec2 a = s.get2d();
          c12[static_cast<int>(a.y * sy) * sx + static_cast<int>(a.x * sx)]++;
          c3[static_cast<int>(s.get1d() * spp)]++;
          const Vec2 b = s.get2d();
          c45[static_cast<int>(b.y * sy) * sx + static_cast<int>(b.x * sx)]++;
        }
        for (uint32_t k = 0; k < spp; ++k) {
          ASSERT_EQ(c0[k], 1) << "spp " << spp << " stratum " << k;
          ASSERT_EQ(c3[k], 1) << "spp " << spp << " stratum " << k;
          ASSERT_EQ(c12[k], 1) << "spp " << spp << " cell " << k;
          ASSERT_EQ(c45[k], 1) << "spp " << spp << " cell " << k;
        }
      }
  }
}

TEST(Sampler, StratifiedDimensionsAreDecorrelated) {
  // Without per-dimension permutations sample i would sit in stratum i in every dimension (correlation 1).
  const uint32_t spp = 64;
  Sampler s(SamplerType::Stratified, spp, 5);
  double sxy = 0, n = 0;
  for (uint32_t px = 0; px < 64; ++px)
    for (uint32_t i = 0; i < spp; ++i) {
      s.start(px, 0, i);
      const double a = s.get1d() - 0.5, b = s.get1d() - 0.5;
      sxy += a * b;
      n += 1;
    }
  // Correlation coefficient (variance of U(0,1) is 1/12). Over 4096 pairs, |r| of independent pairs has standard
  // deviation 1/64; 0.08 is five of them.
  EXPECT_LT(std::abs(sxy / n * 12.0), 0.08);
}

// Every elementary interval of area 2^-k (2^a x 2^b cells, a + b = k) holds exactly one of the first 2^k points.
TEST(Sampler, SobolPairsAreZeroTwoNets) {
  Sampler s(SamplerType::Sobol, 256, 11);
  for (uint32_t px : {0u, 17u, 4242u})
    for (int pair = 0; pair < 4; ++pair)
      for (int k = 1; k <= 8; ++k) {
        const uint32_t n = 1u << k;
        std::vector<Vec2> pts;
        for (uint32_t i = 0; i < n; ++i) {
          s.start(px, 3, i);
          for (int p = 0; p < pair; ++p) s.get2d();
          pts.push_back(s.get2d());
        }
        for (int a = 0; a <= k; ++a) {
          const int b = k - a;
          std::vector<int> count(n, 0);
          for (Vec2 p : pts)
            count[(static_cast<uint32_t>(p.y * (1u << b)) << a) + static_cast<uint32_t>(p.x * (1u << a))]++;
          for (uint32_t c = 0; c < n; ++c)
            ASSERT_EQ(count[c], 1) << "pixel " << px << " pair " << pair << " k " << k << " a " << a;
        }
      }
  // 1D dimensions (van der Corput, scrambled): the first 2^k values hit each interval of length 2^-k once.
  for (uint32_t px : {0u, 99u}) {
    std::vector<int> count(64, 0);
    for (uint32_t i = 0; i < 64; ++i) {
      s.start(px, 3, i);
      s.get1d();
      count[static_cast<int>(s.get1d() * 64)]++;
    }
    for (int c : count) ASSERT_EQ(c, 1);
  }
}

TEST(Sampler, SobolPixelsAndPairsDiffer) {
  // Scrambling is per pixel and per dimension pair: the same index must not repeat the same point.
  Sampler s(SamplerType::Sobol, 16, 1);
  std::set<float> seen;
  for (uint32_t px = 0; px < 8; ++px) {
    s.start(px, 0, 0);
    for (int d = 0; d < 4; ++d) seen.insert(s.get2d().x);
  }
  EXPECT_EQ(seen.size(), 32u);
}

// Uniformity across pixels: 64 pixels x 64 samples of dimensions (2, 3) of each sampler in a 16 x 16 histogram.
// 3 chi-square tests at a Sidak-corrected family-wise alpha of 0.01, fixed seed.
TEST(Sampler, UniformChiSquare) {
  for (SamplerType t : kTypes) {
    Sampler s(t, 64, 2);
    std::vector<double> obs(256, 0.0), exp(256, 64.0 * 64.0 * 64.0 / 256.0);
    for (uint32_t px = 0; px < 4096; ++px)
      for (uint32_t i = 0; i < 64; ++i) {
        s.start(px % 64, px / 64, i);
        s.get2d();
        const Vec2 v = s.get2d();
        obs[static_cast<int>(v.y * 16) * 16 + static_cast<int>(v.x * 16)] += 1;
      }
    const ChiSquareResult r = chi_square_test(obs, exp, 0.01, 3);
    std::printf("  %s: %s\n", sampler_type_name(t), r.message.c_str());
    EXPECT_TRUE(r.passed) << sampler_type_name(t) << ": " << r.message;
  }
}

// Mean squared error over pixels of the 64-sample estimate of an integral over [0,1)^2.
double mse(SamplerType t, const std::function<double(Vec2)>& f, double exact, int pair) {
  const uint32_t spp = 64, pixels = 1024;
  Sampler s(t, spp, 12345);
  double err2 = 0;
  for (uint32_t p = 0; p < pixels; ++p) {
    double sum = 0;
    for (uint32_t i = 0; i < spp; ++i) {
      s.start(p % 32, p / 32, i);
      for (int k = 0; k < pair; ++k) s.get2d();
      sum += f(s.get2d());
    }
    err2 += (sum / spp - exact) * (sum / spp - exact);
  }
  return err2 / pixels;
}

TEST(Sampler, StratifiedAndSobolBeatIndependentOnSmoothIntegrands) {
  // Gaussian bump (sigma 0.15, centre (0.5, 0.4)) and cos(1.3 x) cos(2.1 y), both with closed-form integrals.
  const double sg = 0.15, mx = 0.5, my = 0.4;
  auto gauss_1d = [&](double m) {
    const double k = sg * std::sqrt(2.0);
    return sg * std::sqrt(3.14159265358979323846 / 2) * (std::erf((1 - m) / k) + std::erf(m / k));
  };
  const double bump_exact = gauss_1d(mx) * gauss_1d(my);
  auto bump = [&](Vec2 u) { return std::exp(-((u.x - mx) * (u.x - mx) + (u.y - my) * (u.y - my)) / (2 * sg * sg)); };
  const double cos_exact = std::sin(1.3) / 1.3 * std::sin(2.1) / 2.1;
  auto cosines = [](Vec2 u) { return std::cos(1.3 * u.x) * std::cos(2.1 * u.y); };
  // 1024 pixels x 64 samples, seed 12345. Measured MSE ratios independent / stratified: 11.7-14.0 (bump) and 59
  // (cosines); independent / sobol: 43-50 (bump) and ~1100 (cosines), on dimensions 0-1 and 4-5 alike. The required
  // factor 2 is thus far below what is measured, and an unstratified sampler (ratio ~1, noise +-10%) cannot reach it.
  for (int pair : {0, 2}) {
    using Case = std::tuple<const char*, std::function<double(Vec2)>, double>;
    for (const auto& [name, f, exact] : {Case{"bump", bump, bump_exact}, Case{"cosines", cosines, cos_exact}}) {
      const double e_ind = mse(SamplerType::Independent, f, exact, pair);
      const double e_str = mse(SamplerType::Stratified, f, exact, pair);
      const double e_sob = mse(SamplerType::Sobol, f, exact, pair);
      std::printf("  %s, dims %d-%d: MSE independent %.3g, stratified %.3g (ratio %.1f), sobol %.3g (ratio %.1f)\n",
                  name, 2 * pair, 2 * pair + 1, e_ind, e_str, e_ind / e_str, e_sob, e_ind / e_sob);
      EXPECT_GT(e_ind / e_str, 2.0) << name;
      EXPECT_GT(e_ind / e_sob, 2.0) << name;
    }
  }
}

}  // namespace
}  // namespace lumis
