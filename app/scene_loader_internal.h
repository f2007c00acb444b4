// Shared by app/scene_loader.cpp (lumis JSON scenes) and app/gltf_scene.cpp (glTF files rendered with defaults); not
// part of scene_loader.h's interface.
#pragma once

#include <memory>
#include <string>

#include "app/scene_loader.h"

namespace lumis {

constexpr int kMaxResolution = 16384;  // per side; 16384^2 = 2^28 pixels, about 3 GiB of float RGB accumulators

/// Reject geometry or a given camera (at `camera_location`; empty for a framing camera) too far from the origin,
/// or geometry too small, for float arithmetic (see kMaxCoordinate, kMinSize). near_location: where the camera's
/// near clip distance is given (empty: none is). Throws SceneError naming `path`.
void check_extent(const Scene& scene, const std::string& path, const std::string& camera_location,
                  const std::string& near_location = "");

/// A glTF file (.gltf/.glb) as a finalized scene with defaults (see gltf_scene.cpp). Throws as load_scene does.
std::unique_ptr<Scene> load_gltf_scene(const std::string& path, const SceneLoadOptions& options);

}  // namespace lumis
