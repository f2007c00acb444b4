// Helpers shared by the lumis JSON scene loader tests (test_scene_loader.cpp: scenes that load;
// test_scene_loader_errors.cpp: bad input and its exact location): a folder per test case, scene files written into
// it, and the error a scene must fail with.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "app/scene_error.h"
#include "app/scene_loader.h"

namespace lumis::scene_test {

namespace fs = std::filesystem;

inline const std::string kAssets = LUMIS_SHARED_ASSETS;
inline const std::string kBoxGlb = kAssets + "/gltf/Box/glTF-Binary/Box.glb";

// One folder per test case, so that ctest may run the cases in parallel.
inline fs::path test_dir_path() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return fs::temp_directory_path() /
         ("lumis_scene_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
}

inline fs::path test_dir() {
  const fs::path dir = test_dir_path();
  fs::create_directories(dir);
  return dir;
}

/// The fixture of the loader tests: removes the test case's folder when it ends, so that a run leaves nothing in
/// the temporary folder (scripts/test.sh fails a stage whose tests leave files there).
class LoaderTest : public ::testing::Test {
 protected:
  void TearDown() override { fs::remove_all(test_dir_path()); }
};

inline std::string write_file(const std::string& name, const std::string& text) {
  const fs::path p = test_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

inline std::string write_scene(const std::string& text) { return write_file("scene.json", text); }

// Load `text` as a scene that must fail; returns the error.
inline SceneError load_error(const std::string& text, const std::string& name = "scene.json") {
  const std::string path = write_file(name, text);
  try {
    load_scene(path);
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file, path);
    return e;
  }
  ADD_FAILURE() << "no SceneError for:\n" << text;
  return SceneError(path, "", "");
}

#define EXPECT_SCENE_ERROR(text, where, part)                                   \
  do {                                                                          \
    const SceneError e_ = load_error(text);                                     \
    EXPECT_EQ(e_.location, where) << e_.what();                                 \
    EXPECT_NE(e_.detail.find(part), std::string::npos) << e_.what();            \
  } while (0)

// A valid scene around one sphere; `extra` adds top-level members, `sphere` replaces the sphere's members.
inline std::string scene_with(const std::string& extra,
                              const std::string& sphere = R"("center": [0,0,0], "radius": 1, "material": "m")",
                              const std::string& materials = R"("m": {"type": "diffuse"})") {
  return R"({"materials": {)" + materials + R"(}, "shapes": [{"type": "sphere", )" + sphere + "}]" +
         (extra.empty() ? "" : ", " + extra) + "}";
}

}  // namespace lumis::scene_test
