// Three per-pixel samplers behind one value type. Every number is a function of (pixel, sample index, seed,
// dimension) alone: each call hashes those into its own seeds, so tiles and threads cannot change an image.
//
// independent: PCG32 seeded from hash(pixel, index, seed); dimension d is the d-th draw.
// stratified:  the lecture's "stratified random numbers instead of a PRNG": jittered strata (spp strata for a 1D
//              dimension, a near-square grid for a 2D one); which stratum sample `index` gets is a pseudo-random
//              permutation keyed by (pixel, dimension, seed, block of spp samples), so dimensions are not
//              correlated with each other. The jittered point is rounded down to the 2^-24 grid, each grid value
//              equally likely (sampler_detail::in_stratum).
// sobol:       the 2D Sobol (0,2)-sequence per pair of dimensions (Burley 2020, "Practical Hash-based Owen
//              Scrambling"): the index is shuffled by a nested scramble and both coordinates are Owen-scrambled,
//              all with seeds keyed by (pixel, dimension, seed), so every pair is an independent randomised net.
#include "core/sampler.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "core/sampler_internal.h"

namespace lumis {

using sampler_detail::hash_combine_mixed;
using sampler_detail::in_stratum;
using sampler_detail::mixed_dim;
using sampler_detail::permute_round;

namespace {

uint32_t reverse_bits(uint32_t x) {
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
  return x;
}

// Direction numbers of the second Sobol dimension (primitive polynomial x + 1, m_1 = 1): the recurrence
// v_k = v_{k-1} ^ (v_{k-1} >> 1) from v_1 = 1/2. The first dimension is the van der Corput sequence, reverse_bits.
constexpr std::array<uint32_t, 32> make_sobol_dim1() {
  std::array<uint32_t, 32> v{};
  v[0] = 1u << 31;
  for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
  return v;
}
constexpr std::array<uint32_t, 32> kSobolDim1 = make_sobol_dim1();

uint32_t sobol_dim1(uint32_t index) {
  uint32_t x = 0;
  for (int k = 0; index; index >>= 1, ++k)
    if (index & 1u) x ^= kSobolDim1[k];
  return x;
}

// Each step replaces bit j by bit j XOR (a function of bits below j): additions, odd multiplications and
// x ^= x * even. Applied to bit-reversed values this is a nested uniform (Owen) scramble: digit j of the result is
// flipped by a pseudo-random function of the digits before it, which keeps every (0,m,2)-net a net.
uint32_t scramble_low_to_high(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c8e9cf6u;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x2b9a4f1cu;
  x += seed ^ 0x9e3779b9u;
  x ^= x * 0xd1b54a32u;
  x *= (seed << 7) | 1u;
  return x;
}
uint32_t owen_scramble(uint32_t x, uint32_t seed) { return reverse_bits(scramble_low_to_high(reverse_bits(x), seed)); }

uint32_t seed32(uint64_t h) { return static_cast<uint32_t>(h ^ (h >> 32)); }

// 24 significant bits: the largest result is 1 - 2^-24 < 1.
float to_unit_float(uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

// Pseudo-random permutation of [0, n) by a bijection on the next power of two and cycle walking (an image >= n is
// mapped again; it returns below n in fewer than two steps on average, and always, since the map is a permutation).
// mask (the next power of two minus one) and shift depend on n only: the caller computes them once (permute_mask).
uint32_t permute(uint32_t i, uint32_t n, uint32_t mask, int shift, uint64_t key) {
  if (n <= 1) return 0;
  do i = permute_round(i, mask, shift, key);
  while (i >= n);
  return i;
}

uint32_t permute_mask(uint32_t n) {
  uint32_t mask = n - 1;
  mask |= mask >> 1, mask |= mask >> 2, mask |= mask >> 4, mask |= mask >> 8, mask |= mask >> 16;
  return mask;
}

// mix64(d) for the first dimensions (a path of depth 8 uses 66): hash_combine(pixel, d) without one of its mixes.
constexpr int kMixedDims = 128;
struct MixedDims {
  uint64_t v[kMixedDims];
  MixedDims() {
    for (int d = 0; d < kMixedDims; ++d) v[d] = mix64(static_cast<uint64_t>(d));
  }
};
const MixedDims kMixed;

// The most nearly square factorisation spp = sx * sy with sx >= sy.
void near_square(uint32_t spp, uint32_t* sx, uint32_t* sy) {
  uint32_t y = static_cast<uint32_t>(std::sqrt(static_cast<double>(spp)));
  while (y > 1 && spp % y != 0) --y;
  *sy = std::max(y, 1u);
  *sx = spp / *sy;
}

}  // namespace

uint64_t sampler_detail::mixed_dim(uint32_t d) { return d < kMixedDims ? kMixed.v[d] : mix64(d); }

std::optional<SamplerType> parse_sampler_type(std::string_view name) {
  if (name == "independent") return SamplerType::Independent;
  if (name == "stratified") return SamplerType::Stratified;
  if (name == "sobol") return SamplerType::Sobol;
  return std::nullopt;
}

const char* sampler_type_name(SamplerType type) {
  switch (type) {
    case SamplerType::Independent: return "independent";
    case SamplerType::Stratified: return "stratified";
    case SamplerType::Sobol: return "sobol";
  }
  return "unknown";
}

Sampler::Sampler(SamplerType type, uint32_t spp, uint32_t seed) : type_(type), spp_(std::max(spp, 1u)), seed_(seed) {
  near_square(spp_, &strata_x_, &strata_y_);
  mask_ = permute_mask(spp_);
  shift_ = std::max(1, static_cast<int>(std::bit_width(mask_)) / 2);
  inv_spp_ = 1.0 / spp_;
  inv_strata_x_ = 1.0 / strata_x_;
  inv_strata_y_ = 1.0 / strata_y_;
  // m = floor(2^32 / sx) + 1 exceeds 2^32 / sx by e <= sx, so (k m) >> 32 = floor(k / sx + k e / (sx 2^32)) is exact
  // while k e < 2^32, which k < spp <= 2^16 and sx <= spp guarantee.
  if (spp_ <= (1u << 16)) div_strata_x_ = (uint64_t{1} << 32) / strata_x_ + 1;
}

void Sampler::start(uint32_t px, uint32_t py, uint32_t index) {
  start_hashes(px, py, index);
  rng_.seed(hash_combine(pixel_hash_, index), pixel_hash_);
}

void Sampler::start_hashes(uint32_t px, uint32_t py, uint32_t index) {
  // A renderer starts one pixel's samples in a row: its hashes are kept while the pixel (and block) stays the same.
  const bool same_pixel = has_pixel_ && px == px_ && py == py_;
  if (!same_pixel) pixel_hash_ = hash_combine(hash_combine(px, py), 0x51ed0000ULL + seed_);
  px_ = px, py_ = py, index_ = index, dim_ = 0;
  has_pixel_ = true;
  // Past spp, each further block of spp samples is a fresh stratified set (its own permutation).
  const uint32_t block = index / spp_;
  stratum_index_ = index - block * spp_;
  if (!same_pixel || block != block_) block_hash_ = hash_combine(pixel_hash_, block);
  block_ = block;
}

uint32_t Sampler::stratum(uint32_t d) const {
  return permute(stratum_index_, spp_, mask_, shift_, hash_combine_mixed(block_hash_, mixed_dim(d)));
}

float Sampler::get1d() {
  const uint32_t d = dim_++;
  if (type_ == SamplerType::Independent) return rng_.next_float();
  if (type_ == SamplerType::Stratified)
    return in_stratum(stratum(d), rng_.next_u32(), spp_, inv_spp_);
  const uint64_t key = hash_combine_mixed(pixel_hash_, mixed_dim(d));
  const uint32_t index = owen_scramble(index_, seed32(mix64(key)));
  return to_unit_float(owen_scramble(reverse_bits(index), seed32(mix64(key + 1))));
}

Vec2 Sampler::stratified2d(uint32_t k) {
  const uint32_t row = div_strata_x_ ? static_cast<uint32_t>((k * div_strata_x_) >> 32) : k / strata_x_;
  const uint32_t column = k - row * strata_x_;
  const uint32_t jx = rng_.next_u32(), jy = rng_.next_u32();
  return {in_stratum(column, jx, strata_x_, inv_strata_x_), in_stratum(row, jy, strata_y_, inv_strata_y_)};
}

Vec2 Sampler::get2d() {
  const uint32_t d = dim_;
  dim_ += 2;
  if (type_ == SamplerType::Independent) {
    const float a = rng_.next_float();
    return {a, rng_.next_float()};
  }
  if (type_ == SamplerType::Stratified) return stratified2d(stratum(d));
  const uint64_t key = hash_combine_mixed(pixel_hash_, mixed_dim(d));
  // Shuffling the index by an MSB-first nested scramble maps each aligned block of 2^k indices onto another aligned
  // block, so the first 2^k samples of a pixel are still a (0,k,2)-net.
  const uint32_t index = owen_scramble(index_, seed32(mix64(key)));
  return {to_unit_float(owen_scramble(reverse_bits(index), seed32(mix64(key + 1)))),
          to_unit_float(owen_scramble(sobol_dim1(index), seed32(mix64(key + 2))))};
}

VertexDims Sampler::get_vertex() {
  if (type_ != SamplerType::Stratified) {
    VertexDims v;
    v.choice = get1d();
    v.light = get2d();
    v.lobe = get1d();
    v.dir = get2d();
    v.rr = get1d();
    return v;
  }
  // Dimensions d (1D), d+1 (2D), d+3 (1D), d+4 (2D), d+6 (1D): five independent hash chains, then the jitters in
  // the order the five separate calls draw them.
  const uint32_t d = dim_;
  dim_ += 7;
  uint32_t k[5];
  for (int i = 0; i < 5; ++i) k[i] = stratum(d + sampler_detail::kVertexStrata[i]);
  const auto one = [&](uint32_t stratum_k) {
    return in_stratum(stratum_k, rng_.next_u32(), spp_, inv_spp_);
  };
  VertexDims v;
  v.choice = one(k[0]);
  v.light = stratified2d(k[1]);
  v.lobe = one(k[2]);
  v.dir = stratified2d(k[3]);
  v.rr = one(k[4]);
  return v;
}

}  // namespace lumis
