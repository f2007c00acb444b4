// Rendering for `lumis compare`: one variant at a time, and the nee_mis reference with its cache
// (app/compare_internal.h).
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
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

namespace {

/// A file the scene reads, and the fnv1a_file_hex of its contents.
struct HashedInput {
  std::string file, hash;
};

/// At most three of `items`, then how many more, joined by ", ".
std::string some_of(const std::vector<std::string>& items) {
  std::string text;
  for (size_t i = 0; i < items.size() && i < 3; ++i) text += (i ? ", " : "") + items[i];
  if (items.size() > 3) text += " and " + std::to_string(items.size() - 3) + " more";
  return text;
}

/// Why a cached reference, whose reference.json is `old` and whose hash differs, is not the one wanted: its key's
/// settings, the scene file, the files the scene reads, or else (as nothing else enters the hash) the camera.
std::string why_stale(const nlohmann::json& old, const nlohmann::json& key, const std::string& scene_hash,
                      const std::vector<HashedInput>& inputs) {
  std::vector<std::string> why, settings, files;
  const nlohmann::json& old_key = old.at("key");
  // The key holds the reference's own seed; a person set the variants' seed (--seed), so that is the one shown.
  const auto shown = [](const std::string& name, const nlohmann::json& v) {
    return name == "seed" && v.is_number_unsigned() ? std::to_string(reference_seed(v.get<uint32_t>())) : v.dump();
  };
  for (const auto& [name, value] : key.items())
    if (!old_key.contains(name) || old_key[name] != value)
      settings.push_back(name + " " + (old_key.contains(name) ? shown(name, old_key[name]) : "unset") + " -> " +
                         shown(name, value));
  if (!settings.empty()) why.push_back("settings changed: " + some_of(settings));
  if (!old.contains("scene_fnv1a") || !old.contains("inputs"))  // written before lumis recorded them
    return why.empty() ? "cached by an older lumis, which did not record the scene's files" : why.front();
  if (old.at("scene_fnv1a").get<std::string>() != scene_hash) why.push_back("the scene file changed");
  std::map<std::string, std::string> before;
  for (const nlohmann::json& in : old.at("inputs")) before[in.at("file").get<std::string>()] = in.at("fnv1a");
  for (const HashedInput& in : inputs) {
    const auto it = before.find(in.file);
    if (it == before.end()) files.push_back(in.file + " (new)");
    else if (it->second != in.hash) files.push_back(in.file);
    if (it != before.end()) before.erase(it);
  }
  for (const auto& [file, hash] : before) files.push_back(file + " (no longer read)");
  if (!files.empty()) why.push_back("changed: " + some_of(files));
  if (why.empty()) why.push_back("the camera changed");
  std::string text;
  for (const std::string& w : why) text += (text.empty() ? "" : "; ") + w;
  return text;
}

}  // namespace

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
  std::vector<HashedInput> hashed;
  std::string inputs;
  for (const std::string& file : scene.inputs()) {
    hashed.push_back({file, fnv1a_file_hex(file)});
    inputs += "\ninput " + hashed.back().hash;
  }
  const std::string scene_hash = fnv1a_file_hex(scene_path);
  const nlohmann::json key = reference_key(base, ref_spp);
  const std::string hash = reference_hash(scene_hash, camera + inputs, base, ref_spp);
  const fs::path exr = dir / "reference.exr", meta = dir / "reference.json";
  bool cached = false;
  std::string stale;  // why a reference found in DIR is not used
  if (fs::exists(exr) && fs::exists(meta)) {
    try {
      const nlohmann::json j = nlohmann::json::parse(read_file_bytes(meta.string()));
      if (j.at("hash").get<std::string>() != hash) {
        stale = why_stale(j, key, scene_hash, hashed);
      } else {
        reference = read_image(exr.string());
        rgb_channels(reference, exr.string());
        cached = reference.width == base.width && reference.height == base.height;
        if (!cached) stale = "reference.exr is " + std::to_string(reference.width) + "x" +
                             std::to_string(reference.height);
      }
    } catch (const std::exception& e) {
      stale = std::string("unreadable: ") + e.what();  // render a new reference
    }
  }
  if (!cached) {
    if (!stale.empty()) log("not reusing the cached reference (" + stale + ")");
    log("rendering reference (nee_mis, " + std::to_string(ref_spp) + " spp)");
    RenderSettings rs = base;
    rs.integrator = "nee_mis";
    rs.seed = reference_seed(base.seed);
    Rendered r = render_variant(scene, rs, ref_spp, 0);
    reference = std::move(r.image);
    fs::create_directories(exr.parent_path());  // -o's folder, made only now that there is something to write
    write_image(exr.string(), reference);
    nlohmann::json files = nlohmann::json::array();
    for (const HashedInput& in : hashed) files.push_back({{"file", in.file}, {"fnv1a", in.hash}});
    nlohmann::json j = {{"hash", hash}, {"scene", scene_path}, {"key", key}, {"seconds", r.stats.seconds},
                        {"scene_fnv1a", scene_hash}, {"inputs", files}};
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
