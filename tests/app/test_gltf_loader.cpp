// glTF loader: the shared sample models (triangle counts from SOURCES.md, transforms, variants, materials,
// cameras) and small synthetic files written here (exact transforms, attribute encodings, every error path).
#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "app/gltf_loader.h"
#include "app/scene_error.h"
#include "core/image_io.h"

namespace fs = std::filesystem;
using namespace lumis;

namespace {

const fs::path kAssets = fs::path(LUMIS_SHARED_ASSETS) / "gltf";

#define REQUIRE_ASSETS()                                                             \
  do {                                                                               \
    if (!fs::exists(kAssets / "SOURCES.md")) GTEST_SKIP() << "no " << kAssets;       \
  } while (0)

std::string model(const std::string& rel) { return (kAssets / rel).string(); }

size_t triangles(const GltfScene& s) {
  size_t n = 0;
  for (const auto& m : s.meshes) n += m.triangle_count();
  return n;
}

/// The "degenerate triangles dropped (N)" warning's N, or 0.
size_t dropped(const GltfScene& s) {
  for (const auto& w : s.warnings) {
    std::smatch m;
    if (std::regex_search(w, m, std::regex(R"(degenerate triangles dropped \((\d+)\))"))) return std::stoul(m[1]);
  }
  return 0;
}

/// SOURCES.md's table: folder -> triangle count after instancing (the number after '/').
std::map<std::string, size_t> documented_counts() {
  std::ifstream in(kAssets / "SOURCES.md");
  std::map<std::string, size_t> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| ", 0) != 0) continue;
    std::vector<std::string> cols;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, '|');) cols.push_back(c);
    if (cols.size() < 7) continue;
    const std::string name = std::regex_replace(cols[1], std::regex(R"([\s*])"), "");
    std::smatch m;
    const std::string tri = std::regex_replace(cols[5], std::regex(","), "");
    if (std::regex_search(tri, m, std::regex(R"(\d+\s*/\s*(\d+))"))) out[name] = std::stoul(m[1]);
  }
  return out;
}

/// Geometric normals from the winding agree with the (averaged) vertex normals: dot > 0 for every triangle.
size_t winding_disagreements(const GltfScene& s, size_t* checked) {
  size_t bad = 0;
  for (const auto& m : s.meshes) {
    if (m.normals.empty()) continue;
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      const uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
      const Vec3 ng = cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
      ++*checked;
      if (!(dot(ng, m.normals[a] + m.normals[b] + m.normals[c]) > 0)) ++bad;
    }
  }
  return bad;
}

/// Structural sanity every loaded scene must have.
void expect_well_formed(const GltfScene& s, const std::string& what) {
  for (const auto& m : s.meshes) {
    const size_t n = m.positions.size();
    ASSERT_EQ(m.indices.size() % 3, 0u) << what;
    for (uint32_t i : m.indices) ASSERT_LT(i, n) << what;
    for (const Vec3& p : m.positions) ASSERT_TRUE(is_finite(p)) << what;
    ASSERT_TRUE(m.normals.empty() || m.normals.size() == n) << what;
    for (const Vec3& v : m.normals) ASSERT_NEAR(length(v), 1.0f, 1e-4f) << what;
    ASSERT_TRUE(m.tangents.empty() || m.tangents.size() == n) << what;
    ASSERT_TRUE(m.uv0.empty() || m.uv0.size() == n) << what;
    ASSERT_TRUE(m.uv1.empty() || m.uv1.size() == n) << what;
    ASSERT_TRUE(m.colors.empty() || m.colors.size() == n) << what;
    ASSERT_GE(m.material, 0) << what;
    ASSERT_LT(static_cast<size_t>(m.material), s.materials.size()) << what;
  }
  ASSERT_FALSE(s.bounds.empty()) << what;
}

void expect_same_meshes(const GltfScene& a, const GltfScene& b, const std::string& what) {
  ASSERT_EQ(a.meshes.size(), b.meshes.size()) << what;
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    const auto &x = a.meshes[i], &y = b.meshes[i];
    EXPECT_EQ(x.indices, y.indices) << what;
    ASSERT_EQ(x.positions.size(), y.positions.size()) << what;
    for (size_t k = 0; k < x.positions.size(); ++k) EXPECT_EQ(x.positions[k], y.positions[k]) << what;
    ASSERT_EQ(x.normals.size(), y.normals.size()) << what;
    for (size_t k = 0; k < x.normals.size(); ++k) EXPECT_EQ(x.normals[k], y.normals[k]) << what;
    ASSERT_EQ(x.uv0.size(), y.uv0.size()) << what;
    for (size_t k = 0; k < x.uv0.size(); ++k) {
      EXPECT_EQ(x.uv0[k].x, y.uv0[k].x) << what;
      EXPECT_EQ(x.uv0[k].y, y.uv0[k].y) << what;
    }
  }
}

// --- synthetic files ---

std::string base64(const std::vector<unsigned char>& d) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < d.size(); i += 3) {
    const uint32_t v = (d[i] << 16) | ((i + 1 < d.size() ? d[i + 1] : 0) << 8) | (i + 2 < d.size() ? d[i + 2] : 0);
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < d.size() ? k[(v >> 6) & 63] : '=';
    out += i + 2 < d.size() ? k[v & 63] : '=';
  }
  return out;
}

/// A binary buffer built piece by piece (each piece 4-byte aligned), embedded as a data: URI.
struct Bin {
  std::vector<unsigned char> bytes;
  template <typename T>
  size_t add(std::initializer_list<T> values) {
    while (bytes.size() % 4) bytes.push_back(0);
    const size_t at = bytes.size();
    for (T v : values) {
      unsigned char b[sizeof(T)];
      std::memcpy(b, &v, sizeof(T));
      bytes.insert(bytes.end(), b, b + sizeof(T));
    }
    return at;
  }
  std::string buffer_json() const {
    return R"({"byteLength":)" + std::to_string(bytes.size()) +
           R"(,"uri":"data:application/octet-stream;base64,)" + base64(bytes) + "\"}";
  }
};

class GltfFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("lumis_gltf_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const std::string p = (dir_ / name).string();
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  /// A one-primitive file: `accessors`, `views` and the primitive JSON given, one buffer from `bin`.
  std::string simple(const std::string& name, const Bin& bin, const std::string& views, const std::string& accessors,
                     const std::string& primitive, const std::string& node = R"({"mesh":0})",
                     const std::string& extra = "") {
    return write(name, R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[)" + node +
                           R"(],"meshes":[{"primitives":[)" + primitive + R"(]}],"buffers":[)" + bin.buffer_json() +
                           R"(],"bufferViews":)" + views + R"(,"accessors":)" + accessors + extra + "}");
  }
  /// load_gltf must throw a SceneError whose message holds every one of `parts`.
  void expect_error(const std::string& path, std::initializer_list<std::string> parts) {
    try {
      load_gltf(path);
      ADD_FAILURE() << path << ": expected a SceneError";
    } catch (const SceneError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
      for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
    }
  }
  fs::path dir_;
};

/// One triangle (0,0,0) (1,0,0) (0,1,0) with normal +z, ushort indices: views 0 (positions), 1 (normals), 2
/// (indices); accessors 0, 1, 2 likewise.
struct Triangle {
  Bin bin;
  std::string views, accessors;
  Triangle() {
    const size_t p = bin.add<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const size_t n = bin.add<float>({0, 0, 1, 0, 0, 1, 0, 0, 1});
    const size_t i = bin.add<uint16_t>({0, 1, 2});
    views = "[" + view(p, 36) + "," + view(n, 36) + "," + view(i, 6) + "]";
    accessors = R"([{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
                R"({"bufferView":1,"componentType":5126,"count":3,"type":"VEC3"},)"
                R"({"bufferView":2,"componentType":5123,"count":3,"type":"SCALAR"}])";
  }
  static std::string view(size_t off, size_t len, size_t stride = 0) {
    return R"({"buffer":0,"byteOffset":)" + std::to_string(off) + R"(,"byteLength":)" + std::to_string(len) +
           (stride ? R"(,"byteStride":)" + std::to_string(stride) : "") + "}";
  }
  static constexpr const char* prim = R"({"attributes":{"POSITION":0,"NORMAL":1},"indices":2})";
};

void expect_vec(Vec3 a, Vec3 b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// Sample models

TEST(GltfModels, TriangleCountsMatchSourcesAndWindingAgreesWithNormals) {
  REQUIRE_ASSETS();
  const auto counts = documented_counts();
  // One variant per model (the other variants are compared below); MetalRoughSpheres has its own test.
  const std::vector<std::pair<std::string, std::string>> models = {
      {"AlphaBlendModeTest", "AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf"},
      {"Box", "Box/glTF/Box.gltf"},
      {"BoxInterleaved", "BoxInterleaved/glTF/BoxInterleaved.gltf"},
      {"BoxWithSpaces", "BoxWithSpaces/glTF/Box With Spaces.gltf"},
      {"Cameras", "Cameras/glTF/Cameras.gltf"},
      {"CornellBox", "CornellBox/CornellBox.gltf"},
      {"CornellBoxVinc3r", "CornellBoxVinc3r/glTF/cornellBox-2.80-Eevee-gltf.gltf"},
      {"DamagedHelmet", "DamagedHelmet/glTF-Binary/DamagedHelmet.glb"},
      {"EmissiveStrengthTest", "EmissiveStrengthTest/glTF/EmissiveStrengthTest.gltf"},
      {"MeshPrimitiveModes", "MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf"},
      {"MultiUVTest", "MultiUVTest/glTF/MultiUVTest.gltf"},
      {"MultipleScenes", "MultipleScenes/glTF/MultipleScenes.gltf"},
      {"NegativeScaleTest", "NegativeScaleTest/glTF/NegativeScaleTest.gltf"},
      {"NormalTangentMirrorTest", "NormalTangentMirrorTest/glTF/NormalTangentMirrorTest.gltf"},
      {"OrientationTest", "OrientationTest/glTF/OrientationTest.gltf"},
      {"SimpleInstancing", "SimpleInstancing/glTF/SimpleInstancing.gltf"},
      {"SimpleSparseAccessor", "SimpleSparseAccessor/glTF/SimpleSparseAccessor.gltf"},
      {"TextureCoordinateTest", "TextureCoordinateTest/glTF/TextureCoordinateTest.gltf"},
      {"TextureSettingsTest", "TextureSettingsTest/glTF/TextureSettingsTest.gltf"},
      {"TextureTransformTest", "TextureTransformTest/glTF/TextureTransformTest.gltf"},
      {"ToyCar", "ToyCar/glTF/ToyCar.gltf"},
      {"TriangleWithoutIndices", "TriangleWithoutIndices/glTF/TriangleWithoutIndices.gltf"},
      {"TwoSidedPlane", "TwoSidedPlane/glTF/TwoSidedPlane.gltf"},
      {"VertexColorTest", "VertexColorTest/glTF/VertexColorTest.gltf"},
  };
  EXPECT_EQ(counts.size(), models.size() + 1) << "SOURCES.md lists models this test does not load";
  for (const auto& [name, rel] : models) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(counts.count(name)) << name << " missing from SOURCES.md";
    const GltfScene s = load_gltf(model(rel));
    expect_well_formed(s, name);
    EXPECT_EQ(triangles(s), counts.at(name));
    EXPECT_EQ(dropped(s), 0u);
    size_t checked = 0;
    EXPECT_EQ(winding_disagreements(s, &checked), 0u);
    if (name == "NegativeScaleTest" || name == "OrientationTest" || name == "Box") {
      EXPECT_EQ(checked, triangles(s)) << "every triangle has vertex normals";
    }
  }
}

TEST(GltfModels, MetalRoughSpheresMillionTriangles) {
  REQUIRE_ASSETS();
  const GltfScene s = load_gltf(model("MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb"));
  expect_well_formed(s, "MetalRoughSpheres");
  // Sphere poles repeat a vertex: those triangles have no area and are dropped, with a warning that counts them.
  EXPECT_GT(dropped(s), 0u);
  EXPECT_EQ(triangles(s) + dropped(s), documented_counts().at("MetalRoughSpheresNoTextures"));
  EXPECT_EQ(s.meshes.size(), 123u);
  EXPECT_EQ(s.materials.size(), 99u);  // 98 in the file and the default one for the primitive without material
  size_t checked = 0;
  EXPECT_EQ(winding_disagreements(s, &checked), 0u);
}

TEST(GltfModels, VariantsMatrixInterleavedAndSparse) {
  REQUIRE_ASSETS();
  const std::vector<std::vector<std::string>> groups = {
      {"Box/glTF/Box.gltf", "Box/glTF-Binary/Box.glb", "Box/glTF-Embedded/Box.gltf"},
      {"BoxInterleaved/glTF/BoxInterleaved.gltf", "BoxInterleaved/glTF-Binary/BoxInterleaved.glb",
       "BoxInterleaved/glTF-Embedded/BoxInterleaved.gltf"},
      {"SimpleSparseAccessor/glTF/SimpleSparseAccessor.gltf",
       "SimpleSparseAccessor/glTF-Embedded/SimpleSparseAccessor.gltf"},
      {"TriangleWithoutIndices/glTF/TriangleWithoutIndices.gltf",
       "TriangleWithoutIndices/glTF-Embedded/TriangleWithoutIndices.gltf"},
  };
  for (const auto& g : groups) {
    const GltfScene first = load_gltf(model(g[0]));
    for (size_t i = 1; i < g.size(); ++i) expect_same_meshes(first, load_gltf(model(g[i])), g[i]);
  }
  // An embedded PNG (decoded by tinygltf) and the same external PNG (decoded by OpenImageIO) agree after sRGB
  // decoding.
  const GltfScene ext = load_gltf(model("EmissiveStrengthTest/glTF/EmissiveStrengthTest.gltf"));
  const GltfScene glb = load_gltf(model("EmissiveStrengthTest/glTF-Binary/EmissiveStrengthTest.glb"));
  expect_same_meshes(ext, glb, "EmissiveStrengthTest");
  ASSERT_EQ(ext.materials.size(), glb.materials.size());
  int textured = 0;
  for (size_t i = 0; i < ext.materials.size(); ++i) {
    const auto &a = ext.materials[i].params.base_color_texture, &b = glb.materials[i].params.base_color_texture;
    ASSERT_EQ(a.has_value(), b.has_value());
    if (!a) continue;
    ++textured;
    ASSERT_EQ(a->image->data.size(), b->image->data.size());
    EXPECT_EQ(a->image->channel_names, b->image->channel_names);
    for (size_t k = 0; k < a->image->data.size(); ++k) ASSERT_NEAR(a->image->data[k], b->image->data[k], 1e-6f);
  }
  EXPECT_EQ(textured, 1);

  // Box: a matrix node, and the loader transform applied after it.
  const GltfScene s = load_gltf(model("Box/glTF/Box.gltf"));
  expect_vec(s.bounds.lo, Vec3(-0.5f));
  expect_vec(s.bounds.hi, Vec3(0.5f));
  // The loader's transform applies after the file's: scale (1,2,3) then move by (10,0,0).
  const GltfScene t = load_gltf(model("Box/glTF/Box.gltf"), Mat4::translate({10, 0, 0}) * Mat4::scale({1, 2, 3}));
  expect_vec(t.bounds.lo, {9.5f, -1, -1.5f});
  expect_vec(t.bounds.hi, {10.5f, 1, 1.5f});
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(t.meshes.size(), 1u);
  // Box's corners are all (+-0.5, +-0.5, +-0.5): the node's 90-degree rotation keeps that, and the loader's scale
  // applied after it gives |y| = 1 and |z| = 1.5 (applied before it, the rotation would swap the two).
  for (const Vec3& p : t.meshes[0].positions) {
    EXPECT_FLOAT_EQ(std::abs(p.y), 1.0f);
    EXPECT_FLOAT_EQ(std::abs(p.z), 1.5f);
  }

  // Interleaved and sparse accessors against plain data.
  const GltfScene box = load_gltf(model("Box/glTF/Box.gltf"));
  const GltfScene inter = load_gltf(model("BoxInterleaved/glTF/BoxInterleaved.gltf"));
  ASSERT_EQ(box.meshes.size(), 1u);
  ASSERT_EQ(inter.meshes.size(), 1u);
  const auto &a = box.meshes[0], &b = inter.meshes[0];
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_EQ(a.positions[i], b.positions[i]) << i;
    EXPECT_EQ(a.normals[i], b.normals[i]) << i;
  }
  EXPECT_EQ(a.indices, b.indices);

  // SimpleSparseAccessor: a 7x2 grid of unit points, with vertices 8, 10 and 12 replaced by the sparse values.
  const GltfScene sp = load_gltf(model("SimpleSparseAccessor/glTF/SimpleSparseAccessor.gltf"));
  ASSERT_EQ(sp.meshes.size(), 1u);
  const auto& p = sp.meshes[0].positions;
  ASSERT_EQ(p.size(), 14u);
  for (int i = 0; i < 14; ++i) {
    Vec3 expected(float(i % 7), float(i / 7), 0);
    if (i == 8) expected = {1, 2, 0};
    if (i == 10) expected = {3, 3, 0};
    if (i == 12) expected = {5, 4, 0};
    EXPECT_EQ(p[i], expected) << "vertex " << i;
  }
}

TEST(GltfModels, ScenesModesAndCameras) {
  REQUIRE_ASSETS();
  // MultipleScenes: the default scene is 1, holding the square (2 triangles), not scene 0's triangle.
  const GltfScene ms = load_gltf(model("MultipleScenes/glTF/MultipleScenes.gltf"));
  EXPECT_EQ(triangles(ms), 2u);
  ASSERT_EQ(ms.meshes.size(), 1u);
  EXPECT_EQ(ms.meshes[0].positions.size(), 4u);

  // MeshPrimitiveModes: triangles, strip and fan give 16; points and lines one warning in total.
  const GltfScene mp = load_gltf(model("MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf"));
  EXPECT_EQ(triangles(mp), 16u);
  ASSERT_EQ(mp.warnings.size(), 1u);
  EXPECT_NE(mp.warnings[0].find("points and lines skipped (4 primitives)"), std::string::npos) << mp.warnings[0];
  // All three meshes lie in z = 0 facing +z: strips and fans must keep one winding.
  for (const auto& m : mp.meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      const Vec3 ng = cross(m.positions[m.indices[3 * t + 1]] - m.positions[m.indices[3 * t]],
                            m.positions[m.indices[3 * t + 2]] - m.positions[m.indices[3 * t]]);
      EXPECT_GT(ng.z, 0) << m.name << " triangle " << t;
    }

  // Cameras: the perspective one (yfov 0.7 rad, aspect 1) at (0.5, 0.5, 3) looking down -z; orthographic skipped.
  const GltfScene cs = load_gltf(model("Cameras/glTF/Cameras.gltf"));
  ASSERT_TRUE(cs.camera.has_value());
  EXPECT_NEAR(cs.camera->fov_y_degrees, 0.7f * 180 / kPi, 1e-4f);
  ASSERT_TRUE(cs.camera_aspect.has_value());
  EXPECT_EQ(*cs.camera_aspect, 1.0f);
  expect_vec(cs.camera->from, {0.5f, 0.5f, 3});
  expect_vec(cs.camera->to, {0.5f, 0.5f, 2});
  expect_vec(cs.camera->up, {0, 1, 0});
  EXPECT_NEAR(cs.camera->near_clip, 0.01f, 1e-7f);
  EXPECT_EQ(std::count_if(cs.warnings.begin(), cs.warnings.end(),
                          [](const std::string& w) { return w.find("orthographic") != std::string::npos; }),
            1);

  // SimpleInstancing: EXT_mesh_gpu_instancing gives 125 placed copies of the 12-triangle cube.
  const GltfScene si = load_gltf(model("SimpleInstancing/glTF/SimpleInstancing.gltf"));
  EXPECT_EQ(si.meshes.size(), 125u);
  EXPECT_GT(si.bounds.diagonal().x, 10.0f);
}

TEST(GltfModels, Materials) {
  REQUIRE_ASSETS();
  // EmissiveStrengthTest: emissive = (0.1, 0.5, 0.9) x emissiveStrength.
  const GltfScene es = load_gltf(model("EmissiveStrengthTest/glTF/EmissiveStrengthTest.gltf"));
  int emitters = 0;
  for (const auto& m : es.materials) {
    std::smatch r;
    if (!std::regex_match(m.name, r, std::regex(R"(Emit(\d+))"))) continue;
    ++emitters;
    expect_vec(m.params.emissive, Vec3(0.1f, 0.5f, 0.9f) * std::stof(r[1]), 1e-5f);
  }
  EXPECT_EQ(emitters, 5);

  // TextureTransformTest: offset, rotation and scale parsed per material; textures 0 and 1 use the clamping
  // sampler, the others have none (repeat).
  const GltfScene tt = load_gltf(model("TextureTransformTest/glTF/TextureTransformTest.gltf"));
  std::map<std::string, TextureTransform> tx;
  for (const auto& m : tt.materials) {
    ASSERT_TRUE(m.params.base_color_texture.has_value()) << m.name;
    tx[m.name] = m.params.base_color_texture->transform;
    const bool clamped = m.name.rfind("Offset", 0) == 0 || m.name == "Rotation" || m.name == "Scale" || m.name == "All";
    EXPECT_EQ(m.params.base_color_texture->wrap_s, clamped ? WrapMode::ClampToEdge : WrapMode::Repeat) << m.name;
    EXPECT_EQ(m.params.base_color_texture->wrap_t, clamped ? WrapMode::ClampToEdge : WrapMode::Repeat) << m.name;
  }
  EXPECT_EQ(tx.at("Offset U").offset.x, 0.5f);
  EXPECT_EQ(tx.at("Offset V").offset.y, 0.5f);
  EXPECT_FLOAT_EQ(tx.at("Rotation").rotation, 0.39269908f);
  EXPECT_EQ(tx.at("Scale").scale.x, 1.5f);
  EXPECT_EQ(tx.at("All").offset.x, -0.2f);
  EXPECT_EQ(tx.at("All").offset.y, -0.1f);
  EXPECT_FLOAT_EQ(tx.at("All").rotation, 0.3f);
  EXPECT_EQ(tx.at("All").scale.y, 1.5f);
  EXPECT_EQ(tx.at("Correct").rotation, 0.0f);
  // Materials sharing one texture share one decoded image.
  EXPECT_EQ(tt.materials[0].params.base_color_texture->image.get(),
            tt.materials[1].params.base_color_texture->image.get());

  // TextureSettingsTest: wrap modes per sampler.
  const GltfScene ts = load_gltf(model("TextureSettingsTest/glTF/TextureSettingsTest.gltf"));
  std::map<std::string, std::pair<WrapMode, WrapMode>> wrap;
  for (const auto& m : ts.materials)
    if (m.params.base_color_texture)
      wrap[m.name] = {m.params.base_color_texture->wrap_s, m.params.base_color_texture->wrap_t};
  EXPECT_EQ(wrap.at("TextureMirrorMaterialT"), std::make_pair(WrapMode::Repeat, WrapMode::MirroredRepeat));
  EXPECT_EQ(wrap.at("TextureMirrorMaterialS"), std::make_pair(WrapMode::MirroredRepeat, WrapMode::Repeat));
  EXPECT_EQ(wrap.at("TextureClampMaterialT"), std::make_pair(WrapMode::Repeat, WrapMode::ClampToEdge));
  EXPECT_EQ(wrap.at("TextureClampMaterialS"), std::make_pair(WrapMode::ClampToEdge, WrapMode::Repeat));

  // AlphaBlendModeTest: MASK materials put their cutoff on the meshes; BLEND is one warning.
  const GltfScene ab = load_gltf(model("AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf"));
  std::map<std::string, float> cutoffs;
  for (const auto& m : ab.meshes)
    if (m.alpha) {
      cutoffs[ab.materials[m.material].name] = m.alpha->cutoff;
      EXPECT_TRUE(m.alpha->texture.has_value());
    }
  EXPECT_EQ(cutoffs.size(), 3u);
  EXPECT_EQ(cutoffs.at("MatCutoff25"), 0.25f);
  EXPECT_EQ(cutoffs.at("MatCutoff75"), 0.75f);
  EXPECT_EQ(cutoffs.at("MatCutoffDefault"), 0.5f);
  EXPECT_EQ(std::count_if(ab.warnings.begin(), ab.warnings.end(),
                          [](const std::string& w) { return w.find("BLEND") != std::string::npos; }),
            1);

  // MultiUVTest: the emissive texture reads TEXCOORD_1, which the mesh carries.
  const GltfScene mu = load_gltf(model("MultiUVTest/glTF/MultiUVTest.gltf"));
  ASSERT_TRUE(mu.materials[0].params.emissive_texture.has_value());
  EXPECT_EQ(mu.materials[0].params.emissive_texture->tex_coord, 1);
  EXPECT_EQ(mu.meshes[0].uv1.size(), mu.meshes[0].positions.size());

  // VertexColorTest: COLOR_0 on the second mesh only.
  const GltfScene vc = load_gltf(model("VertexColorTest/glTF/VertexColorTest.gltf"));
  int coloured = 0;
  for (const auto& m : vc.meshes) coloured += !m.colors.empty();
  EXPECT_EQ(coloured, 1);
}

// ---------------------------------------------------------------------------------------------------------------
// Synthetic files

TEST_F(GltfFiles, HierarchyMatrixThenTrsAndCamera) {
  Triangle t;
  // Parent: matrix = translate(1,2,3) * scale(2) (column-major); child: translate(1,0,0) * rotate 90 deg about z,
  // carrying the mesh and a camera.
  const std::string nodes =
      R"({"matrix":[2,0,0,0, 0,2,0,0, 0,0,2,0, 1,2,3,1],"children":[1]},)"
      R"({"mesh":0,"camera":0,"translation":[1,0,0],"rotation":[0,0,0.70710678,0.70710678]})";
  const std::string path = simple("h.gltf", t.bin, t.views, t.accessors, Triangle::prim, nodes,
                                  R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}}])");
  const GltfScene s = load_gltf(path, Mat4::translate({0, 0, 10}));
  ASSERT_EQ(s.meshes.size(), 1u);
  const auto& m = s.meshes[0];
  // (0,0,0) -> child (1,0,0) -> parent (3,2,3); (1,0,0) -> (1,1,0) -> (3,4,3); (0,1,0) -> (0,0,0) -> (1,2,3);
  // then the loader's +10 in z.
  expect_vec(m.positions[0], {3, 2, 13});
  expect_vec(m.positions[1], {3, 4, 13});
  expect_vec(m.positions[2], {1, 2, 13});
  expect_vec(m.normals[0], {0, 0, 1});
  ASSERT_TRUE(s.camera.has_value());
  expect_vec(s.camera->from, {3, 2, 13});
  expect_vec(s.camera->to, {3, 2, 11});  // -z in camera space, scaled by 2
  expect_vec(s.camera->up, {-1, 0, 0});  // +y rotated 90 degrees about z
  EXPECT_NEAR(s.camera->near_clip, 0.2f, 1e-6f);
  EXPECT_FALSE(s.camera_aspect.has_value());
  EXPECT_EQ(s.materials.size(), 1u);  // the default material, for the primitive without one
  EXPECT_EQ(m.material, 0);
}

TEST_F(GltfFiles, MirroredNodeFlipsWindingNormalsStayOutward) {
  Triangle t;
  const size_t tan = t.bin.add<float>({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1});
  const std::string views = t.views.substr(0, t.views.size() - 1) + "," + Triangle::view(tan, 48) + "]";
  const std::string acc = t.accessors.substr(0, t.accessors.size() - 1) +
                          R"(,{"bufferView":3,"componentType":5126,"count":3,"type":"VEC4"}])";
  const std::string prim = R"({"attributes":{"POSITION":0,"NORMAL":1,"TANGENT":3},"indices":2})";
  for (const char* scale : {"[-1,1,1]", "[1,1,-1]", "[-2,-3,-4]", "[1,1,1]"}) {
    SCOPED_TRACE(scale);
    const GltfScene s = load_gltf(simple("m.gltf", t.bin, views, acc, prim, std::string(R"({"mesh":0,"scale":)") +
                                                                              scale + "}"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const auto& m = s.meshes[0];
    const Vec3 ng = normalize(cross(m.positions[m.indices[1]] - m.positions[m.indices[0]],
                                    m.positions[m.indices[2]] - m.positions[m.indices[0]]));
    // The surface is the plane z = const; the vertex normal is the inverse transpose of +z.
    const float sz = std::string(scale) == "[1,1,-1]" ? -1.0f : std::string(scale) == "[-2,-3,-4]" ? -1.0f : 1.0f;
    expect_vec(m.normals[0], {0, 0, sz});
    expect_vec(ng, m.normals[0]);
    // Bitangent = w * cross(n, t) must be the transformed object bitangent (+y scaled).
    const Vec3 b = m.tangents[0].w * cross(m.normals[0], m.tangents[0].xyz());
    const float sy = std::string(scale) == "[-2,-3,-4]" ? -1.0f : 1.0f;
    expect_vec(b, {0, sy, 0});
  }
}

TEST_F(GltfFiles, StripsFansAndAttributeEncodings) {
  Bin bin;
  // Interleaved view: position (3 floats) + TEXCOORD_0 as normalized ushort (2) = 16-byte stride, 5 vertices in a
  // zig-zag strip in z = 0.
  const float pos[5][3] = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {2, 0, 0}};
  const uint16_t uv[5][2] = {{0, 65535}, {32768, 0}, {65535, 65535}, {0, 0}, {1, 2}};
  for (int i = 0; i < 5; ++i) {
    bin.add<float>({pos[i][0], pos[i][1], pos[i][2]});
    bin.bytes.resize(bin.bytes.size() + 4);
    std::memcpy(&bin.bytes[bin.bytes.size() - 4], uv[i], 4);
  }
  // COLOR_0: VEC3 normalized unsigned byte, 4-byte stride.
  const size_t col = bin.add<uint8_t>({255, 0, 51, 0, 0, 255, 0, 0, 128, 128, 128, 0, 0, 0, 0, 0, 255, 255, 255, 0});
  // TEXCOORD_1: no bufferView (zeros) with one sparse replacement at vertex 3.
  const size_t si = bin.add<uint8_t>({3});
  const size_t sv = bin.add<float>({0.5f, 0.25f});
  const std::string views = "[" + Triangle::view(0, 80, 16) + "," + Triangle::view(col, 20, 4) + "," +
                            Triangle::view(si, 1) + "," + Triangle::view(sv, 8) + "]";
  const std::string acc =
      R"([{"bufferView":0,"componentType":5126,"count":5,"type":"VEC3"},)"
      R"({"bufferView":0,"byteOffset":12,"componentType":5123,"normalized":true,"count":5,"type":"VEC2"},)"
      R"({"bufferView":1,"componentType":5121,"normalized":true,"count":5,"type":"VEC3"},)"
      R"({"componentType":5126,"count":5,"type":"VEC2","sparse":{"count":1,)"
      R"("indices":{"bufferView":2,"componentType":5121},"values":{"bufferView":3}}}])";
  const std::string attrs = R"("attributes":{"POSITION":0,"TEXCOORD_0":1,"COLOR_0":2,"TEXCOORD_1":3})";
  for (int mode : {5, 6}) {
    SCOPED_TRACE(mode);
    const GltfScene s =
        load_gltf(simple("s.gltf", bin, views, acc, "{" + attrs + R"(,"mode":)" + std::to_string(mode) + "}"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const auto& m = s.meshes[0];
    EXPECT_EQ(m.triangle_count(), 3u);
    for (size_t t = 0; t < 3; ++t) {
      const Vec3 ng = cross(m.positions[m.indices[3 * t + 1]] - m.positions[m.indices[3 * t]],
                            m.positions[m.indices[3 * t + 2]] - m.positions[m.indices[3 * t]]);
      // The strip's first triangle (0,1,2) faces -z; all others must match it. The fan (0,1,2),(0,2,3),(0,3,4)
      // mixes orientations by construction here, so only the strip is checked for a single orientation.
      if (mode == 5) {
        EXPECT_LT(ng.z, 0) << t;
      }
    }
    if (mode == 6) {
      const std::vector<uint32_t> fan = {0, 1, 2, 0, 2, 3, 0, 3, 4};
      EXPECT_EQ(m.indices, fan);
    } else {
      const std::vector<uint32_t> strip = {0, 1, 2, 2, 1, 3, 2, 3, 4};
      EXPECT_EQ(m.indices, strip);
    }
    EXPECT_EQ(m.positions[3], Vec3(1, 1, 0));
    EXPECT_EQ(m.uv0[0].x, 0.0f);
    EXPECT_EQ(m.uv0[0].y, 1.0f);
    EXPECT_EQ(m.uv0[1].x, 32768 / 65535.0f);
    EXPECT_EQ(m.uv0[4].y, 2 / 65535.0f);
    EXPECT_EQ(m.colors[0].x, 1.0f);
    EXPECT_EQ(m.colors[0].z, 0.2f);
    EXPECT_EQ(m.colors[0].w, 1.0f);  // VEC3 colours are opaque
    EXPECT_EQ(m.colors[2].x, 128 / 255.0f);
    EXPECT_EQ(m.uv1[2].x, 0.0f);
    EXPECT_EQ(m.uv1[3].x, 0.5f);
    EXPECT_EQ(m.uv1[3].y, 0.25f);
    EXPECT_TRUE(m.normals.empty());  // no NORMAL: flat shading from the winding
  }
}

TEST_F(GltfFiles, TexturesEmbeddedExternalSamplersAndTransforms) {
  // A 2x1 RGBA PNG: used embedded (data: URI, decoded by tinygltf) and external (OpenImageIO).
  const std::string png = (dir_ / "tex.png").string();
  {
    const unsigned char px[8] = {200, 100, 50, 128, 0, 255, 10, 255};
    auto out = OIIO::ImageOutput::create(png);
    OIIO::ImageSpec spec(2, 1, 4, OIIO::TypeDesc::UINT8);
    spec.alpha_channel = 3;
    spec.attribute("oiio:UnassociatedAlpha", 1);
    ASSERT_TRUE(out && out->open(png, spec) && out->write_image(OIIO::TypeDesc::UINT8, px));
    out->close();
  }
  std::ifstream f(png, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  Triangle t;
  const std::string extra =
      R"(,"images":[{"uri":"data:image/png;base64,)" + base64(bytes) + R"("},{"uri":"tex.png"}],)"
      R"("samplers":[{"magFilter":9728,"wrapS":33648,"wrapT":33071}],)"
      R"("textures":[{"source":0,"sampler":0},{"source":1}],)"
      R"("materials":[{"alphaMode":"MASK","alphaCutoff":0.3,"doubleSided":true,"emissiveFactor":[1,1,1],)"
      R"("pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.5],"metallicFactor":0.25,"roughnessFactor":0.75,)"
      R"("baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"offset":[0.5,0],"rotation":1,)"
      R"("scale":[2,3],"texCoord":1}}},"metallicRoughnessTexture":{"index":1}},)"
      R"("emissiveTexture":{"index":0},"normalTexture":{"index":1,"scale":0.5}}],)"
      R"("extensionsUsed":["KHR_texture_transform","KHR_materials_volume"])";
  const std::string prim = R"({"attributes":{"POSITION":0,"NORMAL":1},"indices":2,"material":0})";
  const GltfScene s = load_gltf(simple("t.gltf", t.bin, t.views, t.accessors, prim, R"({"mesh":0})", extra));
  ASSERT_EQ(s.materials.size(), 1u);
  const PbrParams& p = s.materials[0].params;
  EXPECT_EQ(s.materials[0].alpha_mode, AlphaMode::Mask);
  EXPECT_EQ(p.metallic, 0.25f);
  EXPECT_EQ(p.roughness, 0.75f);
  EXPECT_EQ(p.base_alpha, 0.5f);
  EXPECT_TRUE(p.double_sided);
  EXPECT_EQ(p.normal_scale, 0.5f);
  ASSERT_TRUE(p.base_color_texture && p.metallic_roughness_texture && p.emissive_texture && p.normal_texture);
  const Texture& bc = *p.base_color_texture;
  EXPECT_EQ(bc.wrap_s, WrapMode::MirroredRepeat);
  EXPECT_EQ(bc.wrap_t, WrapMode::ClampToEdge);
  EXPECT_TRUE(bc.nearest);
  EXPECT_EQ(bc.tex_coord, 1);  // KHR_texture_transform's texCoord overrides
  EXPECT_EQ(bc.transform.offset.x, 0.5f);
  EXPECT_EQ(bc.transform.rotation, 1.0f);
  EXPECT_EQ(bc.transform.scale.y, 3.0f);
  EXPECT_EQ(p.emissive_texture->tex_coord, 0);
  EXPECT_EQ(p.emissive_texture->image.get(), bc.image.get());  // one sRGB decode shared
  EXPECT_FALSE(p.metallic_roughness_texture->nearest);
  EXPECT_EQ(p.metallic_roughness_texture->wrap_s, WrapMode::Repeat);
  EXPECT_EQ(p.normal_texture->image.get(), p.metallic_roughness_texture->image.get());  // one linear decode shared
  // sRGB decoded colour, untouched alpha (embedded); linear values (external).
  const Image& srgb = *bc.image;
  ASSERT_EQ(srgb.channels, 4);
  EXPECT_NEAR(srgb.at(0, 0, 0), srgb_to_linear(200 / 255.0f), 1e-6f);
  EXPECT_NEAR(srgb.at(0, 0, 3), 128 / 255.0f, 1e-6f);
  EXPECT_NEAR(srgb.at(1, 0, 1), 1.0f, 1e-6f);
  const Image& lin = *p.metallic_roughness_texture->image;
  EXPECT_NEAR(lin.at(0, 0, 0), 200 / 255.0f, 1e-6f);
  EXPECT_NEAR(lin.at(0, 0, 3), 128 / 255.0f, 1e-6f);
  // MASK: the mesh carries the alpha test with the factor and the base colour texture.
  ASSERT_TRUE(s.meshes[0].alpha.has_value());
  EXPECT_EQ(s.meshes[0].alpha->cutoff, 0.3f);
  EXPECT_EQ(s.meshes[0].alpha->factor, 0.5f);
  ASSERT_TRUE(s.meshes[0].alpha->texture.has_value());
  EXPECT_EQ(s.meshes[0].alpha->texture->image.get(), bc.image.get());
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("KHR_materials_volume"), std::string::npos);
}

TEST_F(GltfFiles, InstancingAndDegenerateTriangles) {
  Triangle t;
  // Two more triangles: one repeating a vertex, one collinear; both dropped and counted.
  const size_t p2 = t.bin.add<float>({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0});
  const size_t i2 = t.bin.add<uint16_t>({0, 1, 2, 0, 0, 1, 0, 1, 3});
  const size_t tr = t.bin.add<float>({0, 0, 0, 10, 0, 0});
  const size_t ro = t.bin.add<int16_t>({0, 0, 32767, 0, 0, 0, 0, 32767});  // normalized: 180 deg about z, identity
  const std::string views = "[" + Triangle::view(p2, 48) + "," + Triangle::view(i2, 18) + "," +
                            Triangle::view(tr, 24) + "," + Triangle::view(ro, 16) + "]";
  const std::string acc = R"([{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},)"
                          R"({"bufferView":1,"componentType":5123,"count":9,"type":"SCALAR"},)"
                          R"({"bufferView":2,"componentType":5126,"count":2,"type":"VEC3"},)"
                          R"({"bufferView":3,"componentType":5122,"normalized":true,"count":2,"type":"VEC4"}])";
  const std::string node = R"({"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":)"
                           R"({"TRANSLATION":2,"ROTATION":3}}}})";
  const GltfScene s = load_gltf(simple("i.gltf", t.bin, views, acc, R"({"attributes":{"POSITION":0},"indices":1})",
                                       node, R"(,"extensionsUsed":["EXT_mesh_gpu_instancing"])"));
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].triangle_count(), 1u);
  EXPECT_EQ(s.meshes[1].triangle_count(), 1u);
  expect_vec(s.meshes[0].positions[1], {-1, 0, 0});  // rotated half a turn about z
  expect_vec(s.meshes[1].positions[1], {11, 0, 0});  // moved by 10
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], "degenerate triangles dropped (4)");
}

TEST_F(GltfFiles, ErrorsNameTheGltfPath) {
  Triangle t;
  // Node hierarchies that are not trees.
  const std::string base = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)";
  expect_error(write("cycle.gltf", base + R"([{"children":[1]},{"children":[2]},{"children":[0]}]})"),
               {"nodes[", "cycle"});
  expect_error(write("self.gltf", base + R"([{"children":[0]}]})"), {"nodes[0].children[0]", "cycle"});
  expect_error(write("dag.gltf", base + R"([{"children":[1,2]},{"children":[2]},{}]})"),
               {"nodes[1].children[0]", "tree"});
  expect_error(write("child.gltf", base + R"([{"children":[5]}]})"), {"nodes[0].children[0]", "out of range"});

  // Accessors.
  expect_error(simple("acc.gltf", t.bin, t.views, t.accessors, R"({"attributes":{"POSITION":7},"indices":2})"),
               {"meshes[0].primitives[0].attributes.POSITION", "accessor index 7 out of range"});
  expect_error(simple("range.gltf", t.bin, t.views,
                      R"([{"bufferView":0,"byteOffset":4,"componentType":5126,"count":3,"type":"VEC3"}])",
                      R"({"attributes":{"POSITION":0}})"),
               {"accessors[0]", "need 40 bytes", "bufferViews[0] has 36"});
  expect_error(simple("type.gltf", t.bin, t.views, t.accessors, R"({"attributes":{"POSITION":2}})"),
               {"accessors[2]", "expected VEC3", "attributes.POSITION"});
  expect_error(simple("view.gltf", t.bin, "[" + Triangle::view(0, 4000) + "]", t.accessors,
                      R"({"attributes":{"POSITION":0}})"),
               {"bufferViews[0]", "exceeds buffers[0]"});
  expect_error(simple("count.gltf", t.bin, t.views,
                      R"([{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
                      R"({"bufferView":1,"componentType":5126,"count":2,"type":"VEC3"}])",
                      R"({"attributes":{"POSITION":0,"NORMAL":1}})"),
               {"attributes.NORMAL", "expected 3"});
  Bin bad_index = t.bin;
  std::memcpy(&bad_index.bytes[76], "\x03\x00", 2);  // third index (at byte 72 + 4) -> 3
  expect_error(simple("index.gltf", bad_index, t.views, t.accessors, Triangle::prim),
               {"meshes[0].primitives[0].indices", "index value 3"});
  Bin nan = t.bin;
  const float qnan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan.bytes[16], &qnan, 4);
  expect_error(simple("nan.gltf", nan, t.views, t.accessors, Triangle::prim), {"accessors[0]", "not finite"});
  expect_error(simple("mode.gltf", t.bin, t.views, t.accessors, R"({"attributes":{"POSITION":0},"mode":9})"),
               {"meshes[0].primitives[0].mode"});
  expect_error(simple("mat.gltf", t.bin, t.views, t.accessors, R"({"attributes":{"POSITION":0},"material":3})"),
               {"meshes[0].primitives[0].material", "out of range"});

  // Images: missing (URI named), unsupported formats, external and embedded.
  const std::string prim = R"({"attributes":{"POSITION":0},"material":0})";
  const std::string mat = R"(,"textures":[{"source":0}],)"
                          R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}])";
  expect_error(simple("img.gltf", t.bin, t.views, t.accessors, prim, R"({"mesh":0})",
                      R"(,"images":[{"uri":"missing%20texture.png"}])" + mat),
               {"images[0]", "missing%20texture.png", "not found"});
  write("tex.ktx2", "not an image at all");
  expect_error(simple("ktx.gltf", t.bin, t.views, t.accessors, prim, R"({"mesh":0})",
                      R"(,"images":[{"uri":"tex.ktx2"}])" + mat),
               {"images[0]", "tex.ktx2"});
  expect_error(simple("webp.gltf", t.bin, t.views, t.accessors, prim, R"({"mesh":0})",
                      R"(,"images":[{"bufferView":0,"mimeType":"image/webp"}])" + mat),
               {"images[0].mimeType", "unsupported image format"});
  expect_error(simple("tex.gltf", t.bin, t.views, t.accessors, prim, R"({"mesh":0})",
                      R"(,"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":4}}}])"),
               {"materials[0].pbrMetallicRoughness.baseColorTexture.index", "out of range"});

  // Whole-file problems: not JSON, truncated .glb, absent file, unsupported required extension.
  expect_error(write("junk.gltf", "{ this is not json"), {"invalid glTF"});
  std::string glb("glTF\x02\0\0\0\xe8\x03\0\0\x08\0\0\0JSON{}      ", 28);
  expect_error(write("short.glb", glb), {"invalid .glb"});
  expect_error((dir_ / "absent.gltf").string(), {"no such file"});
  expect_error(simple("req.gltf", t.bin, t.views, t.accessors, R"({"attributes":{"POSITION":0}})", R"({"mesh":0})",
                      R"(,"extensionsRequired":["KHR_draco_mesh_compression"])"),
               {"extensionsRequired", "KHR_draco_mesh_compression"});
  // A real .glb cut short.
  if (fs::exists(kAssets / "Box/glTF-Binary/Box.glb")) {
    std::ifstream in(model("Box/glTF-Binary/Box.glb"), std::ios::binary);
    const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(all.size(), 100u);
    expect_error(write("cut.glb", all.substr(0, all.size() - 40)), {"invalid .glb"});
    expect_error(write("cut2.glb", all.substr(0, 30)), {"invalid .glb"});
  }
}
