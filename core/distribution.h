// Piecewise-constant 1D and 2D distributions (for environment maps and light selection).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "core/math.h"

namespace lumis {

/// Piecewise-constant density on [0, 1) with n equal cells of weight f[i] >= 0 (all-zero input -> uniform).
/// Sampling is O(log n) by binary search of the CDF. The CDF lies on the sampler's 2^-24 grid, and pmf() and the
/// densities are what sampling realises, exactly. pmf(i) is f[i] / sum f rounded to the grid, except that a cell with
/// f[i] > 0 narrower than one step is lent one, so that it can be drawn, while the steps lent stay under 2^18 (1/64).
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::span<const float> f);

  size_t size() const { return func_.size(); }
  /// Integral of f over [0,1) (mean of the weights).
  float integral() const { return integral_; }
  float func(size_t i) const { return func_[i]; }

  /// Continuous sample x in [0,1); *pdf is the density on [0,1); *cell the cell index.
  float sample_continuous(float u, float* pdf, size_t* cell = nullptr) const;
  /// Density on [0,1) at x.
  float pdf_continuous(float x) const;
  /// Discrete sample of a cell with probability pmf(i); *pmf that probability; *u_remapped reuses u in [0,1).
  size_t sample_discrete(float u, float* pmf = nullptr, float* u_remapped = nullptr) const;
  /// Probability of cell i under sample_discrete (the width of its CDF interval).
  float pmf(size_t i) const;
  /// Inverse of sample_continuous.
  float invert(float x) const;

 private:
  std::vector<float> func_, cdf_;  // cdf_ has n+1 entries
  float integral_ = 0;
};

/// Piecewise-constant density on [0,1)^2 over an nu x nv grid (row-major f[v * nu + u]): marginal in v,
/// conditional in u.
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(std::span<const float> f, int nu, int nv);

  /// Sample (u, v) in [0,1)^2; *pdf is the density with respect to area on [0,1)^2.
  Vec2 sample_continuous(Vec2 u, float* pdf) const;
  /// Density on [0,1)^2 at p.
  float pdf(Vec2 p) const;
  /// Inverse of sample_continuous.
  Vec2 invert(Vec2 p) const;
  int nu() const { return nu_; }
  int nv() const { return nv_; }

 private:
  std::vector<Distribution1D> conditional_;
  Distribution1D marginal_;
  int nu_ = 0, nv_ = 0;
};

}  // namespace lumis
