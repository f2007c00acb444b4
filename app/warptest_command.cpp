// `lumis warptest NAME [--param P] [--samples N] [-o OUT.png]`.
#include <cmath>
#include <iostream>

#include "app/cli.h"
#include "app/warptest.h"

namespace lumis {

void register_warptest_command(CLI::App& app, int& exit_code) {
  struct Args {
    std::string name, out = "warptest.png";
    float param = NAN;
    uint64_t samples = 1'000'000;
  };
  auto args = std::make_shared<Args>();
  std::string names;
  for (const auto& n : warptest_names()) names += (names.empty() ? "" : ", ") + n;
  CLI::App* cmd = app.add_subcommand(
      "warptest", "Chi-square test of a sampling routine against its pdf, with a picture of both histograms");
  cmd->add_option("name", args->name, "Warp to test: " + names)->required();
  cmd->add_option("--param", args->param,
                  "cos_max in (-1, 1) for spherical_cap, alpha in (0, 1] for ggx_* (default: 0.9, 0.3; the test "
                  "decides for cos_max up to 0.9999 and alpha from 1e-19)")
      ->check(kFiniteNumber);
  // The chi-square test needs cells that expect 5 samples or more: uniform_sphere's 3200 equal cells need 16,000
  // samples; from 100,000 on, every warp at its default parameter has hundreds of such cells.
  cmd->add_option("--samples", args->samples, "Number of samples")
      ->check(CLI::Range(100'000ull, 1'000'000'000ull))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->out, "Histogram picture (PNG; .exr, .jpg and .hdr also work), '' for none")
      ->capture_default_str();
  cmd->callback([args, &exit_code] {
    const int rc = run_warptest(args->name, args->param, args->samples, args->out, std::cout, std::cerr);
    exit_code = rc == 2 ? 2 : (rc == 0 ? 0 : 1);
  });
}

}  // namespace lumis
