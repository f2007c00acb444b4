// A bare glTF file as a scene: its first camera, or the one SceneLoadOptions::camera names (or a framing one), and a
// white sky unless it has a light source: an emissive material without an emissive texture (a lamp). Textured
// emission is usually a decal (a helmet's visor display), too weak to light a model on its own, so such files get the
// sky too.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "app/gltf_loader.h"
#include "app/json_scene.h"
#include "app/scene_error.h"
#include "app/scene_loader_internal.h"
#include "core/image.h"

namespace lumis {

namespace {

constexpr int kGltfImageWidth = 512;

/// The camera `wanted` names (SceneLoadOptions::camera) among the file's; throws std::invalid_argument listing them.
const GltfCamera& choose_camera(const GltfScene& gltf, const std::string& wanted, const std::string& path) {
  // By number; else by the node's own name, else the camera object's (Blender names them apart: "Camera.001" /
  // "Camera"). A name that several nodes share, or a camera object several nodes hold, does not say which.
  if (wanted.find_first_not_of("0123456789") == std::string::npos)
    for (size_t i = 0; i < gltf.cameras.size(); ++i)
      if (wanted == std::to_string(i)) return gltf.cameras[i];
  for (const bool by_node : {true, false}) {
    std::vector<size_t> found;
    for (size_t i = 0; i < gltf.cameras.size(); ++i)
      if (wanted == (by_node ? gltf.cameras[i].name : gltf.cameras[i].camera_name)) found.push_back(i);
    if (found.size() == 1) return gltf.cameras[found[0]];
    if (found.empty()) continue;
    std::ostringstream nodes;
    for (size_t i : found) nodes << (i == found.front() ? "" : ", ") << i << " (" << gltf.cameras[i].path << ")";
    const std::string what = by_node ? "several camera nodes of " + path + " are named '" + wanted + "'"
                                     : "camera '" + wanted + "' of " + path + " is in several nodes";
    throw std::invalid_argument("--camera: " + what + ": " + nodes.str() + "; give the number" +
                                (by_node ? "" : " or the node's name"));
  }
  std::ostringstream list;
  for (size_t i = 0; i < gltf.cameras.size(); ++i) {
    const GltfCamera& c = gltf.cameras[i];
    list << (i ? ", " : "") << i;
    if (!c.name.empty()) list << " '" << c.name << "'";
    list << " (" << c.path;
    if (!c.camera_name.empty() && c.camera_name != c.name) list << ", camera '" << c.camera_name << "'";
    list << ")";
  }
  throw std::invalid_argument("--camera: " + path + " has no camera '" + wanted + "'; " +
                              (gltf.cameras.empty() ? "it has no perspective camera" : "its cameras: " + list.str()));
}

}  // namespace

std::unique_ptr<Scene> load_gltf_scene(const std::string& path, const SceneLoadOptions& options) {
  auto scene = std::make_unique<Scene>();
  scene->source = path;
  GltfScene gltf;
  try {
    gltf = load_gltf(path);
  } catch (const ImageError& e) {
    throw SceneError(path, "", std::string("cannot read a texture: ") + e.what());
  }
  for (const auto& w : gltf.warnings) std::cerr << path << ": warning: " << w << "\n";
  scene->input_images = gltf.image_files;
  scene->input_files = gltf.buffer_files;
  if (gltf.meshes.empty()) throw SceneError(path, "", "scene is empty: " + gltf.why_empty);
  std::string camera_at;  // the chosen camera's glTF path, for errors
  if (options.camera == "0" && gltf.cameras.empty()) {  // "0 = the default": the framing camera here
    std::cerr << path << ": warning: --camera 0: the file has no perspective camera; rendering through the framing "
              << "camera, as without --camera\n";
  } else if (!options.camera.empty()) {
    const GltfCamera& c = choose_camera(gltf, options.camera, path);
    gltf.camera = c.camera;
    gltf.camera_aspect = c.aspect;
    camera_at = c.path;
  } else if (gltf.camera && !gltf.cameras.empty()) {
    camera_at = gltf.cameras.front().path;  // the default camera is the first
  }
  if (gltf.camera_aspect && *gltf.camera_aspect > 0) {
    // Keep 512 pixels across and follow the camera's aspect ratio for the height.
    scene->settings.width = kGltfImageWidth;
    // Clamped before rounding: a tiny ratio (1e-30) overflows lround's range, which once gave a height of 1.
    const double height = double(kGltfImageWidth) / *gltf.camera_aspect;
    scene->settings.height = static_cast<int>(std::lround(std::clamp(height, 1.0, double(kMaxResolution))));
    const bool clamped = !(height >= 0.5 && height < kMaxResolution + 0.5);
    if (clamped) scene->settings.aspect = *gltf.camera_aspect;  // what --width or --height alone then keeps
    if (clamped && !options.size_given)  // the image lacks its shape
      std::cerr << path << ": warning: " << (camera_at.empty() ? std::string("the camera") : camera_at)
                << "'s aspectRatio " << *gltf.camera_aspect << " needs an image of " << kGltfImageWidth << " x "
                << height << " pixels; its height is clamped to 1..." << kMaxResolution
                << " (give --width and --height for another shape)\n";
  }
  JsonSceneBuilder builder(*scene, path);
  bool has_lamp = false;
  for (const TriangleMesh& m : gltf.meshes) {
    if (m.material < 0 || m.material >= static_cast<int>(gltf.materials.size())) continue;
    const PbrParams& p = gltf.materials[m.material].params;
    has_lamp |= !is_black(p.emissive) && !p.emissive_texture;
  }
  builder.add_gltf(gltf, std::vector<int>(gltf.materials.size(), -1), TriangleSampling::SphericalTriangle);
  if (!has_lamp) {
    scene->environment = static_cast<int>(scene->lights.size());
    scene->lights.push_back(make_constant_environment(Color(1.0f)));
  }
  if (gltf.camera)
    scene->camera = *gltf.camera;
  else
    frame_camera(*scene, gltf.bounds.empty() ? builder.bounds() : gltf.bounds);
  check_extent(*scene, path, gltf.camera ? camera_at : "", gltf.camera ? camera_at : "");
  scene->finalize();
  return scene;
}

}  // namespace lumis
