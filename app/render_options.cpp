#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>

#include "app/cli.h"
#include "integrators/integrator.h"

namespace lumis {

namespace {
constexpr long kMaxSide = 16384;  // pixels, either side of the image
}  // namespace

void add_render_overrides(CLI::App& cmd, RenderOverrides& o) {
  cmd.add_option("--spp", o.spp, "Samples per pixel")->check(CLI::Range(1u, 1u << 30));
  cmd.add_option("--integrator", o.integrator, "uniform | bsdf | light | mis | nee_mis");
  cmd.add_option("--max-depth", o.max_depth, "Scattering vertices per path (1 = direct lighting only)")
      ->check(CLI::Range(1, 1024));
  cmd.add_option("--rr-depth", o.rr_depth, "Russian roulette from this depth on (0 = off)")->check(CLI::Range(0, 1024));
  cmd.add_option("--seed", o.seed, "Random seed, in [0, 4294967295]")
      ->check(number_in(0, 4294967295.0, "a whole number in [0, 4294967295]"));
  cmd.add_option("--threads", o.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  cmd.add_option("--width", o.width, "Image width in pixels (alone: the height keeps the scene's aspect ratio)")
      ->check(CLI::Range(1, int(kMaxSide)));
  cmd.add_option("--height", o.height, "Image height in pixels (alone: the width keeps the scene's aspect ratio)")
      ->check(CLI::Range(1, int(kMaxSide)));
  cmd.add_option("--sampler", o.sampler, "independent | stratified | sobol");
  cmd.add_option("--light-selection", o.light_selection, "uniform | power | importance");
  cmd.add_option("--mis-heuristic", o.mis_heuristic, "balance | power");
  cmd.add_option("--mis-light-probability", o.mis_light_probability,
                 "For --integrator mis: probability c_l of the light strategy, in [0, 1) (default 0.5)")
      ->check(kFiniteNumber)
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            // 1 is left out: with light sampling alone, directions no light covers (indirect light) are never
            // drawn, and the estimate loses that light.
            try {
              const double v = std::stod(text);
              if (!(v >= 0 && v < 1)) return "expected a probability in [0, 1), found " + text;
            } catch (const std::exception&) {
            }
            return {};
          },
          "in [0, 1)"));
  cmd.add_option("--uniform-measure", o.uniform_measure, "theta-phi | solid-angle (for --integrator uniform)");
  cmd.add_option("--time", o.time, "Stop after this many seconds (writes what was rendered; 0 = no time budget)")
      ->check(kFiniteNumber)
      ->check(CLI::Range(0.0f, 1e7f));
  cmd.add_option("--exposure", o.exposure, "Exposure in stops for PNG/JPG output")
      ->check(kFiniteNumber)
      ->check(CLI::Range(-64.0f, 64.0f));
}

void add_camera_option(CLI::App& cmd, RenderOverrides& o) {
  cmd.add_option("--camera", o.camera,
                 "For a glTF file: the camera to render through, by number (0 = the first, the default) or by name; "
                 "an unknown one lists those the file has");
}

void apply_overrides(const RenderOverrides& o, RenderSettings& s) {
  if (o.spp) s.spp = *o.spp;
  if (o.seed) s.seed = *o.seed;
  if (o.max_depth) s.max_depth = *o.max_depth;
  if (o.rr_depth) s.rr_depth = *o.rr_depth;
  // One of the two alone keeps the scene's aspect ratio (a smaller or larger render of the same picture).
  const double aspect = double(s.width) / double(s.height);
  const auto follow = [](double v) { return static_cast<int>(std::clamp(std::lround(v), 1L, kMaxSide)); };
  if (o.width) s.width = *o.width;
  if (o.height) s.height = *o.height;
  if (o.width && !o.height) s.height = follow(*o.width / aspect);
  if (o.height && !o.width) s.width = follow(*o.height * aspect);
  if (o.threads) s.threads = *o.threads;
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

std::vector<std::string> unused_overrides(const RenderOverrides& o, const std::vector<std::string>& integrators) {
  std::vector<std::string> out;
  std::string list;
  for (const std::string& i : integrators) list += (list.empty() ? "" : ", ") + i;
  // An option is reported when it is given and none of the integrators uses it.
  const auto unused = [&](bool given, const char* option, const char* applies_to,
                          std::initializer_list<const char*> users) {
    if (!given) return;
    for (const std::string& i : integrators)
      for (const char* u : users)
        if (i == u) return;
    out.push_back(std::string(option) + " only affects " + applies_to + "; ignored for " + list);
  };
  unused(o.mis_light_probability.has_value(), "--mis-light-probability", "--integrator mis", {"mis"});
  unused(o.uniform_measure.has_value(), "--uniform-measure", "--integrator uniform", {"uniform"});
  unused(o.mis_heuristic.has_value(), "--mis-heuristic", "mis and nee_mis", {"mis", "nee_mis"});
  unused(o.light_selection.has_value(), "--light-selection", "light, mis and nee_mis", {"light", "mis", "nee_mis"});
  return out;
}

}  // namespace lumis
