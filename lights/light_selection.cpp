// Choosing one light per receiver. Importance follows the lecture: c_j = solid angle x luminance, zero when the
// light is entirely below the horizon; pick j with sum_{l<j} c_l <= C u < sum_{l<=j} c_l by a linear search, so
// the cost is O(number of lights) per vertex and nothing is allocated.
#include <algorithm>
#include <array>
#include <cmath>

#include "lights/light_selection.h"

namespace lumis {

std::optional<LightSelection> parse_light_selection(std::string_view name) {
  if (name == "uniform") return LightSelection::Uniform;
  if (name == "power") return LightSelection::Power;
  if (name == "importance") return LightSelection::Importance;
  return std::nullopt;
}

const char* light_selection_name(LightSelection s) {
  switch (s) {
    case LightSelection::Uniform: return "uniform";
    case LightSelection::Power: return "power";
    case LightSelection::Importance: return "importance";
  }
  return "?";
}

LightSelector::LightSelector(std::vector<const Light*> lights, LightSelection strategy)
    : lights_(std::move(lights)), strategy_(strategy) {
  if (strategy_ == LightSelection::Power && !lights_.empty()) {
    std::vector<float> power(lights_.size());
    for (size_t i = 0; i < lights_.size(); ++i) power[i] = std::max(lights_[i]->power(), 0.0f);
    power_ = Distribution1D(power);
  }
  if (strategy_ == LightSelection::Importance && lights_.size() <= kMaxCached) {
    for (size_t i = 0; i < lights_.size(); ++i) {
      if (const std::optional<SphereEmitter> s = lights_[i]->sphere()) {
        spheres_.x.push_back(s->center.x);
        spheres_.y.push_back(s->center.y);
        spheres_.z.push_back(s->center.z);
        spheres_.radius.push_back(s->radius);
        spheres_.luminance.push_back(s->luminance);
        spheres_.index.push_back(static_cast<int>(i));
      } else {
        other_index_.push_back(static_cast<int>(i));
      }
    }
  }
}

namespace {

// Importance clamped to a finite, non-negative value (a NaN must neither be chosen nor poison the sum).
float clean(float c) { return std::isfinite(c) && c > 0 ? c : 0.0f; }
float clean_importance(const Light* light, const LightSampleContext& ctx) { return clean(light->importance(ctx)); }

}  // namespace

void LightSelector::importances(const LightSampleContext& ctx, float* out) const {
  // Every sphere in one loop over the columns: sphere_importance has no branches, so this vectorises (the file is
  // built with -fno-math-errno -fno-trapping-math, see CMakeLists.txt).
  const SphereColumns& s = spheres_;
  const size_t m = s.index.size();
  float value[kMaxCached];
  for (size_t i = 0; i < m; ++i)
    value[i] = sphere_importance({{s.x[i], s.y[i], s.z[i]}, s.radius[i], s.luminance[i]}, ctx);
  for (size_t i = 0; i < m; ++i) out[s.index[i]] = clean(value[i]);
  for (const int j : other_index_) out[j] = clean_importance(lights_[j], ctx);
}

std::optional<LightChoice> LightSelector::sample(const LightSampleContext& ctx, float u) const {
  const size_t n = lights_.size();
  if (n == 0) return std::nullopt;
  switch (strategy_) {
    case LightSelection::Uniform: {
      const int i = std::min(static_cast<int>(u * static_cast<float>(n)), static_cast<int>(n) - 1);
      return LightChoice{i, 1.0f / static_cast<float>(n)};
    }
    case LightSelection::Power: {
      const size_t i = power_.sample_discrete(u);
      const float p = power_.pmf(i);
      if (!(p > 0)) return std::nullopt;
      return LightChoice{static_cast<int>(i), p};
    }
    case LightSelection::Importance: break;
  }
  if (n == 1) {  // the one light, when it can contribute
    const float c = clean_importance(lights_[0], ctx);
    return c > 0 ? std::optional<LightChoice>(LightChoice{0, 1.0f}) : std::nullopt;
  }
  // Up to kMaxCached lights the importances stay on the stack; more are recomputed in the search (the same values:
  // sphere_importance is what a sphere's importance() returns).
  std::array<float, kMaxCached> cache;
  const bool cached = n <= kMaxCached;
  if (cached) importances(ctx, cache.data());
  float total = 0;
  for (size_t j = 0; j < n; ++j) total += cached ? cache[j] : clean_importance(lights_[j], ctx);
  if (!(total > 0)) return std::nullopt;
  const float target = total * u;
  float running = 0;
  int last_positive = -1;
  float last_c = 0;
  for (size_t j = 0; j < n; ++j) {
    const float c = cached ? cache[j] : clean_importance(lights_[j], ctx);
    if (c <= 0) continue;
    running += c;
    last_positive = static_cast<int>(j);
    last_c = c;
    if (target < running) return LightChoice{last_positive, c / total};
  }
  // Only when total * u rounded up to total: the last light with positive importance owns the top of [0, C).
  return LightChoice{last_positive, last_c / total};
}

void LightSelector::sample_many(const LightSampleContext* ctx, const float* u, int n, LightChoice* out) const {
  if (strategy_ == LightSelection::Importance && lights_.size() == 1 && spheres_.index.size() == 1) {
    // sample()'s one-light case: the light when its importance is positive; sphere_importance is what a sphere's
    // importance() returns, and it has no branches, so this loop vectorises.
    // (The receivers in columns, a chunk at a time: the loop does not vectorise over the structs themselves.)
    const SphereEmitter s{{spheres_.x[0], spheres_.y[0], spheres_.z[0]}, spheres_.radius[0], spheres_.luminance[0]};
    constexpr int kChunk = 64;
    float px[kChunk], py[kChunk], pz[kChunk], nx[kChunk], ny[kChunk], nz[kChunk];
    int positive[kChunk];
    for (int begin = 0; begin < n; begin += kChunk) {
      const int m = std::min(kChunk, n - begin);
      for (int k = 0; k < m; ++k) {
        const LightSampleContext& c = ctx[begin + k];
        px[k] = c.p.x, py[k] = c.p.y, pz[k] = c.p.z, nx[k] = c.n.x, ny[k] = c.n.y, nz[k] = c.n.z;
      }
      for (int k = 0; k < m; ++k)
        positive[k] = clean(sphere_importance(s, {{px[k], py[k], pz[k]}, {nx[k], ny[k], nz[k]}})) > 0;
      for (int k = 0; k < m; ++k) out[begin + k] = positive[k] ? LightChoice{0, 1.0f} : LightChoice{};
    }
    return;
  }
  for (int i = 0; i < n; ++i) out[i] = sample(ctx[i], u[i]).value_or(LightChoice{});
}

float LightSelector::pmf(const LightSampleContext& ctx, int index) const {
  const size_t n = lights_.size();
  if (index < 0 || static_cast<size_t>(index) >= n) return 0;
  switch (strategy_) {
    case LightSelection::Uniform: return 1.0f / static_cast<float>(n);
    case LightSelection::Power: return power_.pmf(static_cast<size_t>(index));
    case LightSelection::Importance: break;
  }
  if (n == 1) return clean_importance(lights_[0], ctx) > 0 ? 1.0f : 0.0f;
  if (n <= kMaxCached) {
    std::array<float, kMaxCached> cache;
    importances(ctx, cache.data());
    float total = 0;
    for (size_t j = 0; j < n; ++j) total += cache[j];
    return total > 0 ? cache[index] / total : 0.0f;
  }
  float total = 0, mine = 0;
  for (size_t j = 0; j < n; ++j) {
    const float c = clean_importance(lights_[j], ctx);
    if (static_cast<int>(j) == index) mine = c;
    total += c;
  }
  return total > 0 ? mine / total : 0.0f;
}

}  // namespace lumis
