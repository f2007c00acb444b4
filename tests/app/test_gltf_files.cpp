// glTF loader on small synthetic files written here: exact transforms, mirrored nodes, strips and fans, attribute
// encodings, instancing, degenerate triangles, lamps, valid files tinygltf would refuse, '+' in URIs. Textures are in
// test_gltf_textures.cpp, the error paths in test_gltf_errors.cpp.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "app/gltf_loader.h"
#include "tests/app/gltf_synthetic.h"
#include "tests/app/gltf_test_util.h"

namespace fs = std::filesystem;
using namespace lumis;
using namespace lumis::gltf_test;

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
  // -z in camera space (scaled by 2: the near clip below). `to` is any point along it (max(1, |from|) away).
  expect_vec(normalize(s.camera->to - s.camera->from), {0, 0, -1});
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

// A node scale far from 1 (1e10, 1e-11) scales the transformed normal by det = scale^3 ... its square leaves the
// float range, yet the normals must come out unit and facing +z, not be dropped for flat shading.
TEST_F(GltfFiles, NormalsSurviveExtremeNodeScales) {
  Triangle t;
  for (const char* scale : {"[1e10,1e10,1e10]", "[1e-11,1e-11,1e-11]", "[1e12,1e12,1]"}) {
    SCOPED_TRACE(scale);
    const GltfScene s =
        load_gltf(simple("s.gltf", t.bin, t.views, t.accessors, Triangle::prim,
                         std::string(R"({"mesh":0,"scale":)") + scale + "}"));
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].normals.size(), 3u);
    for (const Vec3& n : s.meshes[0].normals) expect_vec(n, {0, 0, 1});
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
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

// Lamps (KHR_lights_punctual, as Blender exports them) are not rendered: a warning of their own counts them by type,
// in place of the bare name in the list of ignored extensions. Used without any lights, the name is listed as usual.
TEST_F(GltfFiles, PunctualLightsAreCountedInAWarning) {
  Triangle t;
  const std::string lamps =
      R"(,"extensionsUsed":["KHR_lights_punctual","KHR_materials_volume"],"extensions":{"KHR_lights_punctual":)"
      R"({"lights":[{"type":"point"},{"type":"spot","spot":{}},{"type":"point","intensity":5}]}})";
  const std::string node = R"({"mesh":0,"children":[1]},{"extensions":{"KHR_lights_punctual":{"light":0}}})";
  GltfScene s = load_gltf(simple("l.gltf", t.bin, t.views, t.accessors, Triangle::prim, node, lamps));
  EXPECT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_EQ(s.warnings[0], "ignored glTF extensions: KHR_materials_volume");
  EXPECT_EQ(s.warnings[1], "KHR_lights_punctual: not rendering the file's 3 lights (2 point, 1 spot): lumis has no "
                           "point, spot or directional lights (it renders emissive materials as a glTF file's lights)");
  s = load_gltf(simple("n.gltf", t.bin, t.views, t.accessors, Triangle::prim, R"({"mesh":0})",
                       R"(,"extensionsUsed":["KHR_lights_punctual"])"));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], "ignored glTF extensions: KHR_lights_punctual");
}

// Two fields glTF 2.0 makes optional and tinygltf 2.7 requires, both in parts lumis does not read: a skin's
// inverseBindMatrices and an animation channel's target node (KHR_animation_pointer leaves it out). Such files were
// refused ("'inverseBindMatrices' property is missing in Skin."); they load, .gltf and .glb alike.
TEST_F(GltfFiles, ValidFilesTinygltfWouldRefuseLoad) {
  Triangle t;
  GltfScene s = load_gltf(simple("skin.gltf", t.bin, t.views, t.accessors, Triangle::prim, R"({"mesh":0,"skin":0})",
                                 R"(,"skins":[{"joints":[0]}])"));
  EXPECT_EQ(triangles(s), 1u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], "skins ignored (skinned meshes are drawn in their bind pose)");
  const std::string animation = R"(,"animations":[{"samplers":[{"input":2,"output":2}],"channels":[)"
                                R"({"sampler":0,"target":{"node":0,"path":"scale"}},{"sampler":0,"target":)"
                                R"({"path":"pointer"}}]}])";
  s = load_gltf(simple("animated.gltf", t.bin, t.views, t.accessors, Triangle::prim, R"({"mesh":0})", animation));
  EXPECT_EQ(triangles(s), 1u);
  EXPECT_TRUE(s.warnings.empty());
  // The .glb is given to tinygltf with its JSON chunk replaced, its binary chunk kept: the triangle is the same.
  const std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
                           R"("meshes":[{"primitives":[)" + std::string(Triangle::prim) + R"(]}],"buffers":[)"
                           R"({"byteLength":)" + std::to_string(t.bin.bytes.size()) + R"(}],"bufferViews":)" +
                           t.views + R"(,"accessors":)" + t.accessors + animation + "}";
  const GltfScene b = load_gltf(write("animated.glb", make_glb(json, t.bin.bytes)));
  ASSERT_EQ(triangles(b), 1u);
  ASSERT_EQ(b.meshes[0].positions.size(), 3u);
  expect_vec(b.meshes[0].positions[1], {1, 0, 0});
  expect_vec(b.meshes[0].positions[2], {0, 1, 0});
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

// Normalized BYTE quaternions decode by glTF's max(c / 127, -1): -128 and 127 are -1 and 1 exactly, so (-128, 0, 0,
// 127) is a quarter turn about -x and (0, 0, 127, -128) one about -z. Dividing by 128 instead would make 127 read
// 0.992 and tilt both rotations by about half a degree (0.008 at these vertices); the rotation normalizes q, so only
// the -1 clamp's side of the range shows it.
TEST_F(GltfFiles, SnormRotationsDecodeBySpecsFormula) {
  Triangle t;
  const size_t ro = t.bin.add<int8_t>({-128, 0, 0, 127, 0, 0, 127, -128});
  const std::string views = t.views.substr(0, t.views.size() - 1) + "," + Triangle::view(ro, 8) + "]";
  const std::string acc = t.accessors.substr(0, t.accessors.size() - 1) +
                          R"(,{"bufferView":3,"componentType":5120,"normalized":true,"count":2,"type":"VEC4"}])";
  const std::string node = R"({"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"ROTATION":3}}}})";
  const GltfScene s = load_gltf(simple("q.gltf", t.bin, views, acc, Triangle::prim, node,
                                       R"(,"extensionsUsed":["EXT_mesh_gpu_instancing"])"));
  ASSERT_EQ(s.meshes.size(), 2u);
  expect_vec(s.meshes[0].positions[2], {0, 0, -1});  // (0, 1, 0), a quarter turn about -x
  expect_vec(s.meshes[1].positions[1], {0, -1, 0});  // (1, 0, 0), a quarter turn about -z
}

// A node's translation, rotation and scale, and an EXT_mesh_gpu_instancing instance's, compose as T * R * S: scale
// first, then rotate, then translate. With T (1, 2, 3), a quarter turn about z and S (2, 3, 4), the corner (1, 0, 0)
// goes to (2, 0, 0), (0, 2, 0), (1, 4, 3) and (0, 1, 0) to (0, 3, 0), (-3, 0, 0), (-2, 2, 3); any other order lands
// elsewhere (S * T * R puts (1, 0, 0) at (2, 9, 12)).
TEST_F(GltfFiles, TrsComposesAsTranslateRotateScale) {
  Triangle t;
  const std::string trs = R"("translation":[1,2,3],"rotation":[0,0,0.70710678,0.70710678],"scale":[2,3,4])";
  const GltfScene node = load_gltf(simple("n.gltf", t.bin, t.views, t.accessors, Triangle::prim,
                                          R"({"mesh":0,)" + trs + "}"));
  const size_t tr = t.bin.add<float>({1, 2, 3});
  const size_t ro = t.bin.add<float>({0, 0, 0.70710678f, 0.70710678f});
  const size_t sc = t.bin.add<float>({2, 3, 4});
  const std::string views = t.views.substr(0, t.views.size() - 1) + "," + Triangle::view(tr, 12) + "," +
                            Triangle::view(ro, 16) + "," + Triangle::view(sc, 12) + "]";
  const std::string acc = t.accessors.substr(0, t.accessors.size() - 1) +
                          R"(,{"bufferView":3,"componentType":5126,"count":1,"type":"VEC3"},)"
                          R"({"bufferView":4,"componentType":5126,"count":1,"type":"VEC4"},)"
                          R"({"bufferView":5,"componentType":5126,"count":1,"type":"VEC3"}])";
  const GltfScene instanced = load_gltf(
      simple("i.gltf", t.bin, views, acc, Triangle::prim,
             R"({"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":)"
             R"({"TRANSLATION":3,"ROTATION":4,"SCALE":5}}}})",
             R"(,"extensionsUsed":["EXT_mesh_gpu_instancing"])"));
  for (const GltfScene* s : {&node, &instanced}) {
    ASSERT_EQ(s->meshes.size(), 1u);
    expect_vec(s->meshes[0].positions[0], {1, 2, 3});
    expect_vec(s->meshes[0].positions[1], {1, 4, 3});
    expect_vec(s->meshes[0].positions[2], {-2, 2, 3});
  }
}

// A '+' in a URI is a plus sign (RFC 3986, which glTF's URIs follow); tinygltf 2.7 decodes it as a space, as a web
// form does, so a buffer named wood+stone.bin was "not found".
TEST_F(GltfFiles, PlusInAUriIsAPlusSign) {
  Triangle t;
  const std::string bytes(t.bin.bytes.begin(), t.bin.bytes.end());
  auto buffer = [&](const std::string& uri) {
    return R"({"byteLength":)" + std::to_string(bytes.size()) + R"(,"uri":")" + uri + R"("})";
  };
  auto json = [&](const std::string& buffers) {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
           R"("meshes":[{"primitives":[)" + std::string(Triangle::prim) + R"(]}],"bufferViews":)" + t.views +
           R"(,"accessors":)" + t.accessors + R"(,"buffers":[)" + buffers + "]}";
  };
  auto file = [&](const std::string& name, const std::string& buffers) { return write(name, json(buffers)); };
  write("wood+stone.bin", bytes);
  EXPECT_EQ(triangles(load_gltf(file("plus.gltf", buffer("wood+stone.bin")))), 1u);
  EXPECT_EQ(triangles(load_gltf(file("escaped.gltf", buffer("wood%2Bstone.bin")))), 1u);
  EXPECT_EQ(triangles(load_gltf(write("plus.glb", make_glb(json(buffer("wood+stone.bin")), {})))), 1u);
  // "a+b.bin" does not name a file "a b.bin".
  write("a b.bin", bytes);
  expect_error(file("space.gltf", buffer("a+b.bin")), {"space.gltf:buffers[0].uri", "'a+b.bin' not found"});
  EXPECT_EQ(triangles(load_gltf(file("space20.gltf", buffer("a%20b.bin")))), 1u);
  // Two URIs that tinygltf reads as the same file name, for two files: an error naming both, not the wrong bytes.
  write("a+b.bin", bytes);
  expect_error(file("both.gltf", buffer("a%20b.bin") + "," + buffer("a+b.bin")),
               {"both.gltf:buffers[1].uri", "'a+b.bin' and buffers[0].uri 'a%20b.bin'", "rename one"});
}
