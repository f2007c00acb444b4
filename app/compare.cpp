// `lumis compare [SCENE]`: the pipeline behind compare.h. Exit codes: 0 done, 1 scene or I/O error, 2 usage error.
#include "app/compare.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/commands.h"
#include "app/compare_internal.h"
#include "app/diff.h"
#include "app/memory_check.h"
#include "app/scene_error.h"
#include "app/scene_loader.h"
#include "core/file_ext.h"
#include "core/image_io.h"
#include "integrators/integrator.h"
#include "integrators/render.h"

namespace lumis {

namespace fs = std::filesystem;

namespace {

// Why DIR cannot be the output folder, checked before any work: it, or the first part of it that exists, is not a
// folder. Empty when it can be used (created when missing).
std::string output_folder_problem(const fs::path& dir) {
  std::error_code ec;
  for (fs::path p = dir; !p.empty(); p = p.parent_path()) {
    if (fs::exists(p, ec)) {
      if (fs::is_directory(p, ec)) return "";
      return p == dir ? "exists and is not a folder" : p.string() + " is not a folder";
    }
    if (p == p.parent_path()) break;
  }
  return "";
}

// The files a run writes in its output folder (a given reference must not be one of them).
std::vector<std::string> output_file_names(const std::vector<std::string>& variants) {
  std::vector<std::string> out = {"reference.png", "montage.png", "convergence.png", "report.json", "report.md",
                                  "index.html"};
  for (const std::string& v : variants)
    for (const std::string& f : {v + ".exr", v + ".png", "error-" + v + ".png"}) out.push_back(f);
  return out;
}

// Everything checked before any work (usage, the output folder, a given reference's name, the scene and its memory).
// Returns 0 when the run can go on, else the exit code after printing why.
int prepare(const CompareArgs& args, const std::string& scene_path, const fs::path& dir, std::unique_ptr<Scene>& scene,
            std::vector<std::string>& names, std::optional<CropRect>& crop) {
  try {
    if (args.overrides.integrator) throw UsageError("compare: use --integrators (a list), not --integrator");
    if (args.overrides.spp && args.overrides.time && *args.overrides.time > 0)
      throw UsageError("compare: --spp and --time both given; the variants are compared at equal samples (--spp) "
                       "or at equal time (--time), not both");
    if (const std::string problem = output_folder_problem(dir); !problem.empty())
      throw UsageError("compare: -o " + dir.string() + ": " + problem + " (give a folder for the outputs)");
    names = parse_integrator_list(args.integrators);
    std::vector<std::string> outputs = output_file_names(names);
    if (args.reference.empty()) outputs.insert(outputs.end(), {"reference.exr", "reference.json"});
    std::error_code ec;
    // A folder, pipe or device where a file goes would fail its write only after every render (or, for a pipe,
    // be written to): refused up front, as render refuses its -o.
    for (const std::string& f : outputs)
      if (fs::exists(dir / f, ec) && !fs::is_regular_file(dir / f, ec)) {
        const bool folder = fs::is_directory(dir / f, ec);
        throw UsageError("compare: -o " + dir.string() + ": " + f + " there is " +
                         (folder ? "a folder" : "not a regular file (a pipe, device or socket)") +
                         ", where this run writes a file; remove it or give another -o");
      }
    // A link there is written through: its target must be writable too (a missing folder, a name too long), checked
    // as render checks its -o, or the write fails after every render.
    for (const std::string& f : outputs)
      if (fs::is_symlink(dir / f, ec))
        if (const std::string problem = output_file_problem((dir / f).string()); !problem.empty())
          throw UsageError("compare: -o " + dir.string() + ": " + f + " there " + problem);
    if (!args.reference.empty())
      for (const std::string& f : output_file_names(names))
        if (fs::equivalent(dir / f, args.reference, ec))
          throw UsageError("compare: --reference " + args.reference + " is the " + f + " this run writes in " +
                           dir.string() + "; copy it elsewhere or give another -o");
    scene = load_scene(scene_path, SceneLoadOptions{args.overrides.camera,
                                                    args.overrides.width || args.overrides.height});
    // Like render's -o: no file this run writes in DIR may be the scene file or a file the scene reads.
    for (const std::string& f : outputs)
      if (const std::string file = scene_file_at((dir / f).string(), scene_path, *scene); !file.empty())
        throw UsageError("compare: -o " + dir.string() + ": this run writes " + f + " there, which is " + file +
                         "; give another -o");
    apply_overrides(args.overrides, *scene);
    scene->update_light_selector();
    if (!args.crop.empty()) crop = parse_crop(args.crop, scene->settings.width, scene->settings.height);
    // Up front, like render: the film of one variant at a time, the reference, each variant's image and error map
    // kept for the montage, and the montage of them all with the writer's copy (RGB floats).
    const int w = scene->settings.width, h = scene->settings.height;
    const uint64_t pixels = uint64_t(w) * uint64_t(h), n = names.size();
    const uint64_t need = render_memory_estimate(w, h, 6) + pixels * (12 + 16 * n + 24 * (n + 1));
    const std::string what = "compare of " + std::to_string(n) + (n == 1 ? " variant" : " variants");
    if (const std::string problem = memory_problem(need, w, h, what, "films, images, error maps and montage");
        !problem.empty())
      throw std::runtime_error(problem);
  } catch (const SceneError& e) {
    std::cerr << "lumis compare: " << e.what() << "\n";
    return 1;
  } catch (const std::invalid_argument& e) {
    std::cerr << "lumis compare: " << e.what() << "\n";
    return 2;
  } catch (const UsageError& e) {
    std::cerr << "lumis " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "lumis compare: " << scene_path << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}

// Checks that DIR can be made and written in, recording in `created` the folders this run makes, DIR and any missing
// parents (innermost first), and removes them again until the first write: a failure, or a signal, leaves no empty
// a/b behind for `-o a/b/out`. Throws when DIR cannot be written in (before any rendering, not after the
// reference). A report from an earlier run would describe images this run replaces: removed first, so that a run
// that fails part way leaves no report (the cached reference stays).
void make_output_folder(const fs::path& dir, std::vector<fs::path>& created) {
  for (fs::path p = dir; !p.empty() && !fs::exists(fs::symlink_status(p)); p = p.parent_path()) {
    created.push_back(p);
    if (p == p.parent_path()) break;
  }
  fs::create_directories(dir);
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error(dir.string() + ": cannot write in this folder (" + std::strerror(errno) + ")");
  for (const char* f : {"report.json", "report.md", "index.html"}) fs::remove(dir / f);
  // Made again by the first write: a run stopped before it (Ctrl-C while the reference renders) leaves no empty
  // folders behind, as a failure does.
  std::error_code ec;
  for (const fs::path& p : created)
    if (fs::is_empty(p, ec)) fs::remove(p, ec);
}

}  // namespace

int run_compare(const CompareArgs& args) {
  const std::string scene_path = args.scene.empty() ? default_scene_path() : args.scene;
  const fs::path dir = args.output.empty() ? fs::path("compare-" + fs::path(scene_path).stem().string())
                                           : fs::path(args.output);
  std::unique_ptr<Scene> scene;
  std::vector<std::string> names;
  std::optional<CropRect> crop;
  if (const int rc = prepare(args, scene_path, dir, scene, names, crop); rc != 0) return rc;
  // A rendered reference is nee_mis with these options (and they are in its cache key): an option nee_mis reads is
  // used then, whatever the variants.
  for (const std::string& w : unused_overrides(args.overrides, names, args.reference.empty()))
    std::cerr << "lumis compare: warning: " << w << "\n";
  if (std::any_of(names.begin(), names.end(), finds_lights_by_hitting))
    for (const std::string& w : scene->small_lights) std::cerr << w << "\n";
  if (!args.reference.empty() && args.reference_spp)
    std::cerr << "lumis compare: warning: --reference-spp only affects a rendered reference; "
                 "ignored with --reference\n";
  const RenderSettings base = scene->settings;
  auto log = [&](const std::string& line) {
    if (!args.quiet) std::cerr << "compare: " << line << "\n";
  };

  CompareReport report;
  report.scene = scene_path;
  report.width = base.width;
  report.height = base.height;
  report.equal_time = base.time_budget > 0;
  report.spp = base.spp;
  report.time_budget = base.time_budget;
  report.settings = base;
  report.camera = args.overrides.camera;
  report.crop = crop;
  std::vector<fs::path> created;
  int rc = 0;
  try {
    // Reference: a given file (checked before DIR is created), or nee_mis at many samples, cached by a hash of
    // everything it depends on.
    Image reference;
    if (!args.reference.empty()) reference = read_reference(args.reference, base, scene_path);
    make_output_folder(dir, created);
    if (args.reference.empty()) reference = cached_reference(*scene, args, base, scene_path, dir, report, log);
    else {
      report.reference_source = args.reference;
      report.reference_grey = is_grey(reference);
    }
    WriteOptions display;
    display.exposure = base.exposure;
    fs::create_directories(dir);  // the first write of a given reference (make_output_folder left none)
    write_image((dir / report.reference_png).string(), reference, display);

    const std::vector<Image> images =
        render_variants(*scene, names, base, reference, args.convergence, dir, report, log);
    write_pictures(images, reference, base, args.convergence, dir, report);
    write_text(dir / "report.json", report_json(report).dump(2) + "\n");
    write_text(dir / "report.md", report_markdown(report));
    write_text(dir / "index.html", report_html(report));
  } catch (const UsageError& e) {
    std::cerr << "lumis " << e.what() << "\n";
    rc = 2;
  } catch (const DiffError& e) {
    std::cerr << "lumis compare: " << e.what() << "\n";
    rc = 2;
  } catch (const fs::filesystem_error& e) {
    std::cerr << "lumis compare: " << e.path1().string() << ": " << e.code().message() << "\n";
    rc = 1;
  } catch (const std::exception& e) {
    std::cerr << "lumis compare: " << e.what() << "\n";
    rc = 1;
  }
  if (rc != 0) {
    std::error_code ec;
    for (const fs::path& p : created)
      if (fs::is_empty(p, ec)) fs::remove(p, ec);
    return rc;
  }
  log("wrote " + (dir / "index.html").string() + ", report.md, report.json, montage.png" +
      (args.convergence ? ", convergence.png" : ""));
  if (!args.quiet) std::cout << report_markdown(report);
  return 0;
}

}  // namespace lumis
