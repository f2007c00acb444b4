// Command-line front end: each subcommand is a function that returns the process exit code
// (0 success, 1 scene/IO error, 2 usage error).
#pragma once

#include <cmath>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "app/render_overrides.h"

namespace lumis {

/// CLI11 check that a number option is finite: CLI::Range lets NaN through (every comparison with it is false).
inline const CLI::Validator kFiniteNumber(
    [](std::string& text) -> std::string {
      // CLI11 runs checks before conversion: parse as the option will (a whole string that is a number).
      try {
        size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == text.size() && !std::isfinite(v)) return "expected a finite number, found " + text;
      } catch (const std::exception&) {  // not a number: the option's own conversion reports it
      }
      return {};
    },
    "FINITE");

/// CLI11 check that a number lies in [lo, hi], with a message that says so in the option's own terms (CLI::Range
/// prints its bounds with six decimals, or as the largest double when there is no upper bound).
inline CLI::Validator number_in(double lo, double hi, const std::string& expected) {
  return CLI::Validator(
      [lo, hi, expected](std::string& text) -> std::string {
        try {
          size_t used = 0;
          const double v = std::stod(text, &used);
          if (used == text.size() && !(v >= lo && v <= hi)) return "expected " + expected + ", found " + text;
        } catch (const std::exception&) {  // not a number: the option's own conversion reports it
        }
        return {};
      },
      expected);
}

/// Register the override options on a CLI11 subcommand.
void add_render_overrides(CLI::App& cmd, RenderOverrides& o);
/// Register --camera (render and compare: commands that load one scene).
void add_camera_option(CLI::App& cmd, RenderOverrides& o);

/// True when stderr is a terminal.
bool stderr_is_tty();

void register_render_command(CLI::App& app, int& exit_code);
void register_warptest_command(CLI::App& app, int& exit_code);
void register_diff_command(CLI::App& app, int& exit_code);
void register_compare_command(CLI::App& app, int& exit_code);
void register_bench_command(CLI::App& app, int& exit_code);

}  // namespace lumis
