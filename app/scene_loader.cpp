// Scene files: the top level of the lumis JSON format (version, camera, film, render), and the checks every scene
// passes. Materials, shapes and lights are in json_scene.cpp / json_shapes.cpp; glTF files rendered with defaults in
// gltf_scene.cpp.
#include "app/scene_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/json_scene.h"
#include "app/scene_loader_internal.h"
#include "app/scene_error.h"
#include "core/file_ext.h"
#include "integrators/integrator.h"

namespace lumis {

namespace {

// At the other end, products of three lengths (Embree's intersection terms, squared areas) reach float's denormals
// in scenes much smaller than this, and images go wrong: the geometry's bounding box must be at least this large.
constexpr float kMinSize = 1e-12f;

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string too_far(double extent) {
  return format_number(extent) + " scene units from the origin; coordinates must stay within " +
         format_number(kMaxCoordinate) + " (scale the scene down)";
}

// A JSON shape or light (`what`) whose geometry, ids `first` on, reaches beyond kMaxCoordinate: an error at its node,
// before check_extent would find the whole scene too large without saying where.
void check_reach(const Scene& scene, size_t first, const JsonNode& node, const std::string& what) {
  double reach = 0;  // in double: a sphere's |centre| + radius may pass float's range
  for (size_t id = first; id < scene.geometry.geometry_count(); ++id) {
    const auto g = static_cast<uint32_t>(id);
    if (scene.geometry.is_mesh(g)) {
      for (const Vec3& p : scene.geometry.mesh(g).positions)
        reach = std::max(reach, static_cast<double>(max_component(abs(p))));
    } else {
      const Sphere& s = scene.geometry.sphere(g);
      reach = std::max(reach, static_cast<double>(max_component(abs(s.center))) + s.radius);
    }
  }
  if (!(reach <= kMaxCoordinate)) node.fail("the " + what + " reaches " + too_far(reach));
}

}  // namespace

void check_extent(const Scene& scene, const std::string& path, const std::string& camera_location,
                  const std::string& near_location) {
  const Bounds3 b = scene.geometry.bounds();
  if (!b.empty()) {
    const float extent = std::max(max_component(abs(b.lo)), max_component(abs(b.hi)));
    if (!(extent <= kMaxCoordinate))
      throw SceneError(path, "", "the geometry reaches " + too_far(extent));
    const float size = max_component(b.diagonal());
    if (!(size >= kMinSize))
      throw SceneError(path, "", "the geometry spans only " + format_number(size) +
                                     " scene units; it must span at least " + format_number(kMinSize) +
                                     " (scale the scene up)");
  }
  // A framing camera (no camera location) stands a few extents away, more for an extreme aspect ratio.
  if (!(max_component(abs(scene.camera.from)) <= kMaxCoordinate))
    throw SceneError(path, camera_location,
                     std::string(camera_location.empty() ? "the framing camera (for a " +
                                                               std::to_string(scene.settings.width) + " x " +
                                                               std::to_string(scene.settings.height) + " image)"
                                                         : "the camera") +
                         " is " + format_number(max_component(abs(scene.camera.from))) +
                         " scene units from the origin; coordinates must stay within " + format_number(kMaxCoordinate));
  // Camera rays start near_clip along their direction: past kMaxCoordinate Embree aborts (a near clip of 1e20).
  const float reach = max_component(abs(scene.camera.from)) + scene.camera.near_clip;
  if (!(reach <= kMaxCoordinate))
    throw SceneError(path, near_location,
                     "the camera's near clip distance, " + format_number(scene.camera.near_clip) +
                         ", starts its rays up to " + format_number(reach) +
                         " scene units from the origin; coordinates must stay within " + format_number(kMaxCoordinate));
}

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, "", "cannot open the file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void parse_camera(const JsonNode& node, Camera& camera) {
  node.expect_object({"type", "from", "to", "up", "fov", "near"});
  if (auto t = node.find("type")) t->as_choice({"perspective"}, "camera type");
  camera.from = node["from"].as_vec3();
  camera.to = node["to"].as_vec3();
  if (auto u = node.find("up")) camera.up = u->as_vec3();
  const Vec3 dir = camera.to - camera.from;
  if (!(length(dir) > 0)) node["to"].fail("\"to\" must differ from \"from\" (the camera has no viewing direction)");
  if (!(length(cross(normalize(dir), camera.up)) > 1e-6f * length(camera.up)))
    node[node.has("up") ? "up" : "to"].fail("\"up\" must not be zero or parallel to the viewing direction");
  if (auto f = node.find("fov")) {
    camera.fov_y_degrees = f->as_float();
    if (!(camera.fov_y_degrees > 0 && camera.fov_y_degrees < 180))
      f->fail_expected("a vertical field of view in degrees, strictly between 0 and 180");
  }
  if (auto n = node.find("near")) camera.near_clip = n->as_float(0);
}

void parse_film(const JsonNode& node, RenderSettings& s) {
  node.expect_object({"width", "height"});
  const int64_t unbounded = std::numeric_limits<int64_t>::max();
  int64_t w = s.width, h = s.height;
  if (auto v = node.find("width")) w = v->as_integer(1, unbounded);
  if (auto v = node.find("height")) h = v->as_integer(1, unbounded);
  if (w > kMaxResolution || h > kMaxResolution) {
    const JsonNode at = w > kMaxResolution ? node["width"] : node["height"];
    at.fail("absurd resolution " + std::to_string(w) + " x " + std::to_string(h) + ": at most " +
            std::to_string(kMaxResolution) + " pixels per side (2^28 pixels in all)");
  }
  s.width = static_cast<int>(w);
  s.height = static_cast<int>(h);
}

template <typename Enum>
Enum parse_enum(const JsonNode& node, const std::vector<std::string>& names, std::string_view what) {
  return static_cast<Enum>(node.as_choice(names, what));
}

void parse_render(const JsonNode& node, RenderSettings& s) {
  node.expect_object({"integrator", "spp", "max_depth", "rr_depth", "sampler", "seed", "light_selection",
                      "mis_heuristic", "uniform_measure", "mis_light_probability", "time", "exposure"});
  if (auto v = node.find("integrator"))
    s.integrator = integrator_names()[v->as_choice(integrator_names(), "integrator")];
  if (auto v = node.find("spp")) s.spp = static_cast<uint32_t>(v->as_integer(1, 1 << 30));
  if (auto v = node.find("max_depth")) s.max_depth = static_cast<int>(v->as_integer(1, 1024));
  if (auto v = node.find("rr_depth")) s.rr_depth = static_cast<int>(v->as_integer(0, 1024));
  // The enum orders match these lists (core/sampler.h, lights/light_selection.h, integrators/scene.h).
  if (auto v = node.find("sampler"))
    s.sampler = parse_enum<SamplerType>(*v, {"independent", "stratified", "sobol"}, "sampler");
  if (auto v = node.find("seed")) s.seed = static_cast<uint32_t>(v->as_integer(0, 0xffffffffLL));
  if (auto v = node.find("light_selection"))
    s.light_selection = parse_enum<LightSelection>(*v, {"uniform", "power", "importance"}, "light_selection");
  if (auto v = node.find("mis_heuristic"))
    s.mis_heuristic = parse_enum<MisHeuristic>(*v, {"balance", "power"}, "mis_heuristic");
  if (auto v = node.find("uniform_measure"))
    s.uniform_measure = parse_enum<UniformMeasure>(*v, {"theta_phi", "solid_angle"}, "uniform_measure");
  if (auto v = node.find("mis_light_probability")) {
    s.mis_light_probability = v->as_float();
    // [0, 1), in float: light sampling alone never draws the directions no light covers, so the image would lose
    // indirect light. One message for both ends (as_float's range wording would say [0, 1] below 0).
    if (!(s.mis_light_probability >= 0 && s.mis_light_probability < 1))
      v->fail_expected("a probability in [0, 1) (1 would lose indirect light)");
  }
  if (auto v = node.find("time")) s.time_budget = v->as_double(0, 1e7);
  if (auto v = node.find("exposure")) s.exposure = v->as_float(-64, 64);
}

std::unique_ptr<Scene> load_json_scene(const std::string& text, const std::string& path) {
  const Json doc = parse_json_text(text, path);
  const JsonNode root(doc, "", path);
  root.expect_object({"version", "camera", "film", "render", "materials", "shapes", "lights"});
  if (auto v = root.find("version")) {
    // 1 or 1.0: a whole number, as the other integer keys accept.
    if (!v->value().is_number() || v->value().get<double>() != 1.0)
      v->fail("unsupported scene format version: expected 1, found " + describe_json(v->value()));
  }
  auto scene = std::make_unique<Scene>();
  scene->source = path;
  if (auto f = root.find("film")) parse_film(*f, scene->settings);
  if (auto r = root.find("render")) parse_render(*r, scene->settings);

  JsonSceneBuilder builder(*scene, path);
  if (auto m = root.find("materials")) builder.add_materials(*m);
  std::vector<JsonNode> shapes, lights;
  if (auto s = root.find("shapes")) shapes = s->elements();
  if (auto l = root.find("lights")) lights = l->elements();
  for (const auto& s : shapes) {
    const size_t first = scene->geometry.geometry_count();
    builder.add_shape(s);
    check_reach(*scene, first, s, "shape");
  }
  for (const auto& l : lights) {
    const size_t first = scene->geometry.geometry_count();
    builder.add_light(l);
    check_reach(*scene, first, l, "light");
  }
  // A malformed camera is named before an empty scene: each section's own errors come first.
  if (auto c = root.find("camera")) parse_camera(*c, scene->camera);
  if (shapes.empty() && lights.empty()) throw SceneError(path, "", "scene is empty: it has no shapes and no lights");
  if (!root.has("camera")) frame_camera(*scene, builder.bounds());
  const bool near = root.has("camera") && root["camera"].has("near");
  check_extent(*scene, path, root.has("camera") ? "/camera/from" : "", near ? "/camera/near" : "");
  builder.note_small_lights();
  scene->finalize();
  return scene;
}

}  // namespace

std::unique_ptr<Scene> load_scene(const std::string& path, const SceneLoadOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneError(path, "", "is a folder, expected a scene file");
  if (!std::filesystem::exists(path, ec)) throw SceneError(path, "", "no such scene file");
  if (!std::filesystem::is_regular_file(path, ec))
    throw SceneError(path, "", "is not a regular file (a pipe, device or socket), expected a scene file");
  const std::string ext = lower_extension(path);
  if (ext == ".json") {
    if (!options.camera.empty())
      throw std::invalid_argument("--camera chooses among a glTF file's cameras; " + path +
                                  " is a lumis scene, whose camera is its \"camera\" section");
    return load_json_scene(read_text(path), path);
  }
  if (ext == ".gltf" || ext == ".glb") return load_gltf_scene(path, options);
  throw SceneError(path, "", "unknown scene file type \"" + ext + "\"; expected .json, .gltf or .glb");
}

std::unique_ptr<Scene> load_scene_text(const std::string& text, const std::string& path) {
  return load_json_scene(text, path);
}

std::string scene_file_at(const std::string& out, const std::string& path, const Scene& scene) {
  std::vector<std::string> files = scene.inputs();
  files.insert(files.begin(), path);
  for (const std::string& file : files) {
    std::error_code ec;
    if (std::filesystem::equivalent(out, file, ec))
      return (file == path ? "the scene file (" : "a file the scene reads (") + file + ")";
  }
  return "";
}

}  // namespace lumis
