// A render-ready scene: geometry (Embree), materials, lights, camera and the render settings.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/geometry.h"
#include "core/sampler.h"
#include "lights/light.h"
#include "lights/light_selection.h"
#include "materials/material.h"

namespace lumis {

enum class MisHeuristic { Balance, Power };
enum class UniformMeasure { ThetaPhi, SolidAngle };

struct RenderSettings {
  std::string integrator = "nee_mis";
  uint32_t spp = 64;
  int max_depth = 8;         ///< path vertices that scatter; 1 = direct lighting only
  int rr_depth = 3;          ///< Russian roulette from this depth on; 0 = off
  SamplerType sampler = SamplerType::Stratified;
  uint32_t seed = 0;
  LightSelection light_selection = LightSelection::Importance;
  MisHeuristic mis_heuristic = MisHeuristic::Balance;
  UniformMeasure uniform_measure = UniformMeasure::ThetaPhi;
  float mis_light_probability = 0.5f;  ///< `mis`: probability of the light strategy at a vertex (c_l)
  int width = 512, height = 512;
  double aspect = 0;         ///< width / height meant, where the pixel size is clamped short of it; 0 = width / height
  double time_budget = 0;    ///< seconds; 0 = none
  int threads = 0;           ///< 0 = all cores
  bool aov_albedo = false, aov_normal = false, aov_depth = false, aov_variance = true;
  float exposure = 0;
};

struct Scene {
  Geometry geometry;
  std::vector<std::unique_ptr<Material>> materials;
  std::vector<std::unique_ptr<Light>> lights;
  int environment = -1;      ///< index of the environment light, -1 when none
  LightSelector light_selector;
  Camera camera;
  RenderSettings settings;
  std::string source;        ///< file the scene came from (for messages)
  /// Image files the scene was built from (textures, environment maps), as the loader resolved them.
  std::vector<std::string> input_images;
  /// The other files the scene was built from besides `source`: glTF files a JSON scene includes and every glTF
  /// file's external buffers, resolved.
  std::vector<std::string> input_files;
  /// Set when the file has no camera and `camera` was generated to frame these bounds for the film's aspect ratio
  /// (app/json_scene.h, frame_bounds): a new image size calls for framing them again.
  std::optional<Bounds3> framed;
  /// Warnings ("FILE:POINTER: warning: ...") for lights too small against the scene for a ray to hit them
  /// reliably; only the variants that find lights by hitting them (finds_lights_by_hitting) render those wrong.
  std::vector<std::string> small_lights;

  /// After all geometry and lights are added: build the BVH, preprocess lights, build the light selector.
  void finalize();
  /// Rebuild the light selector after settings.light_selection changed.
  void update_light_selector();
  /// Every file the scene was built from besides `source`, input_files then input_images, each path once (a glTF file
  /// included twice, an image two glTF images name): what a cached compare reference depends on, and what no output
  /// (render -o, compare's folder, bench --json) may be written over.
  std::vector<std::string> inputs() const;
};

}  // namespace lumis
