// `lumis render [SCENE] [-o OUT] [options]`.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/cli.h"
#include "app/scene_error.h"
#include "app/scene_loader.h"
#include "core/image_io.h"
#include "integrators/render.h"

namespace lumis {

namespace {

std::atomic<bool> g_interrupted{false};
void on_sigint(int) { g_interrupted.store(true); }

std::string format_count(double v) {
  char buf[32];
  if (v >= 1e9) std::snprintf(buf, sizeof buf, "%.2fG", v / 1e9);
  else if (v >= 1e6) std::snprintf(buf, sizeof buf, "%.2fM", v / 1e6);
  else if (v >= 1e3) std::snprintf(buf, sizeof buf, "%.1fk", v / 1e3);
  else std::snprintf(buf, sizeof buf, "%.0f", v);
  return buf;
}

struct RenderArgs {
  std::string scene;
  std::string output;
  RenderOverrides overrides;
  bool quiet = false;
  bool aov_albedo = false, aov_normal = false, aov_depth = false;
};

int run_render(const RenderArgs& args) {
  const std::string scene_path = args.scene.empty() ? default_scene_path() : args.scene;
  std::unique_ptr<Scene> scene;
  try {
    scene = load_scene(scene_path);
    apply_overrides(args.overrides, scene->settings);
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
  RenderSettings& s = scene->settings;
  std::string out = args.output;
  if (out.empty()) out = std::filesystem::path(scene_path).stem().string() + ".png";
  const std::string ext = std::filesystem::path(out).extension().string();
  if (ext != ".exr" && ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".hdr") {
    std::cerr << "lumis: " << out << ": unsupported output format '" << ext << "' (use .exr, .png, .jpg or .hdr)\n";
    return 2;
  }
  std::unique_ptr<Integrator> integrator;
  try {
    integrator = make_integrator(s);
  } catch (const std::invalid_argument& e) {
    std::cerr << "lumis: " << e.what() << "\n";
    return 2;
  }

  Film film(s.width, s.height, FilmOptions{args.aov_albedo, args.aov_normal, args.aov_depth, true});
  RenderOptions ro;
  ro.spp = s.time_budget > 0 && !args.overrides.spp ? (1u << 20) : s.spp;
  ro.time_budget = s.time_budget;
  ro.threads = s.threads;
  ro.cancel = &g_interrupted;
  const bool tty = stderr_is_tty() && !args.quiet;
  if (tty) {
    ro.on_progress = [&](const RenderProgress& p) {
      const double frac = p.samples_total ? static_cast<double>(p.samples_done) / p.samples_total : 1;
      const double eta = frac > 0 ? p.elapsed * (1 - frac) / frac : 0;
      const int bar = 30, filled = static_cast<int>(frac * bar);
      std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  %.1fs elapsed  ETA %.1fs  %s samples/s   ", filled,
                   "##############################", bar - filled, "", 100 * frac, p.elapsed, eta,
                   format_count(p.samples_done / std::max(p.elapsed, 1e-9)).c_str());
    };
  }
  std::signal(SIGINT, on_sigint);
  const RenderStats st = render(*scene, *integrator, film, ro);
  std::signal(SIGINT, SIG_DFL);
  if (tty) std::fprintf(stderr, "\n");

  try {
    WriteOptions wo;
    wo.exposure = s.exposure;
    write_image(out, film.to_image(), wo);
  } catch (const std::exception& e) {
    std::cerr << "lumis: " << e.what() << "\n";
    return 1;
  }
  if (!args.quiet) {
    std::fprintf(stderr, "%s: %dx%d, %s, %u spp in %.2f s, %s samples/s, %s rays/s%s -> %s\n", scene_path.c_str(),
                 s.width, s.height, integrator->name(), st.spp, st.seconds,
                 format_count(st.samples / std::max(st.seconds, 1e-9)).c_str(),
                 format_count(st.rays / std::max(st.seconds, 1e-9)).c_str(),
                 st.stopped_early ? (g_interrupted ? " (interrupted)" : " (time budget)") : "", out.c_str());
    if (st.dropped) std::fprintf(stderr, "lumis: warning: %llu non-finite samples dropped\n",
                                 static_cast<unsigned long long>(st.dropped));
  }
  return g_interrupted ? 130 : 0;
}

}  // namespace

bool stderr_is_tty() { return isatty(fileno(stderr)) != 0; }

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

void register_render_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene (lumis JSON, .gltf or .glb) to an image");
  cmd->add_option("scene", args->scene, "Scene file (default: the built-in Cornell box, scenes/cornell-sphere.json)");
  cmd->add_option("-o,--output", args->output,
                  "Output image: .exr (linear, with variance channels), .png/.jpg (sRGB), .hdr "
                  "(default: <scene name>.png)");
  add_render_overrides(*cmd, args->overrides);
  cmd->add_flag("-q,--quiet", args->quiet, "No progress or summary on stderr");
  cmd->add_flag("--aov-albedo", args->aov_albedo, "Add albedo.R/G/B channels (EXR)");
  cmd->add_flag("--aov-normal", args->aov_normal, "Add N.X/Y/Z shading-normal channels (EXR)");
  cmd->add_flag("--aov-depth", args->aov_depth, "Add a Z channel with first-hit distance (EXR)");
  cmd->callback([args, &exit_code] { exit_code = run_render(*args); });
}

}  // namespace lumis
