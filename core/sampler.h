// Per-pixel sample generators. A sampler is a small value type: start(pixel, index) resets it so that the numbers
// it returns depend only on (pixel, sample index, seed, dimension), never on the thread or the tile order.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "core/math.h"
#include "core/rng.h"

namespace lumis {

enum class SamplerType { Independent, Stratified, Sobol };

/// Parse "independent" | "stratified" | "sobol".
std::optional<SamplerType> parse_sampler_type(std::string_view name);
const char* sampler_type_name(SamplerType type);

/// The seven dimensions one path vertex consumes, in the path loop's fixed order (integrators/path.h).
struct VertexDims {
  float choice;  ///< light / strategy choice (1D)
  Vec2 light;    ///< point on the light (2D)
  float lobe;    ///< BSDF lobe choice (1D)
  Vec2 dir;      ///< BSDF direction (2D)
  float rr;      ///< Russian roulette (1D)
};

class Sampler {
 public:
  /// spp is the number of samples each pixel will take (stratified uses it to size its strata).
  Sampler(SamplerType type, uint32_t spp, uint32_t seed);
  Sampler() : Sampler(SamplerType::Independent, 1, 0) {}

  /// Begin sample `index` of pixel (px, py). Resets the dimension counter.
  void start(uint32_t px, uint32_t py, uint32_t index);
  /// Next dimension, uniform in [0,1).
  float get1d();
  /// Next two dimensions, uniform in [0,1)^2 (stratified/Sobol jointly in 2D).
  Vec2 get2d();
  /// get1d, get2d, get1d, get2d, get1d: the same values as those five calls in that order (stratified: the five
  /// strata are computed side by side, so their hashes overlap instead of waiting on each other).
  VertexDims get_vertex();
  /// For every k < n: samplers[k].start(px[k], py[k], index), then out[k] = samplers[k].get2d() (the pixel
  /// jitter), the same numbers bit for bit; side by side as get_vertex_batch.
  static void start_batch(Sampler* samplers, int n, const int* px, const int* py, uint32_t index, Vec2* out,
                          int max_level = 2);
  /// For every i < m: out[lanes[i]] = samplers[lanes[i]].get_vertex(), the same numbers bit for bit. Stratified
  /// samplers of one spp at one dimension (a path batch's lanes at one bounce) are done side by side, with SIMD
  /// where the CPU has it (AVX2, AVX-512); anything else one by one. max_level caps the kernel (tests).
  static void get_vertex_batch(Sampler* samplers, const int* lanes, int m, VertexDims* out, int max_level = 2);
  /// The best kernel the batch calls can use on this CPU: 0 baseline x86-64 (or not x86), 1 AVX2, 2 AVX-512.
  static int batch_level();

  SamplerType type() const { return type_; }
  uint32_t spp() const { return spp_; }

 private:
  SamplerType type_;
  uint32_t spp_, seed_;
  uint32_t px_ = 0, py_ = 0, index_ = 0, dim_ = 0;
  uint64_t pixel_hash_ = 0;
  uint32_t strata_x_ = 1, strata_y_ = 1;  // stratified: spp factored into a near-square grid
  // Stratified constants: of spp (constructor) and of the sample index (start()).
  uint32_t mask_ = 0;
  int shift_ = 1;
  double inv_spp_ = 1, inv_strata_x_ = 1, inv_strata_y_ = 1;  // 1 / the number of strata, for in_stratum
  uint64_t div_strata_x_ = 0;  // k / strata_x_ == (k * div_strata_x_) >> 32 for every k < spp_; 0: divide
  uint32_t stratum_index_ = 0;
  uint64_t block_hash_ = 0;  // hash of (pixel, seed, index / spp): keys the permutations of this block of spp
  uint32_t block_ = 0;       // index / spp of the current sample
  bool has_pixel_ = false;   // pixel_hash_ and block_hash_ belong to (px_, py_) and block_
  Pcg32 rng_;

  uint32_t stratum(uint32_t d) const;  ///< the stratum of dimension d for this sample
  void start_hashes(uint32_t px, uint32_t py, uint32_t index);  ///< start() but for seeding rng_
  void batch_constants(void* batch) const;  ///< the spp-dependent constants into a batch (core/sampler_batch.cpp)
  Vec2 stratified2d(uint32_t k);       ///< point in 2D stratum k of the strata_x_ x strata_y_ grid, jittered
};

}  // namespace lumis
