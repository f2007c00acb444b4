// Render options that override the scene file (app/render_overrides.h): applying them to a scene's settings, and
// naming those that none of the chosen integrators reads.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>

#include "app/json_scene.h"
#include "app/render_overrides.h"
#include "integrators/integrator.h"

namespace lumis {

void apply_overrides(const RenderOverrides& o, RenderSettings& s) {
  if (o.spp) s.spp = *o.spp;
  if (o.seed) s.seed = *o.seed;
  if (o.max_depth) s.max_depth = *o.max_depth;
  if (o.rr_depth) s.rr_depth = *o.rr_depth;
  // One of the two alone keeps the scene's aspect ratio (a smaller or larger render of the same picture); where the
  // other side would leave 1...kMaxImageSide pixels, the picture cannot be kept, and clamping it silently would
  // squash it: a usage error that says so.
  const double aspect = s.aspect > 0 ? s.aspect : double(s.width) / double(s.height);
  char ratio[64];  // as the scene states it: its pixel size, or the camera's own ratio that the size is clamped from
  if (s.aspect > 0) std::snprintf(ratio, sizeof ratio, "camera's aspect ratio %g", s.aspect);
  else std::snprintf(ratio, sizeof ratio, "scene's %d x %d aspect ratio", s.width, s.height);
  const auto follow = [&](double v, const char* given, int n, const char* side, const char* other) {
    if (std::lround(v) < 1 || std::lround(v) > kMaxImageSide) {
      char need[32];
      if (v >= 1) std::snprintf(need, sizeof need, "%ld", std::lround(v));  // the number tested, rounded alike
      else std::snprintf(need, sizeof need, "%.2g", v);
      throw std::invalid_argument(std::string(given) + " " + std::to_string(n) + " alone keeps the " + ratio +
                                  ", which needs a " + side + " of " + need + " pixels, outside 1 to " +
                                  std::to_string(kMaxImageSide) + ": give " + other + " as well");
    }
    return static_cast<int>(std::lround(v));
  };
  if (o.width && !o.height) s.height = follow(*o.width / aspect, "--width", *o.width, "height", "--height");
  if (o.height && !o.width) s.width = follow(*o.height * aspect, "--height", *o.height, "width", "--width");
  if (o.width) s.width = *o.width;
  if (o.height) s.height = *o.height;
  if (o.threads) s.threads = *o.threads;
  // --spp alone asks for that many samples, over a scene file's `time`; with --time too, whichever comes first.
  if (o.spp && !o.time) s.time_budget = 0;
  if (o.time) s.time_budget = *o.time;
  if (o.exposure) s.exposure = *o.exposure;
  if (o.mis_light_probability) s.mis_light_probability = *o.mis_light_probability;
  if (o.integrator) {
    bool ok = false;
    for (const auto& n : integrator_names()) ok |= n == *o.integrator;
    if (!ok) throw std::invalid_argument("--integrator: unknown integrator '" + *o.integrator +
                                         "' (valid: uniform, bsdf, light, mis, nee_mis)");
    s.integrator = *o.integrator;
  }
  if (o.sampler) {
    const auto t = parse_sampler_type(*o.sampler);
    if (!t) throw std::invalid_argument("--sampler: unknown sampler '" + *o.sampler +
                                        "' (valid: independent, stratified, sobol)");
    s.sampler = *t;
  }
  if (o.light_selection) {
    const auto t = parse_light_selection(*o.light_selection);
    if (!t) throw std::invalid_argument("--light-selection: unknown strategy '" + *o.light_selection +
                                        "' (valid: uniform, power, importance)");
    s.light_selection = *t;
  }
  if (o.mis_heuristic) {
    if (*o.mis_heuristic == "balance") s.mis_heuristic = MisHeuristic::Balance;
    else if (*o.mis_heuristic == "power") s.mis_heuristic = MisHeuristic::Power;
    else throw std::invalid_argument("--mis-heuristic: unknown heuristic '" + *o.mis_heuristic +
                                     "' (valid: balance, power)");
  }
  if (o.uniform_measure) {  // the scene file's spelling (theta_phi, solid_angle) is accepted too
    const std::string& m = *o.uniform_measure;
    if (m == "theta-phi" || m == "theta_phi") s.uniform_measure = UniformMeasure::ThetaPhi;
    else if (m == "solid-angle" || m == "solid_angle") s.uniform_measure = UniformMeasure::SolidAngle;
    else throw std::invalid_argument("--uniform-measure: unknown measure '" + *o.uniform_measure +
                                     "' (valid: theta-phi, solid-angle)");
  }
}

void apply_overrides(const RenderOverrides& o, Scene& scene) {
  apply_overrides(o, scene.settings);
  if (!scene.framed) return;
  frame_camera(scene, *scene.framed);
  const float far = max_component(abs(scene.camera.from));
  if (!(far <= kMaxCoordinate)) {
    char distance[32];
    std::snprintf(distance, sizeof distance, "%.3g", far);
    throw std::invalid_argument("--width/--height: to frame the scene in a " + std::to_string(scene.settings.width) +
                                " x " + std::to_string(scene.settings.height) + " image the camera would stand " +
                                distance + " scene units from the origin, beyond the 1e12 that rays can start "
                                "from; choose a less extreme aspect ratio or give the scene a camera");
  }
}

std::vector<std::string> unused_overrides(const RenderOverrides& o, const std::vector<std::string>& integrators,
                                          bool nee_mis_reference) {
  std::vector<std::string> out;
  std::string list;
  for (const std::string& i : integrators) list += (list.empty() ? "" : ", ") + i;
  if (nee_mis_reference) list += std::string(list.empty() ? "" : " and ") + "the reference (nee_mis)";
  // An option is reported when it is given and none of the integrators uses it.
  const auto unused = [&](bool given, const char* option, const char* applies_to,
                          std::initializer_list<const char*> users) {
    if (!given) return;
    for (const char* u : users) {
      if (nee_mis_reference && std::string(u) == "nee_mis") return;
      for (const std::string& i : integrators)
        if (i == u) return;
    }
    out.push_back(std::string(option) + " only affects " + applies_to + "; ignored for " + list);
  };
  unused(o.mis_light_probability.has_value(), "--mis-light-probability", "the mis integrator", {"mis"});
  unused(o.uniform_measure.has_value(), "--uniform-measure", "the uniform integrator", {"uniform"});
  // mis's one-sample estimator (f / the mixture density) is the balance heuristic itself: no choice to make.
  unused(o.mis_heuristic.has_value(), "--mis-heuristic", "the nee_mis integrator", {"nee_mis"});
  unused(o.light_selection.has_value(), "--light-selection", "light, mis and nee_mis", {"light", "mis", "nee_mis"});
  return out;
}

const char* mis_heuristic_name(MisHeuristic h) { return h == MisHeuristic::Power ? "power" : "balance"; }
const char* uniform_measure_name(UniformMeasure m) {
  return m == UniformMeasure::SolidAngle ? "solid-angle" : "theta-phi";
}

std::string scene_defaults_text() {
  const RenderSettings d;
  char text[640];
  std::snprintf(text, sizeof text,
                "Where an option is not given, the scene file's value is used (its render and film blocks), else:\n"
                "  --spp %u, --integrator %s, --max-depth %d, --rr-depth %d, --seed %u,\n"
                "  --sampler %s, --light-selection %s, --mis-heuristic %s,\n"
                "  --mis-light-probability %g, --uniform-measure %s, --time %g (none), --exposure %g,\n"
                "  --width %d --height %d (a glTF file alone: %d wide at its camera's aspect ratio).",
                d.spp, d.integrator.c_str(), d.max_depth, d.rr_depth, d.seed, sampler_type_name(d.sampler),
                light_selection_name(d.light_selection), mis_heuristic_name(d.mis_heuristic), d.mis_light_probability,
                uniform_measure_name(d.uniform_measure),
                d.time_budget, d.exposure, d.width, d.height, d.width);
  return text;
}

}  // namespace lumis
