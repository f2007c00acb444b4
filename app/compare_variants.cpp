// The middle of `lumis compare`'s pipeline (compare_internal.h): each variant rendered and measured against the
// reference, then the pictures made from them (error maps on one scale, the montage, the convergence plot).
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "app/compare_internal.h"
#include "app/diff.h"
#include "app/montage.h"
#include "app/plot.h"
#include "core/image_io.h"

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

// Doubling sample counts, ending at what the comparison used (in equal-time mode: what fitted in the budget), also
// when that is not a power of two: 12 spp gives 1, 2, 4, 8, 12.
std::vector<ConvergencePoint> convergence_series(Scene& scene, const RenderSettings& s, uint32_t spp,
                                                 const Image& reference, const DiffOptions& dopt) {
  std::vector<ConvergencePoint> out;
  const uint32_t last = std::max(1u, spp);
  for (uint32_t n = 1;; n = 2 * uint64_t(n) < last ? 2 * n : last) {
    Rendered c = render_variant(scene, s, n, 0);
    const DiffMetrics cm = compute_metrics(c.image, reference, dopt);
    out.push_back({n, c.stats.seconds, cm.mse, cm.rel_mse});
    if (n == last) break;
  }
  return out;
}

// Said, not hidden: a variant that took kTimedRenderSpp before the budget ran out (it did not get equal time), and at
// equal time a fast variant that outran the reference's 16 x spp: the reference's own noise then sets a floor under
// its relMSE (and efficiency falls with the budget); --reference-spp raises it.
void warn_unequal(const CompareReport& report, const RenderSettings& base) {
  for (const VariantResult& v : report.variants) {
    if (report.equal_time && v.spp >= kTimedRenderSpp)
      std::cerr << "lumis compare: warning: " << v.name << " reached " << kTimedRenderSpp
                << " spp, the most a timed render takes, in " << v.seconds << " s of the " << base.time_budget
                << " s budget: not equal time; use --spp, or a larger image\n";
    if (report.reference_spp > 0 && v.spp > report.reference_spp)
      std::cerr << "lumis compare: warning: " << v.name << " rendered " << v.spp << " spp, more than the reference's "
                << report.reference_spp << ": its error is partly the reference's noise; raise --reference-spp\n";
  }
}

}  // namespace

std::vector<Image> render_variants(Scene& scene, const std::vector<std::string>& names, const RenderSettings& base,
                                   const Image& reference, bool convergence, const fs::path& dir,
                                   CompareReport& report, const std::function<void(const std::string&)>& log) {
  WriteOptions display;
  display.exposure = base.exposure;
  std::vector<Image> images;
  for (const std::string& name : names) {
    RenderSettings s = base;
    s.integrator = name;
    Rendered r = render_variant(scene, s, base.spp, base.time_budget);
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
    if (convergence) v.convergence = convergence_series(scene, s, v.spp, reference, dopt);
    images.push_back(rgb_only(r.image));
    report.variants.push_back(std::move(v));
  }
  scene.settings = base;
  warn_unequal(report, base);
  return images;
}

void write_pictures(const std::vector<Image>& images, const Image& reference, const RenderSettings& base,
                    bool convergence, const fs::path& dir, CompareReport& report) {
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
    const std::string spp_time = std::to_string(v.spp) + " SPP " + timing(v.seconds);
    tiles.push_back({&images[i], {v.name, spp_time, "RELMSE " + short_number(v.rel_mse)}});
  }
  tiles.push_back(
      {&ref_rgb, {"REFERENCE", report.reference_spp ? std::to_string(report.reference_spp) + " SPP" : "FILE", ""}});
  MontageOptions mo;
  mo.exposure = base.exposure;
  if (const std::optional<CropRect>& crop = report.crop)
    mo.crop_x = crop->x, mo.crop_y = crop->y, mo.crop_w = crop->w, mo.crop_h = crop->h;
  write_image((dir / report.montage).string(), make_montage(tiles, mo));

  if (!convergence) return;
  std::vector<PlotSeries> series;
  for (size_t i = 0; i < report.variants.size(); ++i) {
    PlotSeries ps{report.variants[i].name, series_colour(static_cast<int>(i)), {}};
    for (const ConvergencePoint& p : report.variants[i].convergence) ps.points.push_back({p.seconds, p.rel_mse});
    series.push_back(std::move(ps));
  }
  report.convergence_png = "convergence.png";
  write_image((dir / report.convergence_png).string(), plot_loglog(series, "TIME (S)", "RELMSE"));
}

}  // namespace lumis
