// lumis's command line: the one file that includes CLI11 (Debian's 2.1.2 is header-only and costs about 11 s of
// compile time in every file that includes it). It turns argv into the commands' argument structs (app/commands.h),
// runs the chosen command and returns its exit code.
#include "app/cli.h"

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <exception>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <system_error>

#include <CLI/CLI.hpp>

#include "app/cli_checks.h"
#include "app/commands.h"
#include "app/diff.h"
#include "app/warptest.h"
#include "core/file_ext.h"

namespace lumis {

namespace {

/// CLI11 check that a number option is finite: CLI::Range lets NaN through (every comparison with it is false).
const CLI::Validator kFiniteNumber(finite_problem, "FINITE");

/// CLI11 check for a file or name argument (empty_problem).
CLI::Validator non_empty(const std::string& expected) {
  return CLI::Validator([expected](std::string& text) { return empty_problem(text, expected); }, "NONEMPTY");
}
const CLI::Validator kNonEmpty = non_empty("a file name");

/// CLI11 check that a number lies in [lo, hi], with a message that says so in the option's own terms (CLI::Range
/// prints its bounds with six decimals, or as the largest double when there is no upper bound).
CLI::Validator number_in(double lo, double hi, const std::string& expected) {
  return CLI::Validator([=](std::string& text) { return range_problem(text, lo, hi, expected); }, expected);
}

/// CLI11 check of a whole number in [lo, hi]: CLI::Range calls 1e3 or 1.5 "not in range" when they are no integer.
CLI::Validator whole_in(long long lo, long long hi) {
  return CLI::Validator(
      [=](std::string& text) {
        std::string problem = whole_problem(text, lo, hi);
        // The value checked is decimal; CLI11 converts with base 0, where "010" is octal 8: hand it the number read
        // (a transform, which may rewrite the text; a check may not).
        if (problem.empty()) text = std::to_string(std::stoll(text));
        return problem;
      },
      "INT in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

/// The render options that override the scene file (render, compare and bench).
void add_render_overrides(CLI::App& cmd, RenderOverrides& o) {
  cmd.add_option("--spp", o.spp, "Samples per pixel (given alone, it overrides a scene file's time budget)")
      ->transform(whole_in(1, 1 << 30));
  cmd.add_option("--integrator", o.integrator, "uniform | bsdf | light | mis | nee_mis");
  cmd.add_option("--max-depth", o.max_depth, "Scattering vertices per path (1 = direct lighting only)")
      ->transform(whole_in(1, 1024));
  cmd.add_option("--rr-depth", o.rr_depth, "Russian roulette from this depth on (0 = off)")
      ->transform(whole_in(0, 1024));
  cmd.add_option("--seed", o.seed, "Random seed, in [0, 4294967295]")
      ->transform(whole_in(0, 4294967295));
  cmd.add_option("--threads", o.threads, "Worker threads (default: all cores)")->transform(whole_in(1, 1024));
  cmd.add_option("--width", o.width, "Image width in pixels (alone: the height keeps the scene's aspect ratio)")
      ->transform(whole_in(1, kMaxImageSide));
  cmd.add_option("--height", o.height, "Image height in pixels (alone: the width keeps the scene's aspect ratio)")
      ->transform(whole_in(1, kMaxImageSide));
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
            double v = 0;
            if (!read_number(text, v) || !(v >= 0 && v < 1)) return "expected a probability in [0, 1), found " + text;
            // Tested as the float it is kept in too: 0.99999999999 rounds to 1.
            if (!(static_cast<float>(v) < 1))
              return "expected a probability in [0, 1), found " + text + ", which is 1 as the 32-bit float it is "
                     "kept in";
            return {};
          },
          "in [0, 1)"));
  cmd.add_option("--uniform-measure", o.uniform_measure, "theta-phi | solid-angle (for --integrator uniform)");
  cmd.add_option("--time", o.time, "Stop after this many seconds (writes what was rendered; 0 = no time budget)")
      ->check(kFiniteNumber)
      ->check(number_in(0, 1e7, "a number of seconds in [0, 1e7]"));
  cmd.add_option("--exposure", o.exposure, "Exposure in stops for PNG/JPG output")
      ->check(kFiniteNumber)
      ->check(number_in(-64, 64, "a number in [-64, 64]"));
}

/// --camera (render and compare: the commands that load one scene).
void add_camera_option(CLI::App& cmd, RenderOverrides& o) {
  cmd.add_option("--camera", o.camera,
                 "For a glTF file: the camera to render through, by number (0 = the first, the default) or by name; "
                 "an unknown one lists those the file has")
      ->check(non_empty("a camera number or name"));
}

void register_render_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene (lumis JSON, .gltf or .glb) to an image");
  cmd->footer(scene_defaults_text());
  cmd->add_option("scene", args->scene, "Scene file (default: the built-in Cornell box, scenes/cornell-sphere.json)")
      ->check(kNonEmpty);
  cmd->add_option("-o,--output", args->output,
                  "Output image: .exr (linear, with variance channels), .png/.jpg/.jpeg (sRGB), .hdr, in any case "
                  "(default: <scene name>.png)")
      ->check(kNonEmpty);
  add_render_overrides(*cmd, args->overrides);
  add_camera_option(*cmd, args->overrides);
  cmd->add_flag("-q,--quiet", args->quiet, "No progress or summary on stderr");
  cmd->add_flag("--aov-albedo", args->aov_albedo, "Add albedo.R/G/B channels (EXR)");
  cmd->add_flag("--aov-normal", args->aov_normal, "Add N.X/Y/Z shading-normal channels (EXR)");
  cmd->add_flag("--aov-depth", args->aov_depth, "Add a Z channel with first-hit distance (EXR)");
  cmd->callback([args, &exit_code] { exit_code = run_render(*args); });
}

void register_warptest_command(CLI::App& app, int& exit_code) {
  struct Args {
    std::string name, out = "warptest.png";
    double param = NAN;
    uint64_t samples = 1'000'000;
  };
  auto args = std::make_shared<Args>();
  std::string names;
  for (const auto& n : warptest_names()) names += (names.empty() ? "" : ", ") + n;
  CLI::App* cmd = app.add_subcommand(
      "warptest", "Chi-square test of a sampling routine against its pdf, with a picture of both histograms");
  // Not required: without one, run_warptest lists the names (CLI11 would say only "name is required").
  cmd->add_option("name", args->name, "Warp to test: " + names)->check(non_empty("a warp name"));
  cmd->add_option("--param", args->param,
                  "cos_max in (-1, 1) for spherical_cap, alpha in (0, 1] for ggx_* (default: 0.9, 0.3; the test "
                  "decides for cos_max up to 0.9999 and alpha from 1e-19)")
      ->check(kFiniteNumber);
  // The chi-square test needs cells that expect 5 samples or more: uniform_sphere's 3200 equal cells need 16,000
  // samples; from 100,000 on, every warp at its default parameter has hundreds of such cells.
  cmd->add_option("--samples", args->samples, "Number of samples")
      ->transform(whole_in(100'000, 1'000'000'000))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->out, "Histogram picture (PNG; .exr, .jpg and .hdr also work), '' for none")
      ->capture_default_str();
  cmd->callback([args, &exit_code] {
    const int rc = run_warptest(args->name, args->param, args->samples, args->out, std::cout, std::cerr);
    exit_code = rc == 2 ? 2 : (rc == 0 ? 0 : 1);
  });
}

void register_diff_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DiffArgs>();
  CLI::App* cmd = app.add_subcommand(
      "diff", "Compare image A with reference B: error metrics, threshold check, z-test, heatmap (exit 0 pass, "
              "1 fail, 2 error)");
  cmd->add_option("A", args->a, "Test image")->required()->check(kNonEmpty);
  cmd->add_option("B", args->b, "Reference image")->required()->check(kNonEmpty);
  CLI::Option* metric = cmd->add_option("--metric", args->metric, "Metric that --threshold applies to")
                            ->check(non_empty("a metric name"))
                            ->check(CLI::IsMember(metric_names()))
                            ->capture_default_str();
  cmd->add_option("--threshold", args->threshold,
                  "Fail (exit 1) when the metric exceeds this value (psnr: when it is below)")
      ->check(kFiniteNumber);
  cmd->add_option("--tolerance", args->tolerance, "Absolute error per channel for the 'over' metric")
      ->check(kFiniteNumber)
      ->check(number_in(0, std::numeric_limits<double>::max(), "a number >= 0"))
      ->capture_default_str();
  cmd->add_option("--psnr-peak", args->psnr_peak,
                  "PSNR peak: a positive number, or 'max' for the reference's largest value")
      ->capture_default_str();
  cmd->add_option("--heatmap", args->heatmap, "Write a false-colour picture of the per-pixel error (PNG/EXR)")
      ->check(kNonEmpty);
  cmd->add_flag("--json", args->json, "Print the metrics as JSON on stdout");
  cmd->add_flag("--z-test", args->z_test,
                "Per-pixel z-test against B's variance channels (plus A's when present); fail on any rejection");
  CLI::Option* alpha = cmd->add_option("--alpha", args->alpha, "Family-wise significance level of the z-test")
                           ->check(kFiniteNumber)
                           ->check(number_in(1e-12, 0.5, "a significance level in [1e-12, 0.5]"))
                           ->capture_default_str();
  cmd->callback([args, metric, alpha, &exit_code] {
    args->metric_given = metric->count() > 0;
    args->alpha_given = alpha->count() > 0;
    exit_code = run_diff(*args);
  });
}

void register_compare_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Render a scene with several integrators at equal spp (--spp) or equal time (--time) and compare "
                 "them with a reference");
  cmd->add_option("scene", args->scene, "Scene file (default: the built-in Cornell box)")->check(kNonEmpty);
  cmd->add_option("-o,--output", args->output, "Output folder (default: compare-<scene name>)")
      ->check(non_empty("a folder name"));
  cmd->add_option("--integrators", args->integrators, "Comma-separated variants to compare")
      ->check(non_empty("names separated by commas"))
      ->capture_default_str();
  cmd->add_option("--reference", args->reference,
                  "Reference image (EXR or HDR; PNG or JPEG decoded from sRGB; R, G, B or grey) instead of "
                  "rendering one")
      ->check(kNonEmpty);
  cmd->add_option("--reference-spp", args->reference_spp,
                  "Samples per pixel of the rendered nee_mis reference (default: 16 x spp, at least 256)")
      ->transform(whole_in(1, 1 << 30));
  cmd->add_option("--crop", args->crop, "x,y,w,h: add a row of zoomed crops of this region to montage.png")
      ->check(non_empty("x,y,w,h"));
  cmd->add_flag("--convergence", args->convergence,
                "Also render each variant at 1, 2, 4, ... spp up to its own and plot error against time "
                "(convergence.png)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress on stderr and no table on stdout");
  add_render_overrides(*cmd, args->overrides);
  add_camera_option(*cmd, args->overrides);
  // The shared render options, worded for compare. --integrator stays registered only to refuse it helpfully.
  cmd->get_option("--integrator")->group("");
  cmd->get_option("--spp")->description("Equal samples: samples per pixel of every variant (default: the scene's)");
  cmd->get_option("--time")->description(
      "Equal time: every variant renders for this many seconds, in whole passes (instead of --spp; 0 = none)");
  cmd->get_option("--mis-light-probability")
      ->description("For the mis variant: probability c_l of the light strategy, in [0, 1) (default 0.5)");
  cmd->get_option("--uniform-measure")->description("theta-phi | solid-angle (for the uniform variant)");
  cmd->callback([args, &exit_code] { exit_code = run_compare(*args); });
}

void register_bench_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<BenchArgs>();
  BenchOptions& o = a->options;
  CLI::App* cmd = app.add_subcommand(
      "bench", "Measure samples/s and rays/s of every integrator against Embree's raw ray throughput");
  cmd->add_option("scenes", o.scenes,
                  "Scene files, or @large for the generated 1M-triangle room (default: @large, cornell-sphere, "
                  "veach-mis, night-lights and the largest shared glTF models where found)")
      ->check(kNonEmpty);
  cmd->add_option("--json", o.json_out, "Write the results as JSON to this file")->check(kNonEmpty);
  CLI::Option* repeat =
      cmd->add_option("--repeat", o.repeat, "Repetitions; every figure is their median (default 3; 1 with --quick)")
          ->transform(whole_in(1, 100));
  cmd->add_flag("--quick", o.quick,
                "Tiny settings (32x32, 1 spp, 1 repetition, small raw-ray batches, a 20k-triangle @large; of the "
                "default scenes only @large and cornell-sphere): a smoke test, not a measurement");
  cmd->add_option("--assets", o.assets_dir, "Shared assets folder with gltf/ (default: <source>/../shared/assets)")
      ->check(non_empty("a folder"))
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--large-triangles", o.large_triangles,
                  "Triangles in the generated scene, at least (default 1000000; 20000 with --quick)")
      ->transform(whole_in(100, 100'000'000));
  cmd->add_option("--raw-rays", o.raw_rays, "Rays per kind for the raw Embree measurement (default 524288)")
      ->transform(whole_in(16, 1 << 26));
  cmd->add_option("--write-large-scene", a->write_large,
                  "Only write the generated large scene to this .glb (with --large-triangles) and exit")
      ->check(CLI::Validator(
          [](std::string& path) -> std::string {
            if (lower_extension(path) == ".glb") return "";  // .GLB too
            return "expected a .glb file name, found " + (path.empty() ? "an empty string" : path);
          },
          "FILE.glb"));
  add_render_overrides(*cmd, o.overrides);
  // Registered only to be refused by name (run_bench): bench renders a fixed spp, writes no image and measures
  // through each scene's default camera.
  cmd->get_option("--time")->group("");
  cmd->get_option("--exposure")->group("");
  add_camera_option(*cmd, o.overrides);
  cmd->get_option("--camera")->group("");
  cmd->get_option("--spp")->description("Samples per pixel of every render (default 4; 1 with --quick)");
  // Every scene is measured at bench's own square size, whatever its camera's aspect ratio.
  cmd->get_option("--width")->description("Image width in pixels (default 256; 32 with --quick; alone: square)");
  cmd->get_option("--height")->description("Image height in pixels (default 256; 32 with --quick; alone: square)");
  cmd->get_option("--threads")->description("Worker threads (default: all cores; more than the cores are capped)");
  cmd->callback([a, cmd, repeat, &exit_code] {
    // --write-large-scene writes the room and exits: any other option but the room's size would go unused.
    if (!a->write_large.empty()) {
      for (const CLI::Option* opt : cmd->get_options()) {
        // (get_name() is empty for the options hidden above.)
        const std::string name = opt->get_lnames().empty() ? "a scene" : "--" + opt->get_lnames().front();
        if (opt->count() && name != "--write-large-scene" && name != "--large-triangles") {
          std::cerr << "lumis: bench: --write-large-scene only writes the generated room and exits (with "
                    << "--large-triangles); " << name << " does not apply\n";
          exit_code = 2;
          return;
        }
      }
    }
    if (a->options.quick && repeat->count() == 0) a->options.repeat = 1;
    exit_code = run_bench_command(*a);
  });
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{"lumis: an offline path tracer built on the importance-sampling lecture's estimators"};
  app.set_version_flag("--version", std::string("lumis ") + LUMIS_VERSION);
  app.require_subcommand(1);
  // Usage errors start with "lumis: ", as every other message does.
  app.failure_message([](const CLI::App* a, const CLI::Error& e) {
    return "lumis: " + reword_cli11(CLI::FailureMessage::simple(a, e));
  });
  // Past a file-size limit (ulimit -f), a write fails with EFBIG and lumis names the file; the default action of
  // SIGXFSZ would instead kill it with a core dump and leave its temporary file behind.
  std::signal(SIGXFSZ, SIG_IGN);
  int exit_code = 0;
  register_render_command(app, exit_code);
  register_warptest_command(app, exit_code);
  register_diff_command(app, exit_code);
  register_compare_command(app, exit_code);
  register_bench_command(app, exit_code);
  // An unknown command is named with the valid ones (CLI11 would say only "A subcommand is required").
  std::vector<std::string> commands;
  for (const CLI::App* c : app.get_subcommands([](const CLI::App*) { return true; })) commands.push_back(c->get_name());
  if (const std::string problem = unknown_command_problem(argc, argv, commands); !problem.empty()) {
    std::cerr << "lumis: " << problem << "\n";
    return 2;
  }
  try {  // --help's text is output too: lost to a full disk, it is no success either (checked below)
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    exit_code = app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    exit_code = app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    exit_code = app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  // Output lost to a full disk (`lumis diff --json > metrics.json`) must not pass for success, as in coreutils.
  // diff's errors exit 2, since its 1 means "the images differ"; every other command's I/O errors exit 1.
  errno = 0;
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
    const std::string why = errno ? ": " + std::generic_category().message(errno) : "";
    std::cerr << "lumis: cannot write the standard output" << why << "\n";
    return app.got_subcommand("diff") ? 2 : 1;
  }
  return exit_code;
}

}  // namespace lumis
