// Render options that override the scene file (shared by render, compare and bench), and the default scene.
// Kept apart from app/cli.cpp, the one file that includes CLI11 (about 11 s of compile time at -O3 in every file
// that includes it).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "integrators/scene.h"

namespace lumis {

/// Largest image width or height, in pixels (--width, --height, and a side that follows the aspect ratio).
inline constexpr int kMaxImageSide = 16384;

/// Render options that override the scene file (shared by render, compare and bench).
struct RenderOverrides {
  std::optional<uint32_t> spp, seed;
  std::optional<int> max_depth, rr_depth, width, height, threads;
  std::optional<std::string> integrator, sampler, light_selection, mis_heuristic, uniform_measure;
  std::optional<double> time;  ///< seconds, kept in double: 0.05 stays 0.05 in the compare report
  std::optional<float> exposure, mis_light_probability;
  std::string camera;  ///< a glTF file's camera (SceneLoadOptions::camera), from --camera; empty: default
};

/// Apply overrides to settings; throws std::invalid_argument for bad names (listing valid ones).
void apply_overrides(const RenderOverrides& o, RenderSettings& s);
/// Apply overrides to the scene's settings, and frame a generated camera (Scene::framed) again for the final image
/// size, so that the scene fits a --width/--height of another aspect ratio too.
void apply_overrides(const RenderOverrides& o, Scene& scene);
/// Warnings for overrides given on the command line that none of the integrators uses (for example
/// --mis-light-probability with nee_mis), one sentence each; nee_mis_reference: compare's rendered reference (nee_mis)
/// uses them too, and is named as such.
std::vector<std::string> unused_overrides(const RenderOverrides& o, const std::vector<std::string>& integrators,
                                          bool nee_mis_reference = false);

/// The command line's name of a MIS heuristic ("balance", "power") and of a uniform measure ("theta-phi",
/// "solid-angle"), for reports and help.
const char* mis_heuristic_name(MisHeuristic h);
const char* uniform_measure_name(UniformMeasure m);

/// What a render uses where neither the command line nor the scene file says (RenderSettings' defaults), for
/// `render --help`: "--spp 64, --integrator nee_mis, ...".
std::string scene_defaults_text();

/// The built-in default scene (scenes/cornell-sphere.json), found next to the sources or the executable.
std::string default_scene_path();

}  // namespace lumis
