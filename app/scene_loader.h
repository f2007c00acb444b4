// Scene files: the lumis JSON scene format (docs/scene-format.md) and glTF 2.0 files rendered with defaults.
#pragma once

#include <memory>
#include <string>

#include "integrators/scene.h"

namespace lumis {

/// Choices made while a scene loads (the command line's, before any other override applies).
struct SceneLoadOptions {
  /// A glTF file's camera to render through: its position in the file's list of perspective camera nodes (0 is the
  /// default, the first in depth-first file order) or its node's (else camera's) name. Empty: the default.
  std::string camera;
  /// --width or --height was given: both make the shape the user's, and one alone keeps a glTF camera's aspect ratio
  /// that the 512-wide default cannot (or is refused), so that ratio's clamp is not worth a warning.
  bool size_given = false;
};

/// Load a scene file: a lumis JSON scene (.json) or a glTF file (.gltf/.glb) with defaults. Returns a finalized
/// scene. Throws SceneError naming the file, the JSON pointer (or line:column) and what was expected, and
/// std::invalid_argument for a SceneLoadOptions::camera the file does not have (listing those it has) or given for
/// a JSON scene.
std::unique_ptr<Scene> load_scene(const std::string& path, const SceneLoadOptions& options = {});

/// Which of the files `scene` was loaded from a write to `out` would replace (through a symbolic or hard link too):
/// "the scene file (PATH)" for `path`, "a file the scene reads (PATH)" for one of Scene::inputs(), or "" for none.
std::string scene_file_at(const std::string& out, const std::string& path, const Scene& scene);

/// Load a lumis JSON scene from text already in memory (as if read from `path`, which names it in messages and
/// anchors relative paths). Throws SceneError like load_scene.
std::unique_ptr<Scene> load_scene_text(const std::string& text, const std::string& path);

}  // namespace lumis
