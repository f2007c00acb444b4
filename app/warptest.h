// `lumis warptest NAME`: chi-square goodness of fit of one sampling routine against its own density, in the manner
// of Nori's warptest, with a picture of the observed histogram beside the expected one.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace lumis {

/// Names accepted by run_warptest, in the order they are listed to the user.
std::vector<std::string> warptest_names();

/// Draws `samples` directions from the named warp (param: cos_max for spherical_cap, alpha for ggx_*, NaN for
/// the default), bins them in (cos theta, phi) cells, compares with the pdf integrated over each cell, prints the
/// statistic, dof, p-value and verdict to `out`, and when out_png is not empty writes the two histograms side by
/// side on one colour scale. Returns 0 if the chi-square test passes, 1 if it fails, 2 for an unknown name (the
/// valid names are printed) or a param outside the warp's domain (or given to a warp without one), 3 if the
/// picture could not be written; errors go to `err`.
int run_warptest(const std::string& name, float param, uint64_t samples, const std::string& out_png,
                 std::ostream& out, std::ostream& err);

}  // namespace lumis
