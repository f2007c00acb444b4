// Log-log line plots rasterised with the montage drawing helpers (convergence.png of `lumis compare`).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace lumis {

struct PlotSeries {
  std::string name;
  Color colour;                                 ///< linear
  std::vector<std::pair<double, double>> points;  ///< (x, y); points with x or y <= 0 or non-finite are skipped
};

/// Distinct colours for up to 8 series (then repeating), linear.
Color series_colour(int index);

/// Log-log plot: axes spanning whole decades around the data, a tick and label at every decade, minor ticks at
/// 2..9 x each decade, one polyline with markers per series, and a legend in the top-right corner.
Image plot_loglog(const std::vector<PlotSeries>& series, const std::string& x_label, const std::string& y_label,
                  int width = 640, int height = 440);

}  // namespace lumis
