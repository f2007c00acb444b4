// Distribution1D / Distribution2D: chi-square of sampled cells and points against the tabulated density, pmf/pdf
// consistency, zero cells never sampled, all-zero tables uniform, inverses, and the [0,1) domain.
//
// Statistics: 3 chi-square tests of 200k samples each, fixed seeds, Sidak-corrected for a family-wise false-failure
// rate of 0.01 for a correct implementation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "core/chi2.h"
#include "core/distribution.h"

namespace lumis {
namespace {

constexpr int kNumChiSquareTests = 3;
constexpr int kSamples = 200'000;

// Zeros at both ends and inside, so that empty CDF intervals are exercised everywhere.
const std::vector<float> kWeights = {0, 1, 0, 3, 0, 0, 2, 0.5f, 7, 0};

ChiSquareResult report(const ChiSquareResult& r) {
  std::printf("  %s\n", r.message.c_str());
  return r;
}

TEST(Distribution1D, IntegralAndPmf) {
  const Distribution1D d(kWeights);
  const double sum = std::accumulate(kWeights.begin(), kWeights.end(), 0.0);
  EXPECT_EQ(d.size(), kWeights.size());
  EXPECT_FLOAT_EQ(d.integral(), static_cast<float>(sum / kWeights.size()));
  double total = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    // pmf() is the cell's width on the sampler's 2^-24 grid: f / sum to within two steps, 0 only for f == 0.
    EXPECT_NEAR(d.pmf(i), kWeights[i] / sum, 0x1p-23) << "cell " << i;
    EXPECT_EQ(d.pmf(i) > 0, kWeights[i] > 0) << "cell " << i;
    EXPECT_EQ(std::ldexp(d.pmf(i), 24), std::floor(std::ldexp(d.pmf(i), 24))) << "cell " << i << " is off the grid";
    total += d.pmf(i);
  }
  EXPECT_EQ(total, 1.0);
  EXPECT_EQ(d.pmf(d.size()), 0.0f);
}

// Every one of the sampler's 2^24 values of u (k 2^-24: core/rng.h, core/sampler.cpp), each drawn: the number that
// lands in a cell must be pmf() x 2^24 exactly, so that pmf() is the probability sampling realises and not only
// f / sum. The tables hold cells far below 2^-24 of the total (once never drawn, so their light was lost) and 10^5
// random weights (whose realised probabilities once strayed by several percent from f / sum). Deterministic.
TEST(Distribution1D, EveryGridValueOfUGivesExactlyThePmf) {
  std::vector<float> random(100'000);
  Pcg32 rng(5, 11);
  for (float& v : random) v = 0.5f + rng.next_float();
  const std::vector<std::vector<float>> tables = {
      {1, 1e-12f, 3, 0, 1e-9f, 2, 0, 1e-30f}, random, std::vector<float>(7, 0.0f)};
  for (const std::vector<float>& f : tables) {
    const Distribution1D d(f);
    std::vector<uint32_t> count(d.size(), 0);
    for (uint32_t k = 0; k < (1u << 24); ++k) ++count[d.sample_discrete(static_cast<float>(k) * 0x1p-24f)];
    int wrong = 0, lost = 0;
    for (size_t i = 0; i < d.size(); ++i) {
      wrong += static_cast<double>(count[i]) != std::ldexp(double(d.pmf(i)), 24);
      lost += f[i] > 0 && count[i] == 0;
    }
    EXPECT_EQ(wrong, 0) << "cells whose count is not pmf x 2^24, table of " << f.size();
    EXPECT_EQ(lost, 0) << "non-zero cells never drawn, table of " << f.size();
  }
}

TEST(Distribution1D, DiscreteChiSquareAndNoZeroCells) {
  const Distribution1D d(kWeights);
  std::vector<double> obs(d.size(), 0.0), exp(d.size(), 0.0);
  for (size_t i = 0; i < d.size(); ++i) exp[i] = d.pmf(i) * double(kSamples);
  Pcg32 rng(1, 7);
  for (int s = 0; s < kSamples; ++s) {
    float pmf = -1, ur = -1;
    const float u = rng.next_float();
    const size_t i = d.sample_discrete(u, &pmf, &ur);
    ASSERT_LT(i, d.size());
    ASSERT_GT(kWeights[i], 0.0f) << "sampled a zero-weight cell at u = " << u;
    ASSERT_EQ(pmf, d.pmf(i));
    ASSERT_GE(ur, 0.0f);
    ASSERT_LT(ur, 1.0f);
    obs[i] += 1;
  }
  const ChiSquareResult r = report(chi_square_test(obs, exp, 0.01, kNumChiSquareTests));
  EXPECT_TRUE(r.passed) << r.message;
  // Extreme u: the first and last non-zero cells, never a zero cell.
  EXPECT_EQ(d.sample_discrete(0.0f), 1u);
  EXPECT_EQ(d.sample_discrete(kOneMinusEpsilon), 8u);
}

TEST(Distribution1D, ContinuousChiSquarePdfAndInverse) {
  const Distribution1D d(kWeights);
  const int sub = 8, bins = static_cast<int>(d.size()) * sub;  // 8 histogram bins per cell
  std::vector<double> obs(bins, 0.0), exp(bins, 0.0);
  for (int b = 0; b < bins; ++b) exp[b] = d.pdf_continuous((b + 0.5f) / bins) / bins * double(kSamples);
  Pcg32 rng(2, 7);
  for (int s = 0; s < kSamples; ++s) {
    const float u = rng.next_float();
    float pdf = -1;
    size_t cell = 99;
    const float x = d.sample_continuous(u, &pdf, &cell);
    ASSERT_GE(x, 0.0f);
    ASSERT_LT(x, 1.0f);
    ASSERT_EQ(cell, std::min<size_t>(static_cast<size_t>(x * d.size()), d.size() - 1));
    ASSERT_GT(pdf, 0.0f);
    ASSERT_EQ(pdf, d.pdf_continuous(x));
    ASSERT_NEAR(d.invert(x), u, 2e-6f);
    obs[std::min(static_cast<int>(x * bins), bins - 1)] += 1;
  }
  const ChiSquareResult r = report(chi_square_test(obs, exp, 0.01, kNumChiSquareTests));
  EXPECT_TRUE(r.passed) << r.message;
  EXPECT_LT(d.sample_continuous(kOneMinusEpsilon, nullptr), 1.0f);
  EXPECT_EQ(d.pdf_continuous(1.0f), 0.0f);
  EXPECT_EQ(d.pdf_continuous(-0.1f), 0.0f);
}

TEST(Distribution1D, AllZeroAndDegenerateInputsAreUniform) {
  const std::vector<float> zeros(5, 0.0f), bad = {-1.0f, NAN, INFINITY, -INFINITY};
  for (const auto* f : {&zeros, &bad}) {
    const Distribution1D d(*f);
    EXPECT_EQ(d.integral(), 0.0f);
    float pdf = 0;
    for (float u : {0.0f, 0.3f, 0.77f, kOneMinusEpsilon}) {
      const float x = d.sample_continuous(u, &pdf);
      EXPECT_NEAR(x, u, 1e-6f);
      EXPECT_LT(x, 1.0f);
      EXPECT_NEAR(pdf, 1.0f, 1e-6f);  // the cells' widths are rounded to the 2^-24 grid
      EXPECT_EQ(pdf, d.pdf_continuous(x));
    }
    EXPECT_NEAR(d.pmf(2), 1.0f / f->size(), 1e-7f);
    EXPECT_EQ(d.sample_discrete(0.5f), f->size() / 2);
  }
  const Distribution1D empty(std::span<const float>{});
  EXPECT_EQ(empty.sample_discrete(0.4f), 0u);
  EXPECT_EQ(empty.pdf_continuous(0.4f), 1.0f);
}

TEST(Distribution1D, LargeTableBinarySearch) {
  // 2^20 cells with weight i: the cell found for u is the one whose interval of pmf()s holds it, sum_{j<i} pmf(j) <= u
  // < sum_{j<=i} pmf(j) (exact in double: the pmfs are multiples of 2^-24). The pmfs are f / sum, i (i - 1) / (n (n -
  // 1)) apart, to within a step of the grid, except below i = 2^16, where f / sum is under one step and each cell keeps
  // one step (the cells after it give them back).
  const size_t n = 1u << 20;
  std::vector<float> f(n);
  for (size_t i = 0; i < n; ++i) f[i] = static_cast<float>(i);
  const Distribution1D d(f);
  std::vector<double> below(n + 1, 0.0);
  int off = 0;
  for (size_t i = 0; i < n; ++i) {
    below[i + 1] = below[i] + d.pmf(i);
    const double p = 2.0 * double(i) / (double(n) * (n - 1.0));
    if (i >= (1u << 17)) off += std::abs(d.pmf(i) - p) > 0x1p-24;
    if (i > 0) off += d.pmf(i) < 0x1p-24;
  }
  EXPECT_EQ(off, 0) << "cells whose pmf is not f / sum to within one step, or below one step";
  EXPECT_EQ(below[n], 1.0);
  Pcg32 rng(3, 7);
  for (int s = 0; s < 10000; ++s) {
    const float u = rng.next_float();
    const size_t i = d.sample_discrete(u);
    ASSERT_GE(i, 1u);
    ASSERT_LE(below[i], u);
    ASSERT_LT(u, below[i + 1]);
  }
}

// The steps lent to cells narrower than one step come from the cells that carry the weight, so they are limited to
// 2^18 (1/64 of the total). One cell of 99 % beside 2^20 - 1 cells of 1e-8 each: lending each a step once cut the big
// cell to 0.9375; now it keeps 0.99 to within a step, the tiny cells get steps only where their running sum reaches
// them, and every count over all 2^24 values of u is still pmf x 2^24. Under the limit (2^17 tiny cells) each is
// drawable and the big cell gives up at most 2^17 steps. Deterministic.
TEST(Distribution1D, StepsLentToTinyCellsAreLimited) {
  const auto check_realised = [](const Distribution1D& d) {
    std::vector<uint32_t> count(d.size(), 0);
    for (uint32_t k = 0; k < (1u << 24); ++k) ++count[d.sample_discrete(static_cast<float>(k) * 0x1p-24f)];
    int wrong = 0;
    for (size_t i = 0; i < d.size(); ++i) wrong += static_cast<double>(count[i]) != std::ldexp(double(d.pmf(i)), 24);
    return wrong;
  };
  for (const size_t n : {size_t{1} << 20, size_t{1} << 17}) {
    std::vector<float> f(n, 1e-8f);
    f[0] = 0.99f / 0.01f * 1e-8f * static_cast<float>(n - 1);  // 99 % of the total
    const Distribution1D d(f);
    const double tiny = 1e-8f, share = double(f[0]) / (double(f[0]) + tiny * double(n - 1));
    size_t drawable = 0;
    for (size_t i = 1; i < n; ++i) drawable += d.pmf(i) > 0;
    if (n == (size_t{1} << 20)) {
      EXPECT_NEAR(d.pmf(0), share, 0x1p-23) << "the big cell lost its weight to the tiny ones";
      EXPECT_LT(drawable, n / 4) << "tiny cells were lent steps beyond the limit";
    } else {
      EXPECT_EQ(drawable, n - 1) << "a tiny cell cannot be drawn under the limit";
      EXPECT_GE(d.pmf(0), share - double(n) * 0x1p-24);
    }
    EXPECT_EQ(check_realised(d), 0) << "cells whose count is not pmf x 2^24, table of " << n;
  }
}

// For du near 1, (i + du) / n rounds to the next cell's edge in float; the point must stay in the cell whose density
// is returned. 4096 cells of random weight, u at and just below every cell's upper CDF edge, and 10^6 random u.
// Deterministic.
TEST(Distribution1D, ContinuousSampleStaysInTheCellItsPdfIsFor) {
  const size_t n = 4096;
  std::vector<float> f(n);
  Pcg32 rng(4, 9);
  for (float& v : f) v = 0.01f + rng.next_float();
  const Distribution1D d(f);
  int checked = 0, mismatched = 0;
  const auto check = [&](float u) {
    float pdf = -1;
    size_t cell = n;
    const float x = d.sample_continuous(u, &pdf, &cell);
    ++checked;
    mismatched += cell != std::min(static_cast<size_t>(x * static_cast<float>(n)), n - 1) || pdf != d.pdf_continuous(x);
  };
  for (size_t i = 0; i < n; ++i) {
    float u = d.invert(static_cast<float>(i + 1) / static_cast<float>(n));
    for (int k = 0; k < 8; ++k, u = std::nextafter(u, 0.0f)) check(u);
  }
  for (int s = 0; s < 1'000'000; ++s) check(rng.next_float());
  EXPECT_EQ(mismatched, 0) << "of " << checked;
}

// 6 x 4 table with a zero row and zero cells.
const std::vector<float> kTable = {1, 2, 0, 4, 0, 1,   //
                                   0, 0, 0, 0, 0, 0,   //
                                   3, 0, 0, 1, 5, 0.5f,  //
                                   0.2f, 0.2f, 8, 0, 0, 1};

TEST(Distribution2D, ChiSquarePdfAndInverse) {
  const int nu = 6, nv = 4, sub = 4, bu = nu * sub, bv = nv * sub;
  const Distribution2D d(kTable, nu, nv);
  std::vector<double> obs(bu * bv, 0.0), exp(bu * bv, 0.0);
  for (int j = 0; j < bv; ++j)
    for (int i = 0; i < bu; ++i)
      exp[j * bu + i] = d.pdf(Vec2((i + 0.5f) / bu, (j + 0.5f) / bv)) / (bu * bv) * double(kSamples);
  Pcg32 rng(4, 7);
  for (int s = 0; s < kSamples; ++s) {
    const Vec2 u(rng.next_float(), rng.next_float());
    float pdf = -1;
    const Vec2 p = d.sample_continuous(u, &pdf);
    ASSERT_TRUE(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1);
    ASSERT_GT(pdf, 0.0f);
    ASSERT_NEAR(pdf, d.pdf(p), 1e-5f * pdf);
    const Vec2 back = d.invert(p);
    ASSERT_NEAR(back.x, u.x, 4e-6f);
    ASSERT_NEAR(back.y, u.y, 4e-6f);
    obs[std::min(int(p.y * bv), bv - 1) * bu + std::min(int(p.x * bu), bu - 1)] += 1;
  }
  const ChiSquareResult r = report(chi_square_test(obs, exp, 0.01, kNumChiSquareTests));
  EXPECT_TRUE(r.passed) << r.message;
  // The pdf integrates to 1 (midpoint rule is exact for a piecewise-constant density on its own grid).
  double total = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) total += d.pdf(Vec2((i + 0.5f) / nu, (j + 0.5f) / nv)) / (nu * nv);
  EXPECT_NEAR(total, 1.0, 1e-5);
  EXPECT_EQ(d.pdf(Vec2(0.5f, 0.3f)), 0.0f);  // the zero row
}

TEST(Distribution2D, AllZeroIsUniformAndBadSizeThrows) {
  const std::vector<float> zeros(12, 0.0f);
  const Distribution2D d(zeros, 4, 3);
  float pdf = 0;
  const Vec2 p = d.sample_continuous(Vec2(0.25f, 0.6f), &pdf);
  EXPECT_NEAR(p.x, 0.25f, 1e-6f);
  EXPECT_NEAR(p.y, 0.6f, 1e-6f);
  EXPECT_NEAR(pdf, 1.0f, 1e-6f);
  EXPECT_EQ(pdf, d.pdf(p));
  EXPECT_NEAR(d.pdf(Vec2(0.9f, 0.1f)), 1.0f, 1e-6f);
  EXPECT_THROW(Distribution2D(zeros, 5, 3), std::invalid_argument);
  EXPECT_THROW(Distribution2D(zeros, 0, 12), std::invalid_argument);
}

}  // namespace
}  // namespace lumis
