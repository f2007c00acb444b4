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

/// Up to kMaxLanes camera rays (one sample each of neighbouring pixels) whose paths an integrator traces in
/// lockstep, one bounce of all lanes at a time, so that each bounce's queries can go to Embree in packets of
/// kPacket rays. Every lane keeps its own sampler, so a lane's estimate does not depend on its neighbours.
struct PathBatch {
  static constexpr int kMaxLanes = 256;  ///< 16x16 pixels: a bounce's shadow rays fill nearly all their packets
  static constexpr int kPacket = 16;    ///< Embree's widest packet (rtcIntersect16, rtcOccluded16)
  int n = 0;                             ///< lanes, 1..kMaxLanes
  const Ray* rays = nullptr;             ///< camera rays (world)
  const Hit* const* primary = nullptr;   ///< per lane: the camera ray's closest hit, null if it escaped; a null
                                         ///< array: li traces the camera rays itself
  Sampler* samplers = nullptr;           ///< per lane, started at the lane's pixel and sample index
  AovSample* aov = nullptr;              ///< per lane first-hit data (may be null)
  Color* radiance = nullptr;             ///< out: per lane radiance estimate
  bool shadow_packets = true;            ///< trace a bounce's shadow rays in 16-wide queries (false: one by one)
  bool bounce_packets = false;           ///< trace bounce rays (after the camera rays) in 16-wide incoherent
                                         ///< queries (false: one by one, the results of a path traced alone)
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  /// Radiance (W / (m^2 sr)) arriving along each camera ray of the batch, one sample each.
  virtual void li(const Scene& scene, const PathBatch& batch, PathCounters& counters) const = 0;
  virtual const char* name() const = 0;
};

/// The variant names, in the order users see them.
const std::vector<std::string>& integrator_names();
/// Whether a variant sees lights only where its rays hit them (uniform, bsdf, mis): a light too small for a float ray
/// test to hit (Scene::small_lights) escapes it, where light and nee_mis sample the light itself.
bool finds_lights_by_hitting(const std::string& integrator);
/// Build the variant `settings.integrator`; throws std::invalid_argument naming the valid ones.
std::unique_ptr<Integrator> make_integrator(const RenderSettings& settings);

std::unique_ptr<Integrator> make_uniform_integrator(const RenderSettings& settings);
std::unique_ptr<Integrator> make_bsdf_integrator(const RenderSettings& settings);
std::unique_ptr<Integrator> make_light_integrator(const RenderSettings& settings);
std::unique_ptr<Integrator> make_mis_integrator(const RenderSettings& settings);
std::unique_ptr<Integrator> make_nee_mis_integrator(const RenderSettings& settings);

}  // namespace lumis
