#include "app/montage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/image_io.h"

namespace lumis {

namespace {

const Color kBackground = srgb8(24, 24, 24);
const Color kText = srgb8(235, 235, 235);
const Color kCropOutline = srgb8(255, 210, 0);
constexpr int kPad = 6;

// Integer enlargement that brings the longer side of a w x h picture to at least `target` pixels.
int enlargement(int w, int h, int target) {
  return std::max(1, (target + std::max(w, h) - 1) / std::max(1, std::max(w, h)));
}

}  // namespace

Color srgb8(uint8_t r, uint8_t g, uint8_t b) {
  return {srgb_to_linear(r / 255.0f), srgb_to_linear(g / 255.0f), srgb_to_linear(b / 255.0f)};
}

Image make_canvas(int w, int h, Color fill) {
  Image img(std::max(1, w), std::max(1, h), {"R", "G", "B"});
  for (size_t i = 0; i < img.data.size(); i += 3) {
    img.data[i] = fill.x;
    img.data[i + 1] = fill.y;
    img.data[i + 2] = fill.z;
  }
  return img;
}

void fill_rect(Image& canvas, int x, int y, int w, int h, Color c) {
  const int x0 = std::max(0, x), y0 = std::max(0, y);
  const int x1 = std::min(canvas.width, x + w), y1 = std::min(canvas.height, y + h);
  for (int yy = y0; yy < y1; ++yy)
    for (int xx = x0; xx < x1; ++xx)
      for (int k = 0; k < 3; ++k) canvas.at(xx, yy, k) = c[k];
}

void draw_rect_outline(Image& canvas, int x, int y, int w, int h, Color c, int thickness) {
  fill_rect(canvas, x, y, w, thickness, c);
  fill_rect(canvas, x, y + h - thickness, w, thickness, c);
  fill_rect(canvas, x, y, thickness, h, c);
  fill_rect(canvas, x + w - thickness, y, thickness, h, c);
}

void draw_line(Image& canvas, float x0, float y0, float x1, float y1, Color c, int thickness) {
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1)) return;
  const float len = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
  const int steps = std::min(100000, static_cast<int>(std::ceil(len)) + 1);
  const int half = thickness / 2;
  for (int i = 0; i <= steps; ++i) {
    const float t = steps ? static_cast<float>(i) / steps : 0.0f;
    const int x = static_cast<int>(std::lround(x0 + (x1 - x0) * t));
    const int y = static_cast<int>(std::lround(y0 + (y1 - y0) * t));
    fill_rect(canvas, x - half, y - half, thickness, thickness, c);
  }
}

void blit_region(Image& canvas, const Image& src, int sx, int sy, int sw, int sh, int dx, int dy, int zoom,
                 float gain) {
  for (int y = 0; y < sh * zoom; ++y) {
    const int py = sy + y / zoom, cy = dy + y;
    if (py < 0 || py >= src.height || cy < 0 || cy >= canvas.height) continue;
    for (int x = 0; x < sw * zoom; ++x) {
      const int px = sx + x / zoom, cx = dx + x;
      if (px < 0 || px >= src.width || cx < 0 || cx >= canvas.width) continue;
      const Color v = src.rgb(px, py) * gain;
      for (int k = 0; k < 3; ++k) canvas.at(cx, cy, k) = v[k];
    }
  }
}

Color false_colour(float t) {
  // Anchors in sRGB bytes, evenly spaced in t: perceptually ordered from dark to bright like viridis.
  static const uint8_t kAnchors[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  if (!std::isfinite(t)) t = 0;
  t = std::clamp(t, 0.0f, 1.0f) * 4.0f;
  const int i = std::min(3, static_cast<int>(t));
  const float f = t - i;
  float enc[3];
  for (int k = 0; k < 3; ++k) enc[k] = ((1 - f) * kAnchors[i][k] + f * kAnchors[i + 1][k]) / 255.0f;
  return {srgb_to_linear(enc[0]), srgb_to_linear(enc[1]), srgb_to_linear(enc[2])};
}

std::string short_number(double v) {
  char buf[32];
  const double a = std::abs(v);
  if (!std::isfinite(v)) std::snprintf(buf, sizeof buf, "%s", std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf"));
  else if (v == 0) std::snprintf(buf, sizeof buf, "0");
  else if (a >= 1e-3 && a < 1e4) std::snprintf(buf, sizeof buf, "%.3g", v);
  else std::snprintf(buf, sizeof buf, "%.2e", v);
  return buf;
}

Image make_montage(const std::vector<MontageTile>& tiles, const MontageOptions& options) {
  int w = 1, h = 1;
  size_t lines = 0;
  for (const MontageTile& t : tiles) {
    w = std::max(w, t.image->width);
    h = std::max(h, t.image->height);
    lines = std::max(lines, t.label.size());
  }
  const int zoom = enlargement(w, h, 192);
  const int text_scale = w * zoom >= 384 ? 2 : 1;
  int label_w = 0;
  for (const MontageTile& t : tiles)
    for (const std::string& s : t.label) label_w = std::max(label_w, text_width(s, text_scale));
  const bool crop = options.crop_w > 0 && options.crop_h > 0;
  // A crop wider than half the image widens the columns, so that at 2x it still fits in its own.
  const int col_w = std::max({w * zoom, label_w, crop ? 2 * options.crop_w : 0});
  const int label_h = static_cast<int>(lines) * kLineHeight * text_scale;
  // Crops are enlarged so that their longer side fills the column (at least 2x), nearest neighbour.
  const int crop_zoom = crop ? std::max(2, col_w / std::max(options.crop_w, options.crop_h)) : 0;
  const int crop_h = crop ? options.crop_h * crop_zoom : 0;
  const int n = static_cast<int>(tiles.size());
  const int canvas_w = kPad + n * (col_w + kPad);
  const int canvas_h = kPad + h * zoom + kPad + label_h + kPad + (crop ? crop_h + kPad : 0);
  Image canvas = make_canvas(canvas_w, canvas_h, kBackground);
  const float gain = std::exp2(options.exposure);
  for (int i = 0; i < n; ++i) {
    const Image& img = *tiles[i].image;
    const int x0 = kPad + i * (col_w + kPad);
    const int ix = x0 + (col_w - img.width * zoom) / 2;
    blit_region(canvas, img, 0, 0, img.width, img.height, ix, kPad, zoom, gain);
    if (crop)
      draw_rect_outline(canvas, ix + options.crop_x * zoom - 1, kPad + options.crop_y * zoom - 1,
                        options.crop_w * zoom + 2, options.crop_h * zoom + 2, kCropOutline);
    int ty = kPad + h * zoom + kPad;
    for (const std::string& s : tiles[i].label) {
      draw_text(canvas, x0 + (col_w - text_width(s, text_scale)) / 2, ty, s, kText, text_scale);
      ty += kLineHeight * text_scale;
    }
    if (crop) {
      const int cy = kPad + h * zoom + kPad + label_h + kPad;
      const int cx = x0 + (col_w - options.crop_w * crop_zoom) / 2;
      blit_region(canvas, img, options.crop_x, options.crop_y, options.crop_w, options.crop_h, cx, cy, crop_zoom, gain);
    }
  }
  return canvas;
}

Image false_colour_with_bar(const std::vector<float>& values, int w, int h, double lo, double hi,
                            const std::string& caption) {
  const int zoom = enlargement(w, h, 128);
  const int iw = w * zoom, ih = h * zoom;
  const std::string hi_label = short_number(hi), lo_label = short_number(lo);
  const int bar_w = 12;
  const int label_w = std::max(text_width(hi_label), text_width(lo_label));
  const int caption_h = caption.empty() ? 0 : kLineHeight + kPad;
  const int canvas_w = std::max(kPad + iw + kPad + bar_w + 4 + label_w + kPad, kPad + text_width(caption) + kPad);
  Image canvas = make_canvas(canvas_w, kPad + ih + kPad + caption_h, kBackground);
  const Color nonfinite = srgb8(255, 0, 255);
  const double range = hi > lo ? hi - lo : 1.0;
  for (int y = 0; y < ih; ++y)
    for (int x = 0; x < iw; ++x) {
      const float v = values[static_cast<size_t>(y / zoom) * w + x / zoom];
      const Color c = std::isfinite(v) ? false_colour(static_cast<float>((v - lo) / range)) : nonfinite;
      for (int k = 0; k < 3; ++k) canvas.at(kPad + x, kPad + y, k) = c[k];
    }
  const int bx = kPad + iw + kPad;
  for (int y = 0; y < ih; ++y) {
    const Color c = false_colour(ih > 1 ? 1.0f - static_cast<float>(y) / (ih - 1) : 1.0f);
    fill_rect(canvas, bx, kPad + y, bar_w, 1, c);
  }
  draw_text(canvas, bx + bar_w + 4, kPad, hi_label, kText);
  draw_text(canvas, bx + bar_w + 4, kPad + ih - 7, lo_label, kText);
  if (!caption.empty()) draw_text(canvas, kPad, kPad + ih + kPad, caption, kText);
  return canvas;
}

}  // namespace lumis
