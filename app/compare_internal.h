// Shared by app/compare.cpp (the pipeline's checks and outputs), app/compare_reference.cpp (rendering one variant,
// the reference and its cache) and app/compare_variants.cpp (every variant, then the pictures); not part of
// compare.h's interface.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/compare.h"
#include "core/image.h"
#include "integrators/render.h"

namespace lumis {

/// Usage errors found after parsing (bad lists, crop outside the image, mismatched reference).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The whole file, or "" when it cannot be read.
std::string read_file_bytes(const std::string& path);
/// Whole or not at all, like write_image: readers never see half a report. Throws std::runtime_error.
void write_text(const std::filesystem::path& path, const std::string& text);

struct Rendered {
  Image image;
  RenderStats stats;
};
/// One render of `scene` with `settings`: `spp` samples per pixel, or as many as `time_budget` seconds allow (> 0).
Rendered render_variant(Scene& scene, const RenderSettings& settings, uint32_t spp, double time_budget);

/// A given reference: readable, the render's size, with R, G, B (a UsageError or DiffError otherwise).
Image read_reference(const std::string& path, const RenderSettings& s, const std::string& scene_path);
/// The rendered reference: nee_mis at --reference-spp (default 16 x spp, at least 256) with reference_seed(), reused
/// from dir/reference.exr when dir/reference.json's hash matches, else rendered and stored there. Fills report's
/// reference_source, reference_spp and reference_hash.
Image cached_reference(Scene& scene, const CompareArgs& args, const RenderSettings& base, const std::string& scene_path,
                       const std::filesystem::path& dir, CompareReport& report,
                       const std::function<void(const std::string&)>& log);

/// Renders each of `names` with `base` (its integrator replaced), writes NAME.exr and NAME.png in `dir`, and appends
/// to report.variants its statistics and errors against `reference` (with `convergence`: also a series at doubling
/// sample counts). Warns of variants that did not get equal time or outran the reference. Returns each variant's
/// R, G, B, in order, for write_pictures.
std::vector<Image> render_variants(Scene& scene, const std::vector<std::string>& names, const RenderSettings& base,
                                   const Image& reference, bool convergence, const std::filesystem::path& dir,
                                   CompareReport& report, const std::function<void(const std::string&)>& log);
/// Writes error-NAME.png on one shared scale (report.error_scale), montage.png (cropped to report.crop) and, with
/// `convergence`, convergence.png (report.convergence_png).
void write_pictures(const std::vector<Image>& images, const Image& reference, const RenderSettings& base,
                    bool convergence, const std::filesystem::path& dir, CompareReport& report);

}  // namespace lumis
