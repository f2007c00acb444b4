// glTF loader on the shared sample models: triangle counts from SOURCES.md, winding against normals, transforms,
// KHR_materials_variants, interleaved and sparse accessors, scenes, cameras (every one listed, any one chosen) and
// materials.
#include <gtest/gtest.h>

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
#include "app/scene_loader.h"
#include "core/image_io.h"
#include "tests/app/gltf_test_util.h"

namespace fs = std::filesystem;
using namespace lumis;
using namespace lumis::gltf_test;

namespace {

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
  // An embedded PNG and the same external PNG, both decoded by OpenImageIO, give identical texels.
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
    EXPECT_EQ(a->image->data, b->image->data);
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
  expect_vec(normalize(cs.camera->to - cs.camera->from), {0, 0, -1});
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

TEST(GltfModels, EveryPerspectiveCameraIsListedAndCanBeChosen) {
  REQUIRE_ASSETS();
  // ToyCar: eight perspective cameras, listed in depth-first file order; the first is the default.
  const std::string path = model("ToyCar/glTF/ToyCar.gltf");
  const GltfScene car = load_gltf(path);
  ASSERT_EQ(car.cameras.size(), 8u);
  EXPECT_EQ(car.cameras[0].name, "Camera001");
  EXPECT_EQ(car.cameras[0].path, "nodes[3]");
  EXPECT_EQ(car.cameras[7].name, "Camera008");
  ASSERT_TRUE(car.camera.has_value());
  expect_vec(car.camera->from, car.cameras[0].camera.from);
  // load_scene renders through the one chosen, by number or by name, the same camera either way.
  const std::unique_ptr<Scene> by_number = load_scene(path, SceneLoadOptions{"5"});
  const std::unique_ptr<Scene> by_name = load_scene(path, SceneLoadOptions{"Camera006"});
  expect_vec(by_number->camera.from, car.cameras[5].camera.from);
  expect_vec(by_number->camera.to, car.cameras[5].camera.to);
  expect_vec(by_name->camera.from, car.cameras[5].camera.from);
  EXPECT_GT(length(car.cameras[5].camera.from - car.cameras[0].camera.from), 1e-3f);
  // An unknown camera is a usage error that lists the file's cameras; a JSON scene has no glTF cameras to choose.
  try {
    load_scene(path, SceneLoadOptions{"8"});
    FAIL() << "camera 8 of 8 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("0 'Camera001' (nodes[3])"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("7 'Camera008'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_scene(std::string(LUMIS_SOURCE_DIR) + "/scenes/cornell-sphere.json", SceneLoadOptions{"0"}),
               std::invalid_argument);
  // MultiUVTest's one camera is node 'Correction_Camera' holding camera 'Camera': either name chooses it (the
  // camera's was refused), and the list shows both.
  const std::string multi = model("MultiUVTest/glTF/MultiUVTest.gltf");
  const GltfScene uv = load_gltf(multi);
  ASSERT_EQ(uv.cameras.size(), 1u);
  EXPECT_EQ(uv.cameras[0].name, "Correction_Camera");
  EXPECT_EQ(uv.cameras[0].camera_name, "Camera");
  expect_vec(load_scene(multi, SceneLoadOptions{"Camera"})->camera.from, uv.cameras[0].camera.from);
  expect_vec(load_scene(multi, SceneLoadOptions{"Correction_Camera"})->camera.from, uv.cameras[0].camera.from);
  try {
    load_scene(multi, SceneLoadOptions{"Lens"});
    FAIL() << "camera 'Lens' accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("0 'Correction_Camera' (nodes["), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(", camera 'Camera')"), std::string::npos) << e.what();
  }
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


// TextureTransformTest's rotation quad, end to end (loader, node transforms, uv, KHR_texture_transform, texture
// lookup): the arrow texture draws a black arrow along its uv diagonal, from near (0, 0) to a tip at about (0.66,
// 0.66). The material rotates uv by 22.5 degrees about the uv origin, the quad's top-left corner, so the arrow lies on
// the line from that corner to the model's green "correct" marker. The yellow marker (rotation ignored) and the red
// one (rotation turned the other way) sit on lines 22.5 and 45 degrees away; all three are 1.1 from the corner.
// Points on the arrow's shaft are black only along the correct line (the shaft is under 9 texels wide either side;
// the lines are 15 or more texels apart at the points tested).
TEST(GltfModels, TextureTransformArrowPointsAtTheCorrectMarker) {
  REQUIRE_ASSETS();
  const auto scene = load_scene(model("TextureTransformTest/glTF/TextureTransformTest.gltf"));
  const Vec3 quad(-1.1f, -0.55f, 0);  // node "Rotation"
  const Vec3 corner = quad + Vec3(-0.5f, 0.5f, 0);
  // The markers' translations (children of "Rotation", in front of it at z = 0.01).
  const std::array<std::pair<const char*, Vec3>, 3> markers = {{{"correct", Vec3(-0.0790482f, -0.5162675f, 0)},
                                                                {"not supported", Vec3(0.2778175f, -0.2778175f, 0)},
                                                                {"error", Vec3(0.5162675f, 0.0790482f, 0)}}};
  // The albedo seen straight down -z at (x, y); the hit must be the quad (z = 0), not a marker.
  auto albedo_at = [&](Vec3 p, Vec2* uv = nullptr) {
    Hit hit;
    EXPECT_TRUE(scene->geometry.intersect(Ray(Vec3(p.x, p.y, 1), Vec3(0, 0, -1)), hit));
    EXPECT_NEAR(hit.t, 1.0f, 1e-4f);
    if (uv) *uv = hit.uv[0];
    const Color a = scene->materials.at(hit.material)->albedo(hit);
    return (a.x + a.y + a.z) / 3;
  };
  Vec2 uv;
  albedo_at(corner + Vec3(0.001f, -0.001f, 0), &uv);  // the corner is the uv origin
  EXPECT_NEAR(uv.x, 0.0f, 0.01f);
  EXPECT_NEAR(uv.y, 0.0f, 0.01f);
  for (const auto& [name, offset] : markers) {
    const Vec3 to_marker = quad + offset - corner;
    EXPECT_NEAR(length(to_marker), 1.1f, 1e-4f) << name;
    for (float r : {0.3f, 0.5f}) {
      const float a = albedo_at(corner + to_marker * (r / 1.1f));
      if (std::string(name) == "correct")
        EXPECT_LT(a, 0.05f) << "the arrow's shaft is not on the line to the " << name << " marker, at " << r;
      else
        EXPECT_GT(a, 0.5f) << "the arrow's shaft is on the line to the " << name << " marker, at " << r;
    }
  }
}
