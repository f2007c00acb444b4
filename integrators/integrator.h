// Integrator interface: one radiance estimate per camera ray. The five variants (uniform, bsdf, light, mis,
// nee_mis) share one path loop (integrators/path.h) and differ in how they pick directions and count emission.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/film.h"
#include "core/sampler.h"
#include "integrators/scene.h"

namespace lumis {

/// Per-thread counters.
struct PathCounters {
  uint64_t rays = 0;  ///< closest-hit and shadow rays traced
  uint64_t shadow_rays = 0;    ///< of which occlusion (shadow) rays, for `lumis bench`
  uint64_t light_queries = 0;  ///< of which all-light-hit queries (one-sample MIS density), for `lumis bench`
};

/// The camera ray's closest hit, when the renderer has traced it already (camera rays go in 16-ray packets).
struct PrimaryHit {
  const Hit* hit = nullptr;  ///< null: the ray escaped
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  /// Radiance (W / (m^2 sr)) arriving along the camera ray, one sample. primary (may be null: li traces the ray)
  /// is the ray's closest hit; aov (may be null) receives first-hit data.
  virtual Color li(const Scene& scene, const Ray& ray, const PrimaryHit* primary, Sampler& sampler, AovSample* aov,
                   PathCounters& counters) const = 0;
  virtual const char* name() const = 0;
};

/// The variant names, in the order users see them.
const std::vector<std::string>& integrator_names();
/// Build the variant `settings.integrator`; throws std::invalid_argument naming the valid ones.
std::unique_ptr<Integrator> make_integrator(const RenderSettings& settings);

std::unique_ptr<Integrator> make_uniform_integrator(const RenderSettings& settings);
std::unique_ptr<Integrator> make_bsdf_integrator(const RenderSettings& settings);
std::unique_ptr<Integrator> make_light_integrator(const RenderSettings& settings);
std::unique_ptr<Integrator> make_mis_integrator(const RenderSettings& settings);
std::unique_ptr<Integrator> make_nee_mis_integrator(const RenderSettings& settings);

}  // namespace lumis
