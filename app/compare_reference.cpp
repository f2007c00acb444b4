// Rendering for `lumis compare`: one variant at a time, and the nee_mis reference with its cache
// (app/compare_internal.h).
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/compare_internal.h"
#include "app/diff.h"
#include "core/atomic_write.h"
#include "core/image_io.h"

namespace lumis {

namespace fs = std::filesystem;

std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_text(const fs::path& path, const std::string& text) {
  if (const std::string why = write_file_atomically(path.string(), text); !why.empty())
    throw std::runtime_error(path.string() + ": " + why);
}

Rendered render_variant(Scene& scene, const RenderSettings& settings, uint32_t spp, double time_budget) {
  scene.settings = settings;
  const std::unique_ptr<Integrator> integrator = make_integrator(settings);
  Film film(settings.width, settings.height);
  RenderOptions ro;
  // Equal time: ask for far more samples than fit and let the budget stop the render at a pass boundary.
  ro.spp = time_budget > 0 ? kTimedRenderSpp : spp;
  ro.time_budget = time_budget;
  ro.threads = settings.threads;
  Rendered r;
  r.stats = render(scene, *integrator, film, ro);
  r.image = film.to_image();
  return r;
}

Image read_reference(const std::string& path, const RenderSettings& s, const std::string& scene_path) {
  Image reference = read_image(path, true);
  if (reference.width != s.width || reference.height != s.height)
    throw UsageError("compare: reference " + path + " is " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + " but " + scene_path + " renders at " +
                     std::to_string(s.width) + "x" + std::to_string(s.height) + " (use --width/--height)");
  rgb_channels(reference, path);
  return reference;
}

Image cached_reference(Scene& scene, const CompareArgs& args, const RenderSettings& base, const std::string& scene_path,
                       const fs::path& dir, CompareReport& report, const std::function<void(const std::string&)>& log) {
  Image reference;
  // 16x the variants' samples (at least 256), within --spp's own limit of 2^30.
  const uint32_t ref_spp = args.reference_spp ? *args.reference_spp
                                              : static_cast<uint32_t>(std::clamp<uint64_t>(
                                                    16 * uint64_t(base.spp), 256, uint64_t(1) << 30));
  // The camera chosen in a glTF file changes the image as the file's bytes do: its numbers are hashed, not the
  // --camera spelling, so that a camera given by number and by name shares one reference.
  const Camera& c = scene.camera;
  char camera[256];
  std::snprintf(camera, sizeof camera, "\ncamera %a %a %a, %a %a %a, %a %a %a, %a, %a", c.from.x, c.from.y, c.from.z,
                c.to.x, c.to.y, c.to.z, c.up.x, c.up.y, c.up.z, c.fov_y_degrees, c.near_clip);
  // The files the scene file refers to change the image as its own bytes do: their contents (not their paths, so
  // that a moved project keeps its reference) are hashed, glTF files and buffers first, then images, in load order.
  std::string inputs;
  for (const std::string& file : scene.inputs()) inputs += "\ninput " + fnv1a_file_hex(file);
  const std::string hash = reference_hash(read_file_bytes(scene_path) + camera + inputs, base, ref_spp);
  const fs::path exr = dir / "reference.exr", meta = dir / "reference.json";
  bool cached = false;
  if (fs::exists(exr) && fs::exists(meta)) {
    try {
      const nlohmann::json j = nlohmann::json::parse(read_file_bytes(meta.string()));
      if (j.value("hash", "") == hash) {
        reference = read_image(exr.string());
        rgb_channels(reference, exr.string());
        cached = reference.width == base.width && reference.height == base.height;
      }
    } catch (const std::exception&) {
      cached = false;  // unreadable cache: render a new reference
    }
  }
  if (!cached) {
    log("rendering reference (nee_mis, " + std::to_string(ref_spp) + " spp)");
    RenderSettings rs = base;
    rs.integrator = "nee_mis";
    rs.seed = reference_seed(base.seed);
    Rendered r = render_variant(scene, rs, ref_spp, 0);
    reference = std::move(r.image);
    write_image(exr.string(), reference);
    nlohmann::json j = {{"hash", hash}, {"scene", scene_path}, {"key", reference_key(base, ref_spp)},
                        {"seconds", r.stats.seconds}};
    if (!args.overrides.camera.empty()) j["key"]["camera"] = args.overrides.camera;  // render's --camera
    write_text(meta, j.dump(2) + "\n");
  } else {
    log("reusing cached reference " + exr.string());
  }
  report.reference_source = cached ? "cached" : "rendered";
  report.reference_spp = ref_spp;
  report.reference_hash = hash;
  return reference;
}

}  // namespace lumis
