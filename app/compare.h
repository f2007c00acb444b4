// `lumis compare SCENE`: renders one scene with several integrator variants at equal samples or equal time, measures
// each against a reference (given, or rendered with nee_mis and cached), and writes images, a montage, error
// pictures, an optional convergence plot, report.json, report.md and a self-contained index.html.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "integrators/scene.h"

namespace lumis {

struct CropRect {
  int x = 0, y = 0, w = 0, h = 0;
};

/// Parse "x,y,w,h"; throws std::invalid_argument when malformed or outside a width x height image.
CropRect parse_crop(const std::string& text, int width, int height);
/// Parse a comma-separated list of integrator names; throws std::invalid_argument on unknown or repeated names.
std::vector<std::string> parse_integrator_list(const std::string& text);

/// 64-bit FNV-1a as 16 hex digits; with `after` (an earlier result), the hash of the bytes that gave it followed by
/// `bytes` (FNV-1a carries nothing else from one byte to the next). Throws std::invalid_argument on a malformed
/// `after`.
std::string fnv1a_hex(const std::string& bytes, const std::string& after = "");
/// fnv1a_hex of a file's bytes, read in 1 MiB pieces rather than whole (an environment map can be gigabytes); a
/// file that cannot be opened hashes as empty.
std::string fnv1a_file_hex(const std::string& path);
/// The settings that change a reference rendering, as a JSON object (stored in reference.json).
nlohmann::json reference_key(const RenderSettings& s, uint32_t reference_spp);
/// Hash of the scene file's bytes (given as their fnv1a_hex), then `then` (the camera and the hashes of the files the
/// scene reads), then reference_key: a cached reference is reused only when this matches.
std::string reference_hash(const std::string& scene_file_hash, const std::string& then, const RenderSettings& s,
                           uint32_t reference_spp);
/// The seed the reference is rendered with: never the comparison seed, so that nee_mis's samples are not the
/// reference's first samples (which would make its error look smaller than it is).
uint32_t reference_seed(uint32_t seed);
/// Top of the error pictures' shared scale: the largest 99.5th percentile of the maps' finite values, so that one
/// firefly does not flatten every picture (larger errors show in the top colour); 1e-6 when every value is 0.
double shared_error_scale(const std::vector<std::vector<float>>& maps);

struct ConvergencePoint {
  uint32_t spp = 0;
  double seconds = 0, mse = 0, rel_mse = 0;
};

struct VariantResult {
  std::string name;
  uint32_t spp = 0;
  double seconds = 0;
  uint64_t samples = 0, rays = 0;
  double mse = 0, rel_mse = 0, mae = 0;
  std::string exr, png, error_png;  ///< file names relative to the output folder
  std::vector<ConvergencePoint> convergence;

  double samples_per_second() const { return seconds > 0 ? samples / seconds : 0; }
  double rays_per_second() const { return seconds > 0 ? rays / seconds : 0; }
  /// 1 / (relMSE x time): higher is better; equal-time and equal-spp runs rank variants the same way. An exact
  /// match (relMSE 0) is infinitely efficient and a non-finite relMSE gives NaN, not 0 (which would read "worst").
  double efficiency() const {
    if (!(seconds > 0)) return std::numeric_limits<double>::quiet_NaN();
    return 1.0 / (rel_mse * seconds);
  }
};

struct CompareReport {
  std::string scene;
  int width = 0, height = 0;
  bool equal_time = false;
  uint32_t spp = 0;       ///< equal-spp mode: samples per pixel of every variant
  double time_budget = 0; ///< equal-time mode: seconds per variant
  RenderSettings settings;  ///< the variants' settings (their integrator aside), for report.json's "settings"
  std::string camera;       ///< --camera as given (a glTF file's camera); empty: the file's default
  std::string reference_source;  ///< "rendered", "cached" or the --reference path
  bool reference_grey = false;   ///< a given reference that is grey (Y, or Y and A): its Y stands for R, G and B
  std::string reference_png = "reference.png";
  uint32_t reference_spp = 0;    ///< 0 when given as a file
  std::string reference_hash;
  double error_scale = 0;        ///< top of the shared colour scale of error-<name>.png
  std::optional<CropRect> crop;
  std::string montage = "montage.png", convergence_png;  ///< convergence_png empty without --convergence
  std::vector<VariantResult> variants;
};

nlohmann::json report_json(const CompareReport& r);
/// One line of the settings that determine the images, besides size and spp or time (for report.md and index.html):
/// "max depth 8, rr depth 3, stratified sampler, seed 0, ...".
std::string settings_summary(const CompareReport& r);
/// Markdown table: variant, spp, time, samples/s, rays/s, MSE, relMSE, efficiency.
std::string report_markdown(const CompareReport& r);
/// Self-contained viewer (images by relative file name, no external resources).
std::string report_html(const CompareReport& r);

}  // namespace lumis
