// Choosing one light per path vertex: uniform, by power, or by the lecture's per-vertex importance
// (solid angle x luminance, zero below the horizon, linear search over the running sum).
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "core/distribution.h"
#include "lights/light.h"

namespace lumis {

enum class LightSelection { Uniform, Power, Importance };
std::optional<LightSelection> parse_light_selection(std::string_view name);
const char* light_selection_name(LightSelection s);

struct LightChoice {
  int index = -1;
  float pmf = 0;
};

class LightSelector {
 public:
  LightSelector() = default;
  LightSelector(std::vector<const Light*> lights, LightSelection strategy);

  /// Choose a light for the receiver; nullopt when no light can contribute.
  std::optional<LightChoice> sample(const LightSampleContext& ctx, float u) const;
  /// sample() for n receivers: out[i] is receiver i's choice, index -1 where sample() gives none. One sphere light
  /// (cornell-sphere) is tested for every receiver in one vectorised loop; anything else receiver by receiver.
  void sample_many(const LightSampleContext* ctx, const float* u, int n, LightChoice* out) const;
  /// Probability that sample() picks light `index` at this receiver (recomputed exactly as sample() uses it).
  float pmf(const LightSampleContext& ctx, int index) const;
  size_t size() const { return lights_.size(); }

 private:
  std::vector<const Light*> lights_;
  LightSelection strategy_ = LightSelection::Uniform;
  Distribution1D power_;
  // Importance strategy, up to kMaxCached lights: the sphere lights' parameters in columns, evaluated in one
  // branch-free (vectorised) loop with no virtual call each, with sphere_importance's arithmetic; others by Light.
  static constexpr size_t kMaxCached = 64;
  struct SphereColumns {
    std::vector<float> x, y, z, radius, luminance;
    std::vector<int> index;  ///< the light's index in lights_
  } spheres_;
  std::vector<int> other_index_;
  /// Every light's importance at ctx (finite, >= 0) into out[0..size()); size() <= kMaxCached.
  void importances(const LightSampleContext& ctx, float* out) const;
};

}  // namespace lumis
