// Piecewise-constant distributions by inversion of a tabulated CDF (the lecture's discrete sampling, with a binary
// search in place of the linear one). The CDF is summed in double and rounded to the sampler's 2^-24 grid, so that
// pmf() and the densities are the probabilities sampling realises, exactly.
#include "core/distribution.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace lumis {

Distribution1D::Distribution1D(std::span<const float> f) : func_(f.begin(), f.end()) {
  // An empty table behaves as one zero cell, i.e. uniform: callers need not special-case it.
  if (func_.empty()) func_.push_back(0.0f);
  for (float& v : func_)
    if (!(v > 0) || !std::isfinite(v)) v = 0.0f;  // negative, NaN and infinite weights cannot be sampled
  const size_t n = func_.size();
  std::vector<double> sum(n + 1, 0.0);
  for (size_t i = 0; i < n; ++i) sum[i + 1] = sum[i] + static_cast<double>(func_[i]) / n;
  integral_ = static_cast<float>(sum[n]);
  // The CDF on the sampler's grid (multiples of 2^-24, exact in float): a cell's probability is then the width of
  // its interval exactly, for u on that grid or uniform on [0, 1), and pmf() returns that width. The running sum is
  // rounded to the grid, but every cell that can be drawn (f > 0; all of them when f is all zero) keeps at least one
  // step: one far below 2^-24 of the total was never drawn, so its light was lost. The cells after it give the step
  // back as soon as they are wide enough. The steps so lent come from the other cells, so the rule holds only while
  // they are few (at most 2^18, 1/64 of the total): a million cells each below a step would otherwise take most of
  // the probability from the cells that carry the weight. Beyond that, cells under half a step are not drawn, and
  // pmf() says 0 for them, so MIS still counts them through its other strategies.
  const bool weighted = sum[n] > 0;
  const auto drawable = [&](size_t i) { return !weighted || func_[i] > 0; };
  constexpr uint64_t kSteps = uint64_t{1} << 24;
  size_t remaining = 0;
  double lent = 0;  // steps the rule adds to cells narrower than one step
  for (size_t i = 0; i < n; ++i) {
    if (!drawable(i)) continue;
    ++remaining;
    const double steps = weighted ? static_cast<double>(func_[i]) / n / sum[n] * kSteps : double(kSteps) / n;
    lent += std::max(0.0, 1.0 - steps);
  }
  const bool one_each = remaining <= kSteps && lent <= double(kSteps >> 6);
  cdf_.resize(n + 1);
  uint64_t c = 0;  // steps below cell i
  for (size_t i = 0; i < n; ++i) {
    cdf_[i] = static_cast<float>(c) * 0x1p-24f;
    if (!drawable(i)) continue;
    --remaining;
    const double share = weighted ? sum[i + 1] / sum[n] : static_cast<double>(i + 1) / static_cast<double>(n);
    const uint64_t target = static_cast<uint64_t>(std::llround(std::min(share, 1.0) * static_cast<double>(kSteps)));
    c = one_each ? std::clamp(target, c + 1, kSteps - remaining) : std::max(c, target);
  }
  cdf_[n] = 1.0f;
}

namespace {
// Index of the cell whose CDF interval [cdf[i], cdf[i+1]) holds u. Zero-weight cells have empty intervals and are
// skipped by taking the last i with cdf[i] <= u.
size_t find_cell(const std::vector<float>& cdf, float u) {
  const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
  const ptrdiff_t i = (it - cdf.begin()) - 1;
  return static_cast<size_t>(std::clamp<ptrdiff_t>(i, 0, static_cast<ptrdiff_t>(cdf.size()) - 2));
}
}  // namespace

float Distribution1D::sample_continuous(float u, float* pdf, size_t* cell) const {
  const size_t i = find_cell(cdf_, u);
  const float width = cdf_[i + 1] - cdf_[i];
  const float du = width > 0 ? clamp((u - cdf_[i]) / width, 0.0f, 1.0f) : 0.0f;
  if (pdf) *pdf = width * static_cast<float>(size());
  if (cell) *cell = i;
  // Rounding of (i + du) / n can reach 1 for the last cell (the domain is [0, 1)), and for du near 1 the next
  // cell's lower edge (for i ~ 1000, about 3e-5 of the samples): x is kept in cell i as pdf_continuous() finds it,
  // so that *pdf is the density at x. (A cell narrower than a float step near x, n beyond 2^23, is left as it is.)
  const size_t n = size();
  const auto cell_of = [n](float x) { return std::min(static_cast<size_t>(x * static_cast<float>(n)), n - 1); };
  float x = std::min((static_cast<float>(i) + du) / static_cast<float>(n), kOneMinusEpsilon);
  for (int k = 0; k < 4 && cell_of(x) > i; ++k) x = std::nextafter(x, 0.0f);
  for (int k = 0; k < 4 && cell_of(x) < i; ++k) x = std::nextafter(x, 1.0f);
  return x;
}

float Distribution1D::pdf_continuous(float x) const {
  if (!(x >= 0 && x < 1)) return 0.0f;
  const size_t i = std::min(static_cast<size_t>(x * static_cast<float>(size())), size() - 1);
  return (cdf_[i + 1] - cdf_[i]) * static_cast<float>(size());
}

size_t Distribution1D::sample_discrete(float u, float* pmf_out, float* u_remapped) const {
  const size_t i = find_cell(cdf_, u);
  if (pmf_out) *pmf_out = pmf(i);
  if (u_remapped) {
    const float width = cdf_[i + 1] - cdf_[i];
    *u_remapped = width > 0 ? clamp((u - cdf_[i]) / width, 0.0f, kOneMinusEpsilon) : 0.0f;
  }
  return i;
}

float Distribution1D::pmf(size_t i) const {
  if (i >= size()) return 0.0f;
  return cdf_[i + 1] - cdf_[i];
}

float Distribution1D::invert(float x) const {
  const float xn = clamp(x, 0.0f, 1.0f) * static_cast<float>(size());
  const size_t i = std::min(static_cast<size_t>(xn), size() - 1);
  const float frac = clamp(xn - static_cast<float>(i), 0.0f, 1.0f);
  return std::min(cdf_[i] + frac * (cdf_[i + 1] - cdf_[i]), kOneMinusEpsilon);
}

Distribution2D::Distribution2D(std::span<const float> f, int nu, int nv) : nu_(nu), nv_(nv) {
  if (nu <= 0 || nv <= 0 || f.size() != static_cast<size_t>(nu) * static_cast<size_t>(nv))
    throw std::invalid_argument("Distribution2D: table size does not match nu x nv");
  conditional_.reserve(nv);
  std::vector<float> row_integrals(nv);
  for (int v = 0; v < nv; ++v) {
    conditional_.emplace_back(f.subspan(static_cast<size_t>(v) * nu, nu));
    row_integrals[v] = conditional_.back().integral();
  }
  marginal_ = Distribution1D(row_integrals);
}

Vec2 Distribution2D::sample_continuous(Vec2 u, float* pdf_out) const {
  float pdf_v = 0, pdf_u = 0;
  size_t v = 0;
  const float y = marginal_.sample_continuous(u.y, &pdf_v, &v);
  const float x = conditional_[v].sample_continuous(u.x, &pdf_u);
  if (pdf_out) *pdf_out = pdf_u * pdf_v;
  return {x, y};
}

float Distribution2D::pdf(Vec2 p) const {
  if (!(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1)) return 0.0f;
  const int iv = std::min(static_cast<int>(p.y * nv_), nv_ - 1);
  // Same product as sample_continuous: (f / row integral) * (row integral / total) = f / total.
  return marginal_.pdf_continuous(p.y) * conditional_[iv].pdf_continuous(p.x);
}

Vec2 Distribution2D::invert(Vec2 p) const {
  const int iv = std::clamp(static_cast<int>(p.y * nv_), 0, nv_ - 1);
  return {conditional_[iv].invert(p.x), marginal_.invert(p.y)};
}

}  // namespace lumis
