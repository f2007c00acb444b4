// Sampler::start_batch and get_vertex_batch against the one-lane calls, bit for bit, with every kernel this CPU
// can run (baseline, AVX2, AVX-512): spp that are powers of two and not (cycle walking), 1 (a single stratum) and
// above 2^16 (strata rows by division) and 2^27 (strata by integer division), sample indices past spp (a new block), more lanes than a kernel chunk,
// lanes taken out of order, pixels that change between samples, and the other sampler types (one lane at a time).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/sampler.h"

namespace lumis {
namespace {

constexpr SamplerType kTypes[] = {SamplerType::Independent, SamplerType::Stratified, SamplerType::Sobol};
// 2^27 + 29 is a prime: its strata (1D, and the 2D grid of spp x 1) are past in_stratum's double product.
constexpr uint32_t kSpps[] = {1u, 2u, 6u, 7u, 16u, 48u, 64u, 1u << 17, (1u << 27) + 29};
constexpr int kLanes = 150;  // more than one 64-lane chunk

std::string where(SamplerType t, uint32_t spp, int level, uint32_t index, int k) {
  return std::string(sampler_type_name(t)) + " spp " + std::to_string(spp) + " kernel " + std::to_string(level) +
         " index " + std::to_string(index) + " lane " + std::to_string(k);
}

void expect_same(const VertexDims& a, const VertexDims& b, const std::string& at) {
  ASSERT_EQ(a.choice, b.choice) << at;
  ASSERT_EQ(a.light.x, b.light.x) << at;
  ASSERT_EQ(a.light.y, b.light.y) << at;
  ASSERT_EQ(a.lobe, b.lobe) << at;
  ASSERT_EQ(a.dir.x, b.dir.x) << at;
  ASSERT_EQ(a.dir.y, b.dir.y) << at;
  ASSERT_EQ(a.rr, b.rr) << at;
}

TEST(SamplerBatch, KernelLevelIsKnown) {
  EXPECT_GE(Sampler::batch_level(), 0);
  EXPECT_LE(Sampler::batch_level(), 2);
}

TEST(SamplerBatch, StartAndVerticesEqualTheOneLaneCalls) {
  for (SamplerType t : kTypes)
    for (uint32_t spp : kSpps)
      for (int level = 0; level <= Sampler::batch_level(); ++level) {
        std::vector<Sampler> batch(kLanes, Sampler(t, spp, 5)), alone(kLanes, Sampler(t, spp, 5));
        std::vector<int> px(kLanes), py(kLanes);
        for (uint32_t index : {0u, 1u, spp - 1, spp, 3 * spp + 2}) {
          for (int k = 0; k < kLanes; ++k) {  // half the pixels move between samples: their hashes are renewed
            px[k] = k % 17 + (k % 2 ? static_cast<int>(index) : 0);
            py[k] = k / 17;
          }
          std::vector<Vec2> jitter(kLanes);
          Sampler::start_batch(batch.data(), kLanes, px.data(), py.data(), index, jitter.data(), level);
          for (int k = 0; k < kLanes; ++k) {
            alone[k].start(static_cast<uint32_t>(px[k]), static_cast<uint32_t>(py[k]), index);
            const Vec2 j = alone[k].get2d();
            ASSERT_EQ(jitter[k].x, j.x) << where(t, spp, level, index, k);
            ASSERT_EQ(jitter[k].y, j.y) << where(t, spp, level, index, k);
          }
          // Three vertices; at each, every third lane has ended its path, and the lanes are listed backwards.
          for (int vertex = 0; vertex < 3; ++vertex) {
            std::vector<int> lanes;
            for (int k = kLanes - 1; k >= 0; --k)
              if ((k + vertex) % 3 != 0) lanes.push_back(k);
            std::vector<VertexDims> dims(kLanes);
            Sampler::get_vertex_batch(batch.data(), lanes.data(), static_cast<int>(lanes.size()), dims.data(), level);
            for (int k : lanes) expect_same(dims[k], alone[k].get_vertex(), where(t, spp, level, index, k));
            for (int k = 0; k < kLanes; ++k)
              if ((k + vertex) % 3 == 0) {  // the ended lanes restart: keep the one-lane samplers in step
                batch[k].start(static_cast<uint32_t>(px[k]), static_cast<uint32_t>(py[k]), index + 1);
                alone[k].start(static_cast<uint32_t>(px[k]), static_cast<uint32_t>(py[k]), index + 1);
              }
          }
          // The generators were left where the one-lane calls leave them.
          for (int k = 0; k < kLanes; ++k)
            ASSERT_EQ(batch[k].get1d(), alone[k].get1d()) << where(t, spp, level, index, k);
        }
      }
}

TEST(SamplerBatch, LanesAtDifferentDimensionsGoOneByOne) {
  std::vector<Sampler> batch(4, Sampler(SamplerType::Stratified, 16, 1)), alone = batch;
  for (int k = 0; k < 4; ++k) {
    batch[k].start(static_cast<uint32_t>(k), 0, 3);
    alone[k].start(static_cast<uint32_t>(k), 0, 3);
    if (k % 2) {
      batch[k].get1d();
      alone[k].get1d();
    }
  }
  const int lanes[] = {0, 1, 2, 3};
  VertexDims dims[4];
  Sampler::get_vertex_batch(batch.data(), lanes, 4, dims);
  for (int k = 0; k < 4; ++k) expect_same(dims[k], alone[k].get_vertex(), "lane " + std::to_string(k));
}

}  // namespace
}  // namespace lumis
