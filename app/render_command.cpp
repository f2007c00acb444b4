// `lumis render [SCENE] [-o OUT] [options]`.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/memory_check.h"
#include "app/scene_error.h"
#include "app/scene_loader.h"
#include "core/file_ext.h"
#include "core/image_io.h"
#include "integrators/integrator.h"
#include "integrators/render.h"

namespace lumis {

namespace {

// Ctrl-C (SIGINT) and SIGTERM (what batch schedulers and `kill` send) stop the render at a sample boundary; the
// image rendered so far is written and the exit code is 128 + the signal, as a shell reports a killed command.
std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};
void on_stop_signal(int sig) {
  g_signal.store(sig);
  g_interrupted.store(true);
}

std::string format_count(double v) {
  char buf[32];
  if (v >= 1e9) std::snprintf(buf, sizeof buf, "%.2fG", v / 1e9);
  else if (v >= 1e6) std::snprintf(buf, sizeof buf, "%.2fM", v / 1e6);
  else if (v >= 1e3) std::snprintf(buf, sizeof buf, "%.1fk", v / 1e3);
  else std::snprintf(buf, sizeof buf, "%.0f", v);
  return buf;
}

bool stderr_is_tty() { return isatty(fileno(stderr)) != 0; }

}  // namespace

int run_render(const RenderArgs& args) {
  const std::string scene_path = args.scene.empty() ? default_scene_path() : args.scene;
  // The output is checked before anything is loaded or rendered, so that no work is lost to a typo in -o.
  std::string out = args.output;
  if (out.empty()) out = std::filesystem::path(scene_path).stem().string() + ".png";
  const std::string ext = lower_extension(out);  // .PNG as .png
  if (const std::string problem = image_output_problem(out); !problem.empty()) {
    std::cerr << "lumis: " << out << ": " << problem << "\n";
    return 2;
  }
  if (ext != ".exr" && (args.aov_albedo || args.aov_normal || args.aov_depth)) {
    std::vector<std::string> given;  // the flags given, not all three
    if (args.aov_albedo) given.push_back("--aov-albedo");
    if (args.aov_normal) given.push_back("--aov-normal");
    if (args.aov_depth) given.push_back("--aov-depth");
    std::string list = given[0];
    for (size_t i = 1; i < given.size(); ++i) list += (i + 1 == given.size() ? " and " : ", ") + given[i];
    std::cerr << "lumis: " << out << ": " << list << (given.size() == 1 ? " adds" : " add")
              << " EXR channels; write an .exr to keep them\n";
    return 2;
  }
  std::unique_ptr<Scene> scene;
  try {
    scene = load_scene(scene_path, SceneLoadOptions{args.overrides.camera,
                                                    args.overrides.width || args.overrides.height});
    apply_overrides(args.overrides, *scene);
    scene->update_light_selector();
  } catch (const SceneError& e) {
    std::cerr << "lumis: " << e.what() << "\n";
    return 1;
  } catch (const std::invalid_argument& e) {
    std::cerr << "lumis: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "lumis: " << scene_path << ": " << e.what() << "\n";
    return 1;
  }
  // The files the scene reads (an environment map, a texture, a glTF file or buffer) are known only now: -o must not
  // replace one of them, nor the scene file itself.
  if (const std::string file = scene_file_at(out, scene_path, *scene); !file.empty()) {
    std::cerr << "lumis: " << out << ": is " << file << "; write the render elsewhere\n";
    return 2;
  }
  RenderSettings& s = scene->settings;
  for (const std::string& w : unused_overrides(args.overrides, {s.integrator}))
    std::cerr << "lumis: warning: " << w << "\n";
  if (finds_lights_by_hitting(s.integrator))
    for (const std::string& w : scene->small_lights) std::cerr << w << "\n";
  // Linear formats take no exposure; 0 (a script's default, `--exposure "${EV:-0}"`) changes nothing to warn of.
  if (args.overrides.exposure && *args.overrides.exposure != 0 && (ext == ".exr" || ext == ".hdr"))
    std::cerr << "lumis: warning: --exposure only affects .png, .jpg and .jpeg output; ignored for " << out << "\n";
  std::unique_ptr<Integrator> integrator;
  try {
    integrator = make_integrator(s);
  } catch (const std::invalid_argument& e) {
    std::cerr << "lumis: " << e.what() << "\n";
    return 2;
  }

  const FilmOptions film_options{args.aov_albedo, args.aov_normal, args.aov_depth, true};
  {
    // Fail before allocating rather than being killed half-way: an absurd resolution is an input error.
    const int channels = 6 + 3 * args.aov_albedo + 3 * args.aov_normal + args.aov_depth;
    const std::string problem = memory_problem(render_memory_estimate(s.width, s.height, channels), s.width,
                                               s.height, "render", "film and image");
    if (!problem.empty()) {
      std::cerr << "lumis: " << scene_path << ": " << problem << "\n";
      return 1;
    }
  }
  Film film(s.width, s.height, film_options);
  RenderOptions ro;
  const bool timed = s.time_budget > 0 && !args.overrides.spp;  // the budget, not a sample count, ends the render
  ro.spp = timed ? kTimedRenderSpp : s.spp;
  ro.time_budget = s.time_budget;
  ro.threads = s.threads;
  ro.cancel = &g_interrupted;
  const bool tty = stderr_is_tty() && !args.quiet;
  if (tty) {
    ro.on_progress = [&](const RenderProgress& p) {
      const double frac = p.fraction();  // of the time budget, for a timed render
      const double eta = frac > 0 ? p.elapsed * (1 - frac) / frac : 0;
      const int bar = 30, filled = static_cast<int>(frac * bar);
      std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  %.1fs elapsed  ETA %.1fs  %s samples/s   ", filled,
                   "##############################", bar - filled, "", 100 * frac, p.elapsed, eta,
                   format_count(p.samples_done / std::max(p.elapsed, 1e-9)).c_str());
    };
  }
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  const RenderStats st = render(*scene, *integrator, film, ro);
  if (tty) std::fprintf(stderr, "\n");

  try {
    WriteOptions wo;
    wo.exposure = s.exposure;
    // What the image is, so that a partial (interrupted or time-limited) render says how far it got.
    wo.metadata = {{"lumis:spp", std::to_string(st.spp)},
                   {"lumis:integrator", integrator->name()},
                   {"lumis:seed", std::to_string(s.seed)},
                   {"lumis:scene", scene_path},
                   {"lumis:dropped_samples", std::to_string(st.dropped)},
                   {"lumis:stopped", st.stopped_early ? (g_interrupted ? "interrupted" : "time budget")
                                     : timed && st.spp >= kTimedRenderSpp ? "sample cap"
                                                                          : "complete"},
                   {"Software", std::string("lumis ") + LUMIS_VERSION}};
    write_image(out, film.to_image(), wo);
  } catch (const std::exception& e) {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    std::cerr << "lumis: " << e.what() << "\n";
    return 1;
  }
  // Only now: a second signal during the write would otherwise leave a temporary file behind.
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (timed && st.spp >= kTimedRenderSpp)  // a warning: shown also with -q
    std::fprintf(stderr, "lumis: warning: stopped at %u spp, the most a timed render takes, after %.3g s of the %g s "
                 "budget\n", kTimedRenderSpp, st.seconds, s.time_budget);
  if (!args.quiet) {
    std::fprintf(stderr, "%s: %dx%d, %s, %u spp in %.2f s, %s samples/s, %s rays/s%s -> %s\n", scene_path.c_str(),
                 s.width, s.height, integrator->name(), st.spp, st.seconds,
                 format_count(st.samples / std::max(st.seconds, 1e-9)).c_str(),
                 format_count(st.rays / std::max(st.seconds, 1e-9)).c_str(),
                 st.stopped_early ? (g_interrupted ? " (interrupted)" : " (time budget)") : "", out.c_str());
  }
  // A warning even with -q: dropped samples bias the image.
  if (st.dropped) std::fprintf(stderr, "lumis: warning: %llu non-finite samples dropped\n",
                               static_cast<unsigned long long>(st.dropped));
  return g_interrupted ? 128 + g_signal.load() : 0;
}

std::string default_scene_path() {
  namespace fs = std::filesystem;
  const fs::path rel = fs::path("scenes") / "cornell-sphere.json";
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (fs::path dir = exe.parent_path(); !dir.empty() && dir != dir.root_path(); dir = dir.parent_path())
      if (fs::exists(dir / rel)) return (dir / rel).string();
  }
  return (fs::path(LUMIS_SOURCE_DIR) / rel).string();
}

}  // namespace lumis
