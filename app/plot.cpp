#include "app/plot.h"

#include <algorithm>
#include <cmath>

#include "app/montage.h"

namespace lumis {

namespace {

struct DecadeRange {
  int lo = 0, hi = 1;
};

DecadeRange decades(double min_v, double max_v) {
  DecadeRange r;
  if (!(min_v > 0) || !std::isfinite(max_v)) return r;
  r.lo = static_cast<int>(std::floor(std::log10(min_v)));
  r.hi = static_cast<int>(std::ceil(std::log10(max_v)));
  if (r.hi <= r.lo) r.hi = r.lo + 1;
  return r;
}

bool usable(double x, double y) { return std::isfinite(x) && std::isfinite(y) && x > 0 && y > 0; }

}  // namespace

Color series_colour(int index) {
  static const uint8_t kPalette[8][3] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},  {214, 39, 40},
                                         {148, 103, 189}, {140, 86, 75}, {227, 119, 194}, {23, 190, 207}};
  const uint8_t* c = kPalette[((index % 8) + 8) % 8];
  return srgb8(c[0], c[1], c[2]);
}

Image plot_loglog(const std::vector<PlotSeries>& series, const std::string& x_label, const std::string& y_label,
                  int width, int height) {
  const Color white = srgb8(255, 255, 255), black = srgb8(0, 0, 0), grid = srgb8(225, 225, 225),
              grey = srgb8(120, 120, 120);
  Image canvas = make_canvas(width, height, white);
  const int px0 = 70, px1 = width - 16, py0 = 24, py1 = height - 44;

  double xmin = INFINITY, xmax = 0, ymin = INFINITY, ymax = 0;
  for (const PlotSeries& s : series)
    for (const auto& [x, y] : s.points)
      if (usable(x, y)) {
        xmin = std::min(xmin, x), xmax = std::max(xmax, x);
        ymin = std::min(ymin, y), ymax = std::max(ymax, y);
      }
  const bool any = xmax > 0;
  const DecadeRange dx = decades(any ? xmin : 1, any ? xmax : 10), dy = decades(any ? ymin : 1, any ? ymax : 10);
  auto map_x = [&](double x) { return px0 + (std::log10(x) - dx.lo) / (dx.hi - dx.lo) * (px1 - px0); };
  auto map_y = [&](double y) { return py1 - (std::log10(y) - dy.lo) / (dy.hi - dy.lo) * (py1 - py0); };

  // Grid, ticks and labels; with many decades only every step-th one is labelled.
  auto axis = [&](const DecadeRange& d, bool is_x) {
    const int step = std::max(1, (d.hi - d.lo + 7) / 8);
    for (int e = d.lo; e <= d.hi; ++e) {
      const double v = std::pow(10.0, e);
      const int p = static_cast<int>(std::lround(is_x ? map_x(v) : map_y(v)));
      if (is_x) fill_rect(canvas, p, py0, 1, py1 - py0, grid);
      else fill_rect(canvas, px0, p, px1 - px0, 1, grid);
      if (is_x) fill_rect(canvas, p, py1, 1, 6, black);
      else fill_rect(canvas, px0 - 6, p, 6, 1, black);
      if ((e - d.lo) % step == 0) {
        const std::string t = "1E" + std::to_string(e);
        if (is_x) draw_text(canvas, p - text_width(t) / 2, py1 + 9, t, black);
        else draw_text(canvas, px0 - 9 - text_width(t), p - 3, t, black);
      }
      for (int m = 2; m <= 9 && e < d.hi; ++m) {
        const int q = static_cast<int>(std::lround(is_x ? map_x(m * v) : map_y(m * v)));
        if (is_x) fill_rect(canvas, q, py1, 1, 3, black);
        else fill_rect(canvas, px0 - 3, q, 3, 1, black);
      }
    }
  };
  axis(dx, true);
  axis(dy, false);
  fill_rect(canvas, px0, py0, 1, py1 - py0 + 1, black);
  fill_rect(canvas, px0, py1, px1 - px0 + 1, 1, black);
  draw_text(canvas, px0 + (px1 - px0 - text_width(x_label)) / 2, py1 + 24, x_label, black);
  draw_text(canvas, 8, 8, y_label, black);
  if (!any) draw_text(canvas, (px0 + px1 - text_width("NO DATA")) / 2, (py0 + py1) / 2, "NO DATA", grey);

  for (size_t i = 0; i < series.size(); ++i) {
    const Color c = series[i].colour;
    bool have_prev = false;
    double qx = 0, qy = 0;
    for (const auto& [x, y] : series[i].points) {
      if (!usable(x, y)) continue;
      const double sx = map_x(x), sy = map_y(y);
      if (have_prev) draw_line(canvas, static_cast<float>(qx), static_cast<float>(qy), static_cast<float>(sx),
                               static_cast<float>(sy), c, 2);
      fill_rect(canvas, static_cast<int>(std::lround(sx)) - 2, static_cast<int>(std::lround(sy)) - 2, 5, 5, c);
      qx = sx, qy = sy, have_prev = true;
    }
  }

  int legend_w = 0;
  for (const PlotSeries& s : series) legend_w = std::max(legend_w, text_width(s.name));
  legend_w += 34;
  const int legend_h = static_cast<int>(series.size()) * 12 + 8;
  const int lx = px1 - legend_w - 8, ly = py0 + 8;
  if (!series.empty()) {
    fill_rect(canvas, lx, ly, legend_w, legend_h, white);
    draw_rect_outline(canvas, lx, ly, legend_w, legend_h, grey);
    for (size_t i = 0; i < series.size(); ++i) {
      const int y = ly + 6 + static_cast<int>(i) * 12;
      fill_rect(canvas, lx + 6, y + 2, 18, 3, series[i].colour);
      draw_text(canvas, lx + 28, y, series[i].name, black);
    }
  }
  return canvas;
}

}  // namespace lumis
