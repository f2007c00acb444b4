// glTF 2.0 (.gltf with external or data: buffers, .glb) to world-space triangle meshes, materials and a camera.
// Errors in the file throw SceneError naming the file, a glTF path such as
// "meshes[3].primitives[0].attributes.POSITION" or "accessors[5]", and what was expected.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/geometry.h"
#include "core/math.h"
#include "core/transform.h"
#include "materials/material.h"

namespace lumis {

enum class AlphaMode { Opaque, Mask, Blend };

struct GltfMaterial {
  std::string name;
  PbrParams params;
  AlphaMode alpha_mode = AlphaMode::Opaque;  ///< Blend is rendered as Opaque (with a warning)
  float alpha_cutoff = 0.5f;
};

/// A perspective camera node of the scene.
struct GltfCamera {
  std::string name;                     ///< the node's own name (empty when it has none)
  std::string camera_name;              ///< the camera object's own name (exporters often name it apart from the node)
  std::string path;                     ///< the node's glTF path ("nodes[3]")
  Camera camera;                        ///< world space (after `transform`)
  std::optional<float> aspect;          ///< the camera's aspectRatio when the file gives one
};

struct GltfScene {
  std::vector<TriangleMesh> meshes;     ///< world space (after `transform`); mesh.material indexes `materials`
  std::vector<GltfMaterial> materials;  ///< the file's materials in order, plus a default one when a primitive has none
  std::vector<GltfCamera> cameras;      ///< perspective camera nodes of the default scene, depth-first in file order
  std::optional<Camera> camera;         ///< the first of `cameras` (what a render uses unless told otherwise)
  std::optional<float> camera_aspect;   ///< its aspectRatio when the file gives one
  Bounds3 bounds;                       ///< of all mesh vertices, world space
  std::vector<std::string> warnings;    ///< things skipped or approximated, one line each
  std::vector<std::string> image_files; ///< the external image files its materials read, resolved, once each
  std::vector<std::string> buffer_files; ///< the external buffer files it reads (not data: URIs), resolved
  std::string why_empty;  ///< when `meshes` is empty, why, as a phrase ("the glTF file has no triangle meshes")
};

/// Load the default scene (or scene 0) of a glTF file; `transform` maps glTF world space to lumis world space.
/// Without `read_cameras` (a file inside a JSON scene, which has a camera of its own) camera nodes are skipped:
/// their cameras are neither checked nor listed, nor warned about, and `cameras` stays empty.
GltfScene load_gltf(const std::string& path, const Mat4& transform = Mat4::identity(), bool read_cameras = true);

}  // namespace lumis
