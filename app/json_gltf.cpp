// A "gltf" shape of a lumis JSON scene: the file loaded through the glTF loader, its materials kept or remapped by
// name to the scene's, its emissive meshes made mesh lights.
#include <iostream>

#include "app/json_scene.h"
#include "app/scene_error.h"
#include "core/file_ext.h"
#include "core/image_io.h"

namespace lumis {

void JsonSceneBuilder::add_gltf_shape(const JsonNode& node) {
  node.expect_object({"type", "name", "file", "transform", "materials", "sampling"});
  if (auto n = node.find("name")) n->as_string();  // a label for the reader: the meshes keep the file's names
  const JsonNode file = node["file"];
  const std::string path = resolve_path(file);
  const std::string ext = lower_extension(path);
  if (ext != ".gltf" && ext != ".glb")
    file.fail("expected a .gltf or .glb file, found " + (ext.empty() ? "no extension" : "\"" + ext + "\""));
  const Mat4 transform = node.find("transform") ? parse_transform(node["transform"]) : Mat4::identity();
  const TriangleSampling sampling = json_mesh_sampling(node);
  GltfScene gltf;
  try {
    gltf = load_gltf(path, transform, /*read_cameras=*/false);  // the scene's own `camera` is used
  } catch (const ImageError& e) {
    file.fail(std::string("cannot read a texture of the glTF file: ") + e.what());
  } catch (const SceneError& e) {
    file.fail(std::string("in ") + e.what());  // "in model.gltf:meshes[0]...: what was wrong"
  }
  std::vector<int> remap(gltf.materials.size(), -1);
  if (auto m = node.find("materials")) {
    for (const auto& [gltf_name, target] : m->members()) {
      bool found = false;
      for (size_t i = 0; i < gltf.materials.size(); ++i) {
        if (gltf.materials[i].name != gltf_name) continue;
        remap[i] = material_reference(target);
        found = true;
      }
      if (!found) {
        std::vector<std::string> names;
        for (const auto& gm : gltf.materials) names.push_back("\"" + gm.name + "\"");
        target.fail("the glTF file has no material named \"" + gltf_name +
                    "\"; its materials: " + (names.empty() ? "(none)" : join_names(names)));
      }
    }
  }
  for (const auto& w : gltf.warnings) std::cerr << path << ": warning: " << w << "\n";
  // As a mesh shape with no triangle left, and as the file on its own ("scene is empty"): the shape would add nothing.
  if (gltf.meshes.empty()) file.fail(gltf.why_empty + ", so the shape would add nothing");
  scene_.input_images.insert(scene_.input_images.end(), gltf.image_files.begin(), gltf.image_files.end());
  scene_.input_files.push_back(path);
  scene_.input_files.insert(scene_.input_files.end(), gltf.buffer_files.begin(), gltf.buffer_files.end());
  add_gltf(gltf, remap, sampling);
}

bool JsonSceneBuilder::add_gltf(const GltfScene& gltf, const std::vector<int>& remap, TriangleSampling sampling) {
  // Scene indices of the glTF's own materials, created on first use; the last slot is glTF's default material.
  std::vector<int> own(gltf.materials.size() + 1, -1);
  bool any_emitter = false;
  for (const TriangleMesh& source : gltf.meshes) {
    TriangleMesh mesh = source;
    const int gi = mesh.material >= 0 && mesh.material < static_cast<int>(gltf.materials.size())
                       ? mesh.material
                       : static_cast<int>(gltf.materials.size());
    MaterialEmission emission;
    if (gi < static_cast<int>(remap.size()) && remap[gi] >= 0) {
      mesh.material = remap[gi];
      if (auto it = material_emission_.find(mesh.material); it != material_emission_.end()) emission = it->second;
    } else {
      const PbrParams params = gi < static_cast<int>(gltf.materials.size()) ? gltf.materials[gi].params : PbrParams{};
      if (own[gi] < 0) {
        own[gi] = static_cast<int>(scene_.materials.size());
        scene_.materials.push_back(make_pbr_material(params));
      }
      mesh.material = own[gi];
      emission = {params.emissive, params.emissive_texture, params.double_sided};
    }
    // A cut-out (alphaMode MASK) is on the mesh already (mesh.alpha, set by the glTF loader): it belongs to the
    // geometry, so it stays when the shading is remapped.
    any_emitter = any_emitter || emission.emits();
    add_mesh(std::move(mesh), emission, sampling);
  }
  return any_emitter;
}

}  // namespace lumis
