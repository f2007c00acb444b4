// Scene files: the lumis JSON scene format (docs/scene-format.md) and glTF 2.0 files rendered with defaults.
#pragma once

#include <memory>
#include <string>

#include "integrators/scene.h"

namespace lumis {

/// Load a scene file: a lumis JSON scene (.json) or a glTF file (.gltf/.glb) with defaults. Returns a finalized
/// scene. Throws SceneError naming the file, the JSON pointer (or line:column) and what was expected.
std::unique_ptr<Scene> load_scene(const std::string& path);

/// Load a lumis JSON scene from text already in memory (as if read from `path`, which names it in messages and
/// anchors relative paths). Throws SceneError like load_scene.
std::unique_ptr<Scene> load_scene_text(const std::string& text, const std::string& path);

}  // namespace lumis
