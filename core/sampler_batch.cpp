// The stratified sampler for a path batch's lanes side by side: Sampler::start_batch (each pixel's sample start and
// its pixel jitter) and Sampler::get_vertex_batch (a vertex's seven dimensions). Laid out by column (one array per
// quantity, a chunk of lanes at a time), the strata hashes, the PCG32 steps and the jitters are plain loops over
// lanes that the compiler vectorises; the kernels are compiled three times (baseline x86-64, AVX2, AVX-512) and the
// best the CPU has is picked once. They use integer arithmetic and exactly rounded float and double adds, multiplies
// and conversions only (a multiply-add the compiler may fuse is exact either way: in_stratum_product), so
// every kernel returns what the one-lane calls return, bit for bit (SamplerBatch.* tests check each one the CPU can
// run).
#include <algorithm>

#include "core/sampler.h"
#include "core/sampler_internal.h"
#include "core/simd.h"

namespace lumis {
namespace {

struct StratifiedBatch {
  static constexpr int kChunk = 64;
  // Per lane, gathered from the samplers.
  uint64_t pixel_hash[kChunk], block_hash[kChunk], state[kChunk], inc[kChunk];
  uint32_t stratum_index[kChunk];
  // Shared by the lanes: one spp (so one permutation domain and strata grid), one dimension, one sample index.
  uint64_t mixed[5];    // mix64 of the strata's dimensions
  uint64_t mixed_index;  // start: mix64(sample index)
  uint32_t mask, spp, strata_x;
  int shift;
  uint64_t div_strata_x;
  uint32_t strata_y;
  double inv_spp, inv_strata_x, inv_strata_y;
  bool walks;  // spp is not a power of two (or is 1): permute()'s cycle walking may be needed
  // Intermediate values and results.
  uint32_t stratum[5][kChunk], bits[7][kChunk], row[kChunk];
  float value[7][kChunk];

  /// Sampler::start's generator seeding: seed(hash_combine(pixel hash, index), pixel hash).
  [[gnu::always_inline]] inline void reseed(int n) {
    for (int k = 0; k < n; ++k)
      Pcg32::seeded(sampler_detail::hash_combine_mixed(pixel_hash[k], mixed_index), pixel_hash[k], state[k], inc[k]);
  }
  /// Sampler::stratum for the first `count` entries of mixed.
  [[gnu::always_inline]] inline void strata(int n, int count) {
    using sampler_detail::hash_combine_mixed, sampler_detail::permute_round;
    for (int j = 0; j < count; ++j) {
      const uint64_t m = mixed[j];
      for (int k = 0; k < n; ++k)
        stratum[j][k] = permute_round(stratum_index[k], mask, shift, hash_combine_mixed(block_hash[k], m));
    }
    if (walks) [[unlikely]] {  // permute(): an image >= spp is mapped again; one stratum is always 0
      for (int j = 0; j < count; ++j)
        for (int k = 0; k < n; ++k) {
          if (spp <= 1) {
            stratum[j][k] = 0;
            continue;
          }
          const uint64_t key = hash_combine_mixed(block_hash[k], mixed[j]);
          while (stratum[j][k] >= spp) stratum[j][k] = permute_round(stratum[j][k], mask, shift, key);
        }
    }
  }
  /// `count` calls of Pcg32::next_u32 per lane.
  [[gnu::always_inline]] inline void draws(int n, int count) {
    for (int k = 0; k < n; ++k) {
      uint64_t s = state[k];
      for (int j = 0; j < count; ++j) bits[j][k] = Pcg32::step(s, inc[k]);
      state[k] = s;
    }
  }
  /// A 1D dimension (get1d) from stratum s and draw b.
  [[gnu::always_inline]] inline void value1d(int n, int s, int b, int out) {
    using sampler_detail::in_stratum, sampler_detail::in_stratum_product;
    if (sampler_detail::stratum_by_product(spp)) [[likely]]
      for (int k = 0; k < n; ++k) value[out][k] = in_stratum_product(stratum[s][k], bits[b][k], inv_spp);
    else
      for (int k = 0; k < n; ++k) value[out][k] = in_stratum(stratum[s][k], bits[b][k], spp, inv_spp);
  }
  /// A 2D dimension (stratified2d) from stratum s and draws b, b + 1.
  [[gnu::always_inline]] inline void value2d(int n, int s, int b, int out) {
    if (div_strata_x)
      for (int k = 0; k < n; ++k) row[k] = static_cast<uint32_t>((stratum[s][k] * div_strata_x) >> 32);
    else
      for (int k = 0; k < n; ++k) row[k] = stratum[s][k] / strata_x;
    using sampler_detail::in_stratum, sampler_detail::in_stratum_product;
    if (sampler_detail::stratum_by_product(strata_x)) [[likely]]  // strata_y <= sqrt(spp) < 2^16 always
      for (int k = 0; k < n; ++k) {
        value[out][k] = in_stratum_product(stratum[s][k] - row[k] * strata_x, bits[b][k], inv_strata_x);
        value[out + 1][k] = in_stratum_product(row[k], bits[b + 1][k], inv_strata_y);
      }
    else
      for (int k = 0; k < n; ++k) {
        value[out][k] = in_stratum(stratum[s][k] - row[k] * strata_x, bits[b][k], strata_x, inv_strata_x);
        value[out + 1][k] = in_stratum(row[k], bits[b + 1][k], strata_y, inv_strata_y);
      }
  }

  /// start + get2d: value[0], value[1].
  [[gnu::always_inline]] inline void run_start(int n) {
    reseed(n);
    strata(n, 1);
    draws(n, 2);
    value2d(n, 0, 0, 0);
  }
  /// get_vertex: 1D, 2D, 1D, 2D, 1D into value[0..6].
  [[gnu::always_inline]] inline void run_vertex(int n) {
    strata(n, 5);
    draws(n, 7);
    value1d(n, 0, 0, 0);
    value2d(n, 1, 1, 1);
    value1d(n, 2, 3, 3);
    value2d(n, 3, 4, 4);
    value1d(n, 4, 6, 6);
  }
};

using Kernel = void (*)(StratifiedBatch&, int, bool);

void run_baseline(StratifiedBatch& b, int n, bool start) { start ? b.run_start(n) : b.run_vertex(n); }
#if LUMIS_SIMD_DISPATCH
LUMIS_TARGET_AVX2 void run_avx2(StratifiedBatch& b, int n, bool start) { start ? b.run_start(n) : b.run_vertex(n); }
LUMIS_TARGET_AVX512 void run_avx512(StratifiedBatch& b, int n, bool start) {
  start ? b.run_start(n) : b.run_vertex(n);
}
Kernel kernel(int level) { return level >= 2 ? run_avx512 : level == 1 ? run_avx2 : run_baseline; }
#else
Kernel kernel(int) { return run_baseline; }
#endif

}  // namespace

int Sampler::batch_level() { return simd_level(); }

void Sampler::batch_constants(void* batch) const {
  StratifiedBatch& b = *static_cast<StratifiedBatch*>(batch);
  b.mask = mask_, b.spp = spp_, b.strata_x = strata_x_, b.strata_y = strata_y_, b.shift = shift_;
  b.div_strata_x = div_strata_x_;
  b.inv_spp = inv_spp_, b.inv_strata_x = inv_strata_x_, b.inv_strata_y = inv_strata_y_;
  b.walks = spp_ <= 1 || (spp_ & (spp_ - 1)) != 0;
}

void Sampler::start_batch(Sampler* samplers, int n, const int* px, const int* py, uint32_t index, Vec2* out,
                          int max_level) {
  if (n <= 0) return;
  const Sampler& first = samplers[0];
  bool together = first.type_ == SamplerType::Stratified;
  for (int k = 1; k < n && together; ++k)
    together = samplers[k].type_ == SamplerType::Stratified && samplers[k].spp_ == first.spp_;
  if (!together) {
    for (int k = 0; k < n; ++k) {
      samplers[k].start(static_cast<uint32_t>(px[k]), static_cast<uint32_t>(py[k]), index);
      out[k] = samplers[k].get2d();
    }
    return;
  }
  const Kernel run = kernel(std::min(max_level, batch_level()));
  StratifiedBatch b;
  first.batch_constants(&b);
  b.mixed[0] = sampler_detail::mixed_dim(0);
  b.mixed_index = mix64(index);
  for (int begin = 0; begin < n; begin += StratifiedBatch::kChunk) {
    const int m = std::min(StratifiedBatch::kChunk, n - begin);
    for (int k = 0; k < m; ++k) {
      Sampler& s = samplers[begin + k];
      s.start_hashes(static_cast<uint32_t>(px[begin + k]), static_cast<uint32_t>(py[begin + k]), index);
      b.pixel_hash[k] = s.pixel_hash_, b.block_hash[k] = s.block_hash_, b.stratum_index[k] = s.stratum_index_;
    }
    run(b, m, true);
    for (int k = 0; k < m; ++k) {
      Sampler& s = samplers[begin + k];
      s.rng_.state_ = b.state[k], s.rng_.inc_ = b.inc[k];
      s.dim_ = 2;
      out[begin + k] = {b.value[0][k], b.value[1][k]};
    }
  }
}

void Sampler::get_vertex_batch(Sampler* samplers, const int* lanes, int m, VertexDims* out, int max_level) {
  if (m <= 0) return;
  const Sampler& first = samplers[lanes[0]];
  bool together = first.type_ == SamplerType::Stratified;
  for (int i = 1; i < m && together; ++i) {
    const Sampler& s = samplers[lanes[i]];
    together = s.type_ == SamplerType::Stratified && s.spp_ == first.spp_ && s.dim_ == first.dim_;
  }
  if (!together) {
    for (int i = 0; i < m; ++i) out[lanes[i]] = samplers[lanes[i]].get_vertex();
    return;
  }
  const Kernel run = kernel(std::min(max_level, batch_level()));
  StratifiedBatch b;
  first.batch_constants(&b);
  const uint32_t d = first.dim_;
  for (int j = 0; j < 5; ++j) b.mixed[j] = sampler_detail::mixed_dim(d + sampler_detail::kVertexStrata[j]);
  for (int begin = 0; begin < m; begin += StratifiedBatch::kChunk) {
    const int n = std::min(StratifiedBatch::kChunk, m - begin);
    for (int k = 0; k < n; ++k) {
      const Sampler& s = samplers[lanes[begin + k]];
      b.block_hash[k] = s.block_hash_, b.stratum_index[k] = s.stratum_index_;
      b.state[k] = s.rng_.state_, b.inc[k] = s.rng_.inc_;
    }
    run(b, n, false);
    for (int k = 0; k < n; ++k) {
      Sampler& s = samplers[lanes[begin + k]];
      s.rng_.state_ = b.state[k];
      s.dim_ = d + 7;
      out[lanes[begin + k]] = {b.value[0][k], {b.value[1][k], b.value[2][k]}, b.value[3][k],
                               {b.value[4][k], b.value[5][k]}, b.value[6][k]};
    }
  }
}

}  // namespace lumis
