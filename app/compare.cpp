// `lumis compare [SCENE]`: the pipeline behind compare.h. Exit codes: 0 done, 1 scene or I/O error, 2 usage error.
#include "app/compare.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/commands.h"
#include "app/compare_internal.h"
#include "app/diff.h"
#include "app/memory_check.h"
#include "app/montage.h"
#include "app/plot.h"
#include "app/scene_error.h"
#include "app/scene_loader.h"
#include "core/image_io.h"
#include "integrators/render.h"

namespace lumis {

namespace fs = std::filesystem;

namespace {

// Keeps only the R, G, B channels (montage, PNG and metrics need nothing else).
Image rgb_only(const Image& img) {
  const std::vector<int> c = rgb_channels(img, "image");
  Image out(img.width, img.height, {"R", "G", "B"});
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = img.at(x, y, c[k]);
  return out;
}

std::string timing(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, seconds < 10 ? "%.2fS" : "%.0fS", seconds);
  return buf;
}

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

}  // namespace

int run_compare(const CompareArgs& args) {
  const std::string scene_path = args.scene.empty() ? default_scene_path() : args.scene;
  const fs::path dir = args.output.empty() ? fs::path("compare-" + fs::path(scene_path).stem().string())
                                           : fs::path(args.output);
  std::unique_ptr<Scene> scene;
  std::vector<std::string> names;
  std::optional<CropRect> crop;
  try {
    if (args.overrides.integrator) throw UsageError("compare: use --integrators (a list), not --integrator");
    if (args.overrides.spp && args.overrides.time && *args.overrides.time > 0)
      throw UsageError("compare: --spp and --time both given; the variants are compared at equal samples (--spp) "
                       "or at equal time (--time), not both");
    if (const std::string problem = output_folder_problem(dir); !problem.empty())
      throw UsageError("compare: -o " + dir.string() + ": " + problem + " (give a folder for the outputs)");
    names = parse_integrator_list(args.integrators);
    std::error_code ec;
    if (!args.reference.empty())
      for (const std::string& f : output_file_names(names))
        if (fs::equivalent(dir / f, args.reference, ec))
          throw UsageError("compare: --reference " + args.reference + " is the " + f + " this run writes in " +
                           dir.string() + "; copy it elsewhere or give another -o");
    scene = load_scene(scene_path, SceneLoadOptions{args.overrides.camera,
                                                    args.overrides.width && args.overrides.height});
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
  // A rendered reference is nee_mis with these options (and they are in its cache key): an option nee_mis reads is
  // used then, whatever the variants.
  std::vector<std::string> users = names;
  if (args.reference.empty()) users.push_back("nee_mis");
  for (const std::string& w : unused_overrides(args.overrides, users))
    std::cerr << "lumis compare: warning: " << w << "\n";
  if (!args.reference.empty() && args.reference_spp)
    std::cerr << "lumis compare: warning: --reference-spp only affects a rendered reference; ignored with --reference\n";
  const RenderSettings base = scene->settings;
  const bool equal_time = base.time_budget > 0;
  auto log = [&](const std::string& line) {
    if (!args.quiet) std::cerr << "compare: " << line << "\n";
  };

  CompareReport report;
  report.scene = scene_path;
  report.width = base.width;
  report.height = base.height;
  report.equal_time = equal_time;
  report.spp = base.spp;
  report.time_budget = base.time_budget;
  report.settings = base;
  report.camera = args.overrides.camera;
  report.crop = crop;
  // The folders this run creates, DIR and any missing parents (innermost first): a failure removes those it leaves
  // empty, so that `-o a/b/out` leaves no empty a/b behind.
  std::vector<fs::path> created;
  int rc = 0;
  try {
    // Reference: a given file (checked before DIR is created), or nee_mis at many samples, cached by a hash of
    // everything it depends on.
    Image reference;
    if (!args.reference.empty()) reference = read_reference(args.reference, base, scene_path);
    for (fs::path p = dir; !p.empty() && !fs::exists(fs::symlink_status(p)); p = p.parent_path()) {
      created.push_back(p);
      if (p == p.parent_path()) break;
    }
    fs::create_directories(dir);
    // Before any rendering: a folder that cannot be written in fails now, not after the reference.
    if (::access(dir.c_str(), W_OK) != 0)
      throw std::runtime_error(dir.string() + ": cannot write in this folder (" + std::strerror(errno) + ")");
    // A report from an earlier run would describe images this run replaces: removed first, so that a run that
    // fails part way leaves no report (the cached reference stays).
    for (const char* f : {"report.json", "report.md", "index.html"}) fs::remove(dir / f);
    if (args.reference.empty()) reference = cached_reference(*scene, args, base, scene_path, dir, report, log);
    else report.reference_source = args.reference;
    WriteOptions display;
    display.exposure = base.exposure;
    write_image((dir / report.reference_png).string(), reference, display);

    // Variants.
    std::vector<Image> images;
    for (const std::string& name : names) {
      RenderSettings s = base;
      s.integrator = name;
      Rendered r = render_variant(*scene, s, base.spp, base.time_budget);
      VariantResult v;
      v.name = name;
      v.spp = r.stats.spp;
      v.seconds = r.stats.seconds;
      v.samples = r.stats.samples;
      v.rays = r.stats.rays;
      DiffOptions dopt{name, "reference"};
      const DiffMetrics m = compute_metrics(r.image, reference, dopt);
      v.mse = m.mse;
      v.rel_mse = m.rel_mse;
      v.mae = m.mae;
      v.exr = name + ".exr";
      v.png = name + ".png";
      v.error_png = "error-" + name + ".png";
      write_image((dir / v.exr).string(), r.image);
      write_image((dir / v.png).string(), r.image, display);
      char line[160];
      std::snprintf(line, sizeof line, "%-8s %6u spp %8.3f s  relMSE %.4g  MSE %.4g", name.c_str(), v.spp, v.seconds,
                    v.rel_mse, v.mse);
      log(line);
      if (args.convergence) {
        // Doubling sample counts, ending at what the comparison used (in equal-time mode: what fitted in the
        // budget), also when that is not a power of two: 12 spp gives 1, 2, 4, 8, 12.
        const uint32_t last = std::max(1u, v.spp);
        for (uint32_t n = 1;; n = 2 * uint64_t(n) < last ? 2 * n : last) {
          Rendered c = render_variant(*scene, s, n, 0);
          const DiffMetrics cm = compute_metrics(c.image, reference, dopt);
          v.convergence.push_back({n, c.stats.seconds, cm.mse, cm.rel_mse});
          if (n == last) break;
        }
      }
      images.push_back(rgb_only(r.image));
      report.variants.push_back(std::move(v));
    }
    scene->settings = base;
    // Said, not hidden: a variant that took kTimedRenderSpp before the budget ran out (it did not get equal time), and
    // at equal time a fast variant that outran the reference's 16 x spp: the reference's own noise then sets a floor
    // under its relMSE (and efficiency falls with the budget); --reference-spp raises it.
    for (const VariantResult& v : report.variants) {
      if (equal_time && v.spp >= kTimedRenderSpp)
        std::cerr << "lumis compare: warning: " << v.name << " reached " << kTimedRenderSpp
                  << " spp, the most a timed render takes, in " << v.seconds << " s of the "
                  << base.time_budget << " s budget: not equal time; use --spp, or a larger image\n";
      if (report.reference_spp > 0 && v.spp > report.reference_spp)
        std::cerr << "lumis compare: warning: " << v.name << " rendered " << v.spp << " spp, more than the reference's "
                  << report.reference_spp << ": its error is partly the reference's noise; raise --reference-spp\n";
    }

    // Error pictures on one shared scale.
    std::vector<std::vector<float>> maps;
    for (const Image& img : images) maps.push_back(abs_error_map(img, reference));
    report.error_scale = shared_error_scale(maps);
    for (size_t i = 0; i < images.size(); ++i)
      write_image((dir / report.variants[i].error_png).string(),
                  error_heatmap(maps[i], base.width, base.height, 0, report.error_scale,
                                "|" + report.variants[i].name + " - REF|"));

    // Montage: variants, then the reference.
    const Image ref_rgb = rgb_only(reference);
    std::vector<MontageTile> tiles;
    for (size_t i = 0; i < images.size(); ++i) {
      const VariantResult& v = report.variants[i];
      tiles.push_back({&images[i],
                       {v.name, std::to_string(v.spp) + " SPP " + timing(v.seconds), "RELMSE " + short_number(v.rel_mse)}});
    }
    tiles.push_back({&ref_rgb,
                     {"REFERENCE", report.reference_spp ? std::to_string(report.reference_spp) + " SPP" : "FILE", ""}});
    MontageOptions mo;
    mo.exposure = base.exposure;
    if (crop) mo.crop_x = crop->x, mo.crop_y = crop->y, mo.crop_w = crop->w, mo.crop_h = crop->h;
    write_image((dir / report.montage).string(), make_montage(tiles, mo));

    if (args.convergence) {
      std::vector<PlotSeries> series;
      for (size_t i = 0; i < report.variants.size(); ++i) {
        PlotSeries ps{report.variants[i].name, series_colour(static_cast<int>(i)), {}};
        for (const ConvergencePoint& p : report.variants[i].convergence) ps.points.push_back({p.seconds, p.rel_mse});
        series.push_back(std::move(ps));
      }
      report.convergence_png = "convergence.png";
      write_image((dir / report.convergence_png).string(), plot_loglog(series, "TIME (S)", "RELMSE"));
    }

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
  log("wrote " + (dir / "index.html").string() + ", report.md, report.json, montage.png");
  if (!args.quiet) std::cout << report_markdown(report);
  return 0;
}

}  // namespace lumis
