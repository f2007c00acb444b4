// Helpers shared by the glTF loader tests (test_gltf_models.cpp, test_gltf_files.cpp, test_gltf_errors.cpp): where
// the shared sample models are, triangle and dropped-triangle counts of a loaded file, and a vector comparison.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

#include "app/gltf_loader.h"

namespace lumis::gltf_test {

namespace fs = std::filesystem;

inline const fs::path kAssets = fs::path(LUMIS_SHARED_ASSETS) / "gltf";

#define REQUIRE_ASSETS()                                                             \
  do {                                                                               \
    if (!fs::exists(kAssets / "SOURCES.md")) GTEST_SKIP() << "no " << kAssets;       \
  } while (0)

inline std::string model(const std::string& rel) { return (kAssets / rel).string(); }

inline size_t triangles(const GltfScene& s) {
  size_t n = 0;
  for (const auto& m : s.meshes) n += m.triangle_count();
  return n;
}

/// The "degenerate triangles dropped (N)" warning's N, or 0.
inline size_t dropped(const GltfScene& s) {
  for (const auto& w : s.warnings) {
    std::smatch m;
    if (std::regex_search(w, m, std::regex(R"(degenerate triangles dropped \((\d+)\))"))) return std::stoul(m[1]);
  }
  return 0;
}

inline void expect_vec(Vec3 a, Vec3 b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

}  // namespace lumis::gltf_test
