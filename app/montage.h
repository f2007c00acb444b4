// Raster drawing for the pictures `lumis diff` and `lumis compare` write: a canvas is an Image with channels R, G, B
// holding linear values (write_image applies the sRGB curve for PNG), colours are given as sRGB bytes, text uses a
// built-in 5x7 bitmap font, and false colour uses a viridis-like ramp defined here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace lumis {

/// Linear colour of an sRGB-encoded 8-bit triple.
Color srgb8(uint8_t r, uint8_t g, uint8_t b);
/// A w x h canvas (channels R, G, B) filled with `fill` (linear).
Image make_canvas(int w, int h, Color fill);

void fill_rect(Image& canvas, int x, int y, int w, int h, Color c);
/// One-pixel-wide rectangle border, `thickness` pixels inwards.
void draw_rect_outline(Image& canvas, int x, int y, int w, int h, Color c, int thickness = 1);
/// Line from (x0, y0) to (x1, y1) in canvas pixels, as a chain of square dots `thickness` wide.
void draw_line(Image& canvas, float x0, float y0, float x1, float y1, Color c, int thickness = 1);
/// Copy the region (sx, sy, sw, sh) of src's first three channels, times `gain`, enlarged `zoom` times
/// (nearest neighbour) with its top-left corner at (dx, dy). Pixels outside either image are skipped.
void blit_region(Image& canvas, const Image& src, int sx, int sy, int sw, int sh, int dx, int dy, int zoom,
                 float gain = 1.0f);

/// Glyph cell of the bitmap font at scale 1: 5x7 pixels plus 1 pixel spacing each way.
inline constexpr int kGlyphAdvance = 6;
inline constexpr int kLineHeight = 9;
/// Width in pixels of `text` drawn at `scale`.
int text_width(const std::string& text, int scale = 1);
/// Draw `text` with its top-left corner at (x, y). Lower case is drawn as upper case; characters the font lacks
/// are drawn as a hollow box.
void draw_text(Image& canvas, int x, int y, const std::string& text, Color c, int scale = 1);
/// The 7 rows of the glyph for `ch` (bit 4 = leftmost column).
const uint8_t* glyph_rows(char ch);

/// Viridis-like ramp: dark purple (t = 0), blue, teal, green, yellow (t = 1); t is clamped. Returns linear colour.
Color false_colour(float t);

/// Compact number for labels: 3 significant digits, exponent form outside [1e-3, 1e4).
std::string short_number(double v);

/// One picture in a montage, with up to a few label lines drawn under it.
struct MontageTile {
  const Image* image = nullptr;
  std::vector<std::string> label;
};

struct MontageOptions {
  float exposure = 0;  ///< stops applied to the tiles (labels are drawn unscaled)
  int crop_x = 0, crop_y = 0, crop_w = 0, crop_h = 0;  ///< crop_w > 0 adds a row of zoomed crops
};

/// Tiles side by side (each enlarged by an integer factor when small), labels under each, and optionally a second
/// row with the crop region of each tile enlarged (nearest neighbour); the crop region is outlined in the first row.
Image make_montage(const std::vector<MontageTile>& tiles, const MontageOptions& options);

/// Per-pixel false-colour picture of `values` (row-major, w x h; non-finite values drawn magenta), mapped from
/// [lo, hi] onto the ramp, with a colour bar on the right labelled hi (top) and lo (bottom). Images smaller than
/// 128 pixels are enlarged by an integer factor.
Image false_colour_with_bar(const std::vector<float>& values, int w, int h, double lo, double hi,
                            const std::string& caption);

}  // namespace lumis
