// `lumis warptest NAME`: chi-square goodness of fit of one sampling routine against its own density, in the manner
// of Nori's warptest, with a picture of the observed histogram beside the expected one.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "core/math.h"

namespace lumis {

/// A sampling routine (a direction, nullopt when it fails) and its solid-angle density in the same frame.
struct Warp {
  std::function<std::optional<Vec3>(Vec2)> sample;
  std::function<double(Vec3)> pdf;
};

/// `warp` seen through the bijection w -> normalize(k x, k y, z), k >= 1: its samples mapped and its density
/// transformed to match, so that a lobe about the pole k times narrower than the histogram's cells spans them.
Warp stretched(const Warp& warp, double k);

/// Names accepted by run_warptest, in the order they are listed to the user.
std::vector<std::string> warptest_names();

/// Draws `samples` directions from the named warp (param: cos_max for spherical_cap, alpha for ggx_*, NaN for
/// the default; checked as given and as the float the warp uses), bins them in (cos theta, phi) cells, compares
/// with the pdf integrated over each cell, prints the statistic, dof, p-value and verdict to `out`, and when out_png
/// is not empty writes the two histograms side by side on one colour scale. GGX lobes narrower than at alpha = 0.3,
/// and caps narrower than at cos_max = 0.9, are binned in `stretched` directions, so that the lobe spans the cells.
/// Returns 0 if the chi-square test passes, 1 if it fails, 2 for a usage error: an unknown name (the valid names
/// are printed), a param outside the warp's domain (or given to a warp without one) or where the test cannot decide
/// (cos_max above 0.9999, alpha below 1e-19), an output path that cannot be written or has an unsupported extension
/// (checked before sampling), or too few samples for the test to decide (the number needed is printed); 3 if the
/// picture could not be written; errors go to `err`.
int run_warptest(const std::string& name, double param, uint64_t samples, const std::string& out_png,
                 std::ostream& out, std::ostream& err);

/// The test run_warptest runs once it has found and checked its warp, for any `warp` (solid-angle pdf, world frame
/// = the cells' frame): `title` names it in the report, `cells_note` follows the cells' description, and `out_png`
/// (empty: none) must already be known to be writable. Returns 0 pass, 1 fail, 2 too few samples to decide, 3 the
/// picture could not be written.
int check_warp(const Warp& warp, const std::string& title, const std::string& cells_note, uint64_t samples,
               const std::string& out_png, std::ostream& out, std::ostream& err);

}  // namespace lumis
