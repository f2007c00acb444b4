// The stratified sampler's numbers on the 2^-24 grid: Distribution1D's CDF lies on that grid, and the pmf it reports
// is the probability sampling realises only for numbers uniform on it
// (Distribution1D.EveryGridValueOfUGivesExactlyThePmf). These tests check that the stratified numbers are: for every
// strata count, each grid value exactly as often as any other over a uniformly random stratum and jitter; the
// quotient exact beyond the double product's range; and the Sampler's own numbers, one lane and batch alike, on the
// grid. All are exact checks (no statistics, no false failures). Before, (stratum + jitter) / n in float drew
// alternate grid values of spp 4's upper strata 5/4 and 3/4 as often as they should, and put stratum 0's values
// between grid values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "core/sampler.h"
#include "core/sampler_internal.h"

namespace lumis {
namespace {

using sampler_detail::in_stratum;

constexpr uint32_t kGrid = 1u << 24;

// floor((stratum 2^24 + m) / n): the grid index in_stratum must return, by integer division.
uint32_t exact_index(uint32_t stratum, uint32_t m, uint32_t n) {
  return static_cast<uint32_t>(((uint64_t{stratum} << 24) + m) / n);
}

// The grid index of u, which must be a multiple of 2^-24 in [0, 1).
uint32_t grid_index(float u) {
  const float scaled = u * 0x1p24f;  // exact: a power-of-two scaling
  EXPECT_EQ(scaled, std::floor(scaled)) << u << " is not on the 2^-24 grid";
  EXPECT_GE(u, 0.0f);
  EXPECT_LT(u, 1.0f);
  return static_cast<uint32_t>(scaled);
}

// Every stratum and every one of the 2^24 jitters: each grid value comes out exactly n times, and inside its stratum
// (below it by less than a step where the stratum's edge falls between grid values).
TEST(StratifiedGrid, EveryGridValueComesOutExactlyNTimes) {
  for (uint32_t n : {1u, 3u, 4u}) {
    std::vector<uint8_t> count(kGrid, 0);
    const double inv = 1.0 / n;
    for (uint32_t stratum = 0; stratum < n; ++stratum) {
      const uint64_t lo = (uint64_t{stratum} << 24) / n, hi = ((uint64_t{stratum + 1} << 24) + n - 1) / n;
      for (uint32_t m = 0; m < kGrid; ++m) {
        const float u = in_stratum(stratum, (m << 8) | (m & 0xffu), n, inv);  // the low 8 bits are not used
        const uint32_t k = static_cast<uint32_t>(u * 0x1p24f);
        ASSERT_EQ(static_cast<float>(k), u * 0x1p24f) << "n " << n << " stratum " << stratum << " m " << m;
        ASSERT_GE(k, lo) << "n " << n << " stratum " << stratum << " m " << m;
        ASSERT_LT(k, hi) << "n " << n << " stratum " << stratum << " m " << m;
        ++count[k];
      }
    }
    for (uint32_t k = 0; k < kGrid; ++k) ASSERT_EQ(count[k], n) << "n " << n << " grid value " << k;
  }
}

// The double product is exact below 2^27 strata (its error under 2^-28, the half step keeps the quotient 0.5 / n
// from an integer); beyond, an integer division. Random strata and jitters, and the jitters where the quotient is
// closest to an integer (the numerator a multiple of n, and one either side), for strata counts up to spp's 2^30.
TEST(StratifiedGrid, QuotientIsExactForAnyStrataCount) {
  Pcg32 rng(11, 3);
  for (uint32_t n : {2u, 5u, 7u, 1000u, 65537u, 1000003u, (1u << 26) + 1, (1u << 27) - 1, 1u << 27, (1u << 27) + 1,
                     (1u << 29) + 11, (1u << 30) - 1, 1u << 30}) {
    const double inv = 1.0 / n;
    for (int trial = 0; trial < 20000; ++trial) {
      const uint32_t stratum = trial == 0 ? 0 : trial == 1 ? n - 1 : rng.next_u32() % n;
      const uint64_t base = uint64_t{stratum} << 24;
      const uint64_t next_multiple = (base + n - 1) / n * n;  // the first numerator >= base that n divides
      std::vector<uint32_t> jitters = {0, kGrid - 1, rng.next_u32() >> 8};
      for (const uint64_t j : {next_multiple - base - 1, next_multiple - base, next_multiple - base + 1})
        if (j < kGrid) jitters.push_back(static_cast<uint32_t>(j));  // (j = -1 wraps around to beyond the grid)
      for (const uint32_t m : jitters) {
        ASSERT_EQ(grid_index(in_stratum(stratum, m << 8, n, inv)), exact_index(stratum, m, n))
            << "n " << n << " stratum " << stratum << " m " << m;
      }
    }
  }
}

// The Sampler's own numbers, through every call and the batch path, lie on the grid: for spp of a power of two, of
// none, with a 2D grid of oblong strata, and a prime past the product's range (1D, and 2D's spp x 1 grid).
TEST(StratifiedGrid, SamplerNumbersLieOnTheGrid) {
  for (uint32_t spp : {3u, 4u, 6u, 64u, 1000u, (1u << 27) + 29}) {
    Sampler s(SamplerType::Stratified, spp, 7);
    std::vector<Sampler> lanes(8, s);
    for (uint32_t i : {0u, 1u, 2u, spp - 1, spp + 1}) {
      for (uint32_t px = 0; px < 8; ++px) {
        s.start(px, 2, i);
        const Vec2 a = s.get2d();
        grid_index(a.x), grid_index(a.y), grid_index(s.get1d());
        const VertexDims v = s.get_vertex();
        for (float u : {v.choice, v.light.x, v.light.y, v.lobe, v.dir.x, v.dir.y, v.rr}) grid_index(u);
      }
      const int px[8] = {0, 1, 2, 3, 4, 5, 6, 7}, py[8] = {2, 2, 2, 2, 2, 2, 2, 2}, all[8] = {0, 1, 2, 3, 4, 5, 6, 7};
      Vec2 jitter[8];
      VertexDims dims[8];
      Sampler::start_batch(lanes.data(), 8, px, py, i, jitter);
      Sampler::get_vertex_batch(lanes.data(), all, 8, dims);
      for (int k = 0; k < 8; ++k) {
        grid_index(jitter[k].x), grid_index(jitter[k].y);
        for (float u : {dims[k].choice, dims[k].light.x, dims[k].light.y, dims[k].lobe, dims[k].dir.x, dims[k].dir.y,
                        dims[k].rr})
          grid_index(u);
      }
    }
    ASSERT_FALSE(HasFailure()) << "spp " << spp;
  }
}

}  // namespace
}  // namespace lumis
