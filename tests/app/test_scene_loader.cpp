// The lumis JSON scene loader: the documented example and every shipped scene load and assemble as specified, and
// each kind of bad input fails with the exact location (JSON pointer or line:column) and the telling part of the
// message.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <unistd.h>

#include "app/scene_error.h"
#include "app/scene_loader.h"
#include "core/image_io.h"

namespace lumis {
namespace {

namespace fs = std::filesystem;

const std::string kAssets = LUMIS_SHARED_ASSETS;
const std::string kBoxGlb = kAssets + "/gltf/Box/glTF-Binary/Box.glb";

// One folder per test case, so that ctest may run the cases in parallel.
fs::path test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() /
                       ("lumis_scene_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path p = test_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

std::string write_scene(const std::string& text) { return write_file("scene.json", text); }

// Load `text` as a scene that must fail; returns the error.
SceneError load_error(const std::string& text, const std::string& name = "scene.json") {
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
std::string scene_with(const std::string& extra, const std::string& sphere = R"("center": [0,0,0], "radius": 1, "material": "m")",
                       const std::string& materials = R"("m": {"type": "diffuse"})") {
  return R"({"materials": {)" + materials + R"(}, "shapes": [{"type": "sphere", )" + sphere + "}]" +
         (extra.empty() ? "" : ", " + extra) + "}";
}

const std::string kExample = R"({
  "camera":    {"type": "perspective", "from": [0,1,4], "to": [0,1,0], "up": [0,1,0], "fov": 40},
  "film":      {"width": 512, "height": 512},
  "render":    {"integrator": "nee_mis", "spp": 64, "max_depth": 8, "sampler": "stratified", "seed": 0},
  "materials": {"grey":  {"type": "diffuse", "albedo": [0.5,0.5,0.5]},
                "gold":  {"type": "pbr", "base_color": [1,0.8,0.4], "metallic": 1, "roughness": 0.2}},
  "shapes":    [{"type": "gltf", "file": "BOX", "transform": {"translate": [0,0,0], "rotate": [0,90,0], "scale": 1},
                 "materials": {"Red": "grey"}},
                {"type": "sphere", "center": [0,1,0], "radius": 1, "material": "gold"},
                {"type": "quad", "origin": [-1,0,-1], "edge_u": [2,0,0], "edge_v": [0,0,2], "material": "grey"}],
  "lights":    [{"type": "sphere", "center": [0,3,0], "radius": 0.25, "radiance": [20,20,20]},
                {"type": "quad", "origin": [0,2,0], "edge_u": [0.5,0,0], "edge_v": [0,0,0.5], "radiance": [10,10,10]},
                {"type": "environment", "radiance": [1,1,1]}]
})";

std::string example_with_box() { return std::regex_replace(kExample, std::regex("BOX"), kBoxGlb); }

// ---------------------------------------------------------------------------------------------------------------
// Scenes that load.

TEST(SceneLoader, DocumentedExampleLoadsAndAssembles) {
  const auto scene = load_scene(write_scene(example_with_box()));
  EXPECT_EQ(scene->settings.integrator, "nee_mis");
  EXPECT_EQ(scene->settings.spp, 64u);
  EXPECT_EQ(scene->settings.max_depth, 8);
  EXPECT_EQ(scene->settings.sampler, SamplerType::Stratified);
  EXPECT_EQ(scene->settings.width, 512);
  EXPECT_FLOAT_EQ(scene->camera.fov_y_degrees, 40);
  EXPECT_EQ(scene->camera.from, Vec3(0, 1, 4));
  // grey, gold; the box's own material "Red" is remapped to grey, so no third material is made.
  EXPECT_EQ(scene->materials.size(), 2u);
  ASSERT_EQ(scene->lights.size(), 3u);
  EXPECT_EQ(scene->environment, 2);
  EXPECT_TRUE(scene->lights[2]->is_environment());
  EXPECT_EQ(scene->light_selector.size(), 3u);
  // box mesh, sphere, quad, sphere light, quad light.
  ASSERT_EQ(scene->geometry.geometry_count(), 5u);
  EXPECT_TRUE(scene->geometry.is_mesh(0));
  EXPECT_EQ(scene->geometry.mesh(0).material, 0);  // grey
  EXPECT_EQ(scene->geometry.mesh(0).light, -1);
  EXPECT_EQ(scene->geometry.sphere(1).material, 1);  // gold
  EXPECT_EQ(scene->geometry.sphere(1).light, -1);
  // The sphere light is a pure emitter.
  EXPECT_EQ(scene->geometry.sphere(3).material, -1);
  EXPECT_EQ(scene->geometry.sphere(3).light, 0);
  EXPECT_FLOAT_EQ(scene->geometry.sphere(3).radius, 0.25f);
  // The quad light: corners origin, +u, +u+v, +v; triangles (0,1,2), (0,2,3) facing cross(u, v) = -y.
  const TriangleMesh& q = scene->geometry.mesh(4);
  EXPECT_EQ(q.material, -1);
  EXPECT_EQ(q.light, 1);
  ASSERT_EQ(q.positions.size(), 4u);
  EXPECT_EQ(q.positions[2], Vec3(0.5f, 2, 0.5f));
  EXPECT_EQ(q.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  const Vec3 n = cross(q.positions[1] - q.positions[0], q.positions[2] - q.positions[0]);
  EXPECT_LT(n.y, 0);
}

TEST(SceneLoader, EveryShippedSceneLoads) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(LUMIS_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW({
      const auto scene = load_scene(entry.path().string());
      EXPECT_GT(scene->geometry.geometry_count(), 0u);
      EXPECT_GT(scene->lights.size(), 0u);
    });
    ++count;
  }
  EXPECT_GE(count, 2);  // cornell-sphere.json and furnace.json at least
}

TEST(SceneLoader, DefaultSceneIsTheSpecifiedCornellBox) {
  const auto scene = load_scene(std::string(LUMIS_SOURCE_DIR) + "/scenes/cornell-sphere.json");
  EXPECT_EQ(scene->settings.width, 512);
  EXPECT_EQ(scene->settings.height, 512);
  EXPECT_EQ(scene->settings.integrator, "nee_mis");
  EXPECT_EQ(scene->settings.spp, 64u);
  EXPECT_EQ(scene->settings.max_depth, 8);
  ASSERT_EQ(scene->lights.size(), 1u);
  EXPECT_EQ(scene->environment, -1);
  // Every wall faces the inside of the box (its centre is at (0, 1, 0)).
  for (uint32_t id = 0; id < scene->geometry.geometry_count(); ++id) {
    if (!scene->geometry.is_mesh(id)) continue;
    const TriangleMesh& m = scene->geometry.mesh(id);
    const Vec3 n = cross(m.positions[1] - m.positions[0], m.positions[2] - m.positions[0]);
    EXPECT_GT(dot(n, Vec3(0, 1, 0) - m.positions[0]), 0) << m.name;
  }
}

TEST(SceneLoader, MissingSectionsTakeRenderSettingsDefaultsAndAFramingCamera) {
  const auto scene = load_scene(write_scene(scene_with("")));
  const RenderSettings d;
  EXPECT_EQ(scene->settings.integrator, d.integrator);
  EXPECT_EQ(scene->settings.spp, d.spp);
  EXPECT_EQ(scene->settings.max_depth, d.max_depth);
  EXPECT_EQ(scene->settings.rr_depth, d.rr_depth);
  EXPECT_EQ(scene->settings.sampler, d.sampler);
  EXPECT_EQ(scene->settings.light_selection, d.light_selection);
  EXPECT_EQ(scene->settings.width, d.width);
  EXPECT_EQ(scene->settings.height, d.height);
  // The framing camera looks at the unit sphere's centre from outside it, seeing all of it.
  EXPECT_EQ(scene->camera.to, Vec3(0, 0, 0));
  const float dist = length(scene->camera.from);
  EXPECT_GT(dist, 1.0f / std::sin(20 * kPi / 180));
  EXPECT_GT(scene->camera.from.z, 0);
}

TEST(SceneLoader, RenderKeysAreRead) {
  const auto scene = load_scene(write_scene(scene_with(
      R"("render": {"integrator": "mis", "spp": 16, "max_depth": 3, "rr_depth": 0, "sampler": "sobol", "seed": 7,
                    "light_selection": "power", "mis_heuristic": "power", "uniform_measure": "solid_angle",
                    "mis_light_probability": 0.25, "time": 2.5, "exposure": -1}, "film": {"width": 64, "height": 32})")));
  const RenderSettings& s = scene->settings;
  EXPECT_EQ(s.integrator, "mis");
  EXPECT_EQ(s.spp, 16u);
  EXPECT_EQ(s.max_depth, 3);
  EXPECT_EQ(s.rr_depth, 0);
  EXPECT_EQ(s.sampler, SamplerType::Sobol);
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.light_selection, LightSelection::Power);
  EXPECT_EQ(s.mis_heuristic, MisHeuristic::Power);
  EXPECT_EQ(s.uniform_measure, UniformMeasure::SolidAngle);
  EXPECT_FLOAT_EQ(s.mis_light_probability, 0.25f);
  EXPECT_FLOAT_EQ(s.time_budget, 2.5f);
  EXPECT_FLOAT_EQ(s.exposure, -1);
  EXPECT_EQ(s.width, 64);
  EXPECT_EQ(s.height, 32);
}

// The documented transform conventions: scale, then rotate X, Y, Z (degrees, right-handed), then translate; a
// "matrix" is row-major with the translation in the last column.
TEST(SceneLoader, TransformConventions) {
  auto mesh_vertex = [](const std::string& transform) {
    const auto scene = load_scene(write_scene(
        R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [{"type": "mesh", "material": "m",
            "positions": [[1,0,0], [0,1,0], [0,0,1]], "indices": [0,1,2], "transform": )" + transform + "}]}"));
    return scene->geometry.mesh(0).positions;
  };
  auto near = [](Vec3 a, Vec3 b) { return length(a - b) < 1e-5f; };
  auto p = mesh_vertex(R"({"scale": 2, "rotate": [0, 90, 0], "translate": [0, 1, 0]})");
  EXPECT_TRUE(near(p[0], {0, 1, -2}));  // (2,0,0) -> Ry(90) -> (0,0,-2) -> +y
  p = mesh_vertex(R"({"rotate": [90, 90, 0]})");
  EXPECT_TRUE(near(p[1], {1, 0, 0}));   // X first: (0,1,0) -> (0,0,1); then Y: -> (1,0,0)
  p = mesh_vertex(R"({"scale": [1, 3, 1]})");
  EXPECT_TRUE(near(p[1], {0, 3, 0}));
  p = mesh_vertex(R"({"matrix": [1,0,0,5, 0,1,0,0, 0,0,1,0, 0,0,0,1]})");
  EXPECT_TRUE(near(p[0], {6, 0, 0}));
}

TEST(SceneLoader, MirroringTransformKeepsTheFrontFace) {
  const auto scene = load_scene(write_scene(
      R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [{"type": "mesh", "material": "m",
          "positions": [[0,0,0], [1,0,0], [0,1,0]], "normals": [[0,0,1], [0,0,1], [0,0,1]], "indices": [0,1,2],
          "transform": {"scale": [1, 1, -1]}}]})"));
  const TriangleMesh& m = scene->geometry.mesh(0);
  const Vec3 ng = cross(m.positions[m.indices[1]] - m.positions[m.indices[0]],
                        m.positions[m.indices[2]] - m.positions[m.indices[0]]);
  EXPECT_LT(m.normals[0].z, 0);
  EXPECT_GT(dot(ng, m.normals[0]), 0);
}

TEST(SceneLoader, EmissionMakesShapesLightsThatStayGeometry) {
  const auto scene = load_scene(write_scene(
      R"({"materials": {"m": {"type": "diffuse"}, "glow": {"type": "pbr", "emissive": [2, 2, 2]}},
          "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m", "emission": [3,3,3]},
                     {"type": "quad", "origin": [0,0,0], "edge_u": [1,0,0], "edge_v": [0,1,0], "material": "glow"},
                     {"type": "mesh", "positions": [[0,0,0], [1,0,0], [0,1,0]], "indices": [0,1,2], "material": "m",
                      "emission": [1,0,0], "sampling": "area"}]})"));
  ASSERT_EQ(scene->lights.size(), 3u);
  EXPECT_EQ(scene->geometry.sphere(0).material, 0);
  EXPECT_EQ(scene->geometry.sphere(0).light, 0);
  EXPECT_EQ(scene->geometry.mesh(1).material, 1);
  EXPECT_EQ(scene->geometry.mesh(1).light, 1);
  EXPECT_EQ(scene->geometry.mesh(2).light, 2);
}

TEST(SceneLoader, GltfFileAloneGetsFramingCameraAndWhiteSky) {
  const auto scene = load_scene(kBoxGlb);
  ASSERT_GE(scene->environment, 0);
  EXPECT_TRUE(scene->lights[scene->environment]->is_environment());
  EXPECT_EQ(scene->lights.size(), 1u);
  // Box.glb spans [-0.5, 0.5]^3: the camera is outside its bounding sphere, looking at the centre.
  EXPECT_LT(length(scene->camera.to), 1e-5f);
  EXPECT_GT(length(scene->camera.from), std::sqrt(0.75f));
}

TEST(SceneLoader, GltfEmissiveMeshesBecomeMeshLightsAndNoSkyIsAdded) {
  const auto scene = load_scene(kAssets + "/gltf/EmissiveStrengthTest/glTF-Binary/EmissiveStrengthTest.glb");
  EXPECT_EQ(scene->environment, -1);
  ASSERT_GT(scene->lights.size(), 0u);
  size_t lit = 0;
  for (uint32_t id = 0; id < scene->geometry.geometry_count(); ++id)
    if (scene->geometry.is_mesh(id) && scene->geometry.mesh(id).light >= 0) {
      ++lit;
      EXPECT_GE(scene->geometry.mesh(id).material, 0);  // still shaded geometry
    }
  EXPECT_EQ(lit, scene->lights.size());
}

TEST(SceneLoader, EnvironmentMapAndTexturesLoad) {
  Image sky(8, 4, {"R", "G", "B"});
  for (float& v : sky.data) v = 0.5f;
  write_image((test_dir() / "sky.exr").string(), sky);
  const std::string png = kAssets + "/gltf/BoxWithSpaces/glTF/glTF Logo With Spaces.png";
  const auto scene = load_scene(write_scene(
      R"({"materials": {"t": {"type": "pbr", "base_color_texture": ")" + png + R"(", "metallic": 0},
                        "d": {"type": "diffuse", "texture": ")" + png + R"("}},
          "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "t"},
                     {"type": "sphere", "center": [3,0,0], "radius": 1, "material": "d"}],
          "lights": [{"type": "environment", "file": "sky.exr", "scale": 2, "rotation": 90}]})"));
  EXPECT_EQ(scene->environment, 0);
  EXPECT_TRUE(scene->lights[0]->is_environment());
  EXPECT_EQ(scene->materials.size(), 2u);
}

// ---------------------------------------------------------------------------------------------------------------
// Errors: syntax (line:column).

TEST(SceneLoaderErrors, SyntaxErrorGivesLineAndColumn) {
  // Line 2 lacks its comma; the parser gives up at the last character of the string "render" on line 3 (the
  // same place nlohmann's own message names).
  const SceneError e = load_error("{\n  \"film\": {\"width\": 5}\n  \"render\": {}\n}");
  EXPECT_EQ(e.location, "3:10") << e.what();
  EXPECT_NE(e.detail.find("invalid JSON"), std::string::npos) << e.what();
  EXPECT_NE(e.detail.find("expected '}'"), std::string::npos) << e.what();
}

TEST(SceneLoaderErrors, TruncatedFileGivesPositionAtTheEnd) {
  const SceneError e = load_error("{\n  \"film\": {\"width\": 5}");
  EXPECT_EQ(e.location, "2:23") << e.what();
  EXPECT_NE(e.detail.find("end of input"), std::string::npos) << e.what();
}

TEST(SceneLoaderErrors, OverflowingNumberIsRejectedWithPosition) {
  const SceneError e = load_error("{\"film\": {\"width\": 1e999}}");
  EXPECT_EQ(e.location, "1:24") << e.what();  // the last digit of 1e999
  EXPECT_NE(e.detail.find("number overflow"), std::string::npos) << e.what();
}

TEST(SceneLoaderErrors, DuplicateKey) {
  EXPECT_SCENE_ERROR(scene_with(R"("film": {"width": 64, "width": 32})"), "/film/width", "duplicate key");
}

// Errors: structure, types and unknown keys.

TEST(SceneLoaderErrors, TopLevelMustBeAnObject) {
  EXPECT_SCENE_ERROR("[1, 2]", "", "expected an object, found an array of 2 elements");
}

TEST(SceneLoaderErrors, UnknownTopLevelKeyListsValidKeys) {
  const SceneError e = load_error(R"({"shape": []})");
  EXPECT_EQ(e.location, "/shape");
  EXPECT_NE(e.detail.find("unknown key \"shape\" (did you mean \"shapes\"?)"), std::string::npos) << e.what();
  EXPECT_NE(e.detail.find("valid keys: version, camera, film, render, materials, shapes, lights"), std::string::npos)
      << e.what();
}

TEST(SceneLoaderErrors, UnknownShapeKey) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radus": 1, "material": "m")"), "/shapes/0/radus",
                     "did you mean \"radius\"");
}

TEST(SceneLoaderErrors, UnsupportedVersion) {
  EXPECT_SCENE_ERROR(scene_with(R"("version": 2)"), "/version", "expected 1, found the number 2");
}

TEST(SceneLoaderErrors, WrongTypeForWidth) {
  EXPECT_SCENE_ERROR(scene_with(R"("film": {"width": "512"})"), "/film/width",
                     "expected an integer >= 1, found the string \"512\"");
}

TEST(SceneLoaderErrors, ZeroWidth) {
  EXPECT_SCENE_ERROR(scene_with(R"("film": {"width": 0})"), "/film/width", "found the number 0");
}

TEST(SceneLoaderErrors, AbsurdResolution) {
  EXPECT_SCENE_ERROR(scene_with(R"("film": {"width": 512, "height": 100000})"), "/film/height",
                     "absurd resolution 512 x 100000: at most 16384 pixels per side");
}

TEST(SceneLoaderErrors, ZeroSpp) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"spp": 0})"), "/render/spp", "expected an integer in [1, 1073741824]");
}

TEST(SceneLoaderErrors, FractionalSpp) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"spp": 1.5})"), "/render/spp", "found the number 1.5");
}

TEST(SceneLoaderErrors, UnknownIntegratorListsValidOnes) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"integrator": "path"})"), "/render/integrator",
                     "unknown integrator \"path\"; valid: uniform, bsdf, light, mis, nee_mis");
}

TEST(SceneLoaderErrors, UnknownSamplerListsValidOnes) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"sampler": "sobel"})"), "/render/sampler",
                     "unknown sampler \"sobel\" (did you mean \"sobol\"?); valid: independent, stratified, sobol");
}

TEST(SceneLoaderErrors, UnknownLightSelectionListsValidOnes) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"light_selection": "best"})"), "/render/light_selection",
                     "valid: uniform, power, importance");
}

TEST(SceneLoaderErrors, ProbabilityOutOfRange) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"mis_light_probability": 1.5})"), "/render/mis_light_probability",
                     "expected a number in [0, 1], found the number 1.5");
}

// Errors: cameras.

TEST(SceneLoaderErrors, CameraWithoutDirection) {
  EXPECT_SCENE_ERROR(scene_with(R"("camera": {"from": [0,0,5], "to": [0,0,5]})"), "/camera/to", "must differ");
}

TEST(SceneLoaderErrors, FieldOfViewOutOfRange) {
  EXPECT_SCENE_ERROR(scene_with(R"("camera": {"from": [0,0,5], "to": [0,0,0], "fov": 180})"), "/camera/fov",
                     "strictly between 0 and 180");
}

// Errors: materials.

TEST(SceneLoaderErrors, UnknownMaterialTypeListsValidOnes) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1, "material": "m")", R"("m": {"type": "glass"})"),
                     "/materials/m/type", "unknown material type \"glass\"; valid: diffuse, pbr, ggx");
}

TEST(SceneLoaderErrors, AlbedoAboveOne) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1, "material": "m")",
                                R"("m": {"type": "diffuse", "albedo": [0.5, 1.5, 0.5]})"),
                     "/materials/m/albedo/1", "expected a number in [0, 1], found the number 1.5");
}

TEST(SceneLoaderErrors, ColorWithTwoComponents) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1, "material": "m")",
                                R"("m": {"type": "diffuse", "albedo": [0.5, 0.5]})"),
                     "/materials/m/albedo", "expected an array of 3 numbers, found an array of 2 elements");
}

TEST(SceneLoaderErrors, MisspelledPbrKey) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1, "material": "m")",
                                R"("m": {"type": "pbr", "roughnes": 0.5})"),
                     "/materials/m/roughnes", "did you mean \"roughness\"");
}

TEST(SceneLoaderErrors, MissingTextureFile) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1, "material": "m")",
                                R"("m": {"type": "diffuse", "texture": "no-such.png"})"),
                     "/materials/m/texture", "file not found");
}

// Errors: shapes.

TEST(SceneLoaderErrors, NegativeRadius) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": -1, "material": "m")"), "/shapes/0/radius",
                     "found the number -1");
}

TEST(SceneLoaderErrors, RadiusBeyondFloatRange) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1e39, "material": "m")"), "/shapes/0/radius",
                     "a finite number within float range");
}

TEST(SceneLoaderErrors, UnknownMaterialReference) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1, "material": "gol")"), "/shapes/0/material",
                     "unknown material \"gol\"; defined materials: m");
}

TEST(SceneLoaderErrors, ShapeWithoutMaterial) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1)"), "/shapes/0",
                     "missing required key \"material\"");
}

TEST(SceneLoaderErrors, UnknownShapeTypeListsValidOnes) {
  EXPECT_SCENE_ERROR(R"({"shapes": [{"type": "cube"}]})", "/shapes/0/type",
                     "unknown shape type \"cube\"; valid: sphere, quad, mesh, gltf");
}

TEST(SceneLoaderErrors, DegenerateQuad) {
  EXPECT_SCENE_ERROR(R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [{"type": "quad", "origin": [0,0,0],
                         "edge_u": [1,0,0], "edge_v": [2,0,0], "material": "m"}]})",
                     "/shapes/0/edge_v", "not parallel");
}

TEST(SceneLoaderErrors, MeshIndexOutOfRange) {
  EXPECT_SCENE_ERROR(R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [{"type": "mesh", "material": "m",
                         "positions": [[0,0,0], [1,0,0], [0,1,0]], "indices": [0, 1, 3]}]})",
                     "/shapes/0/indices/2", "expected an integer in [0, 2], found the number 3");
}

TEST(SceneLoaderErrors, MissingGltfFile) {
  EXPECT_SCENE_ERROR(R"({"shapes": [{"type": "gltf", "file": "missing.glb"}]})", "/shapes/0/file",
                     "file not found");
}

TEST(SceneLoaderErrors, GltfMaterialNameNotInFile) {
  EXPECT_SCENE_ERROR(R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [{"type": "gltf", "file": ")" + kBoxGlb +
                         R"(", "materials": {"Blue": "m"}}]})",
                     "/shapes/0/materials/Blue", "no material named \"Blue\"; its materials: \"Red\"");
}

TEST(SceneLoaderErrors, MatrixTogetherWithTranslate) {
  EXPECT_SCENE_ERROR(R"({"shapes": [{"type": "gltf", "file": ")" + kBoxGlb +
                         R"(", "transform": {"translate": [1,0,0], "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}}]})",
                     "/shapes/0/transform/translate", "\"matrix\" replaces translate/rotate/scale");
}

// Errors: lights.

TEST(SceneLoaderErrors, UnknownLightTypeListsValidOnes) {
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "point"}]})", "/lights/0/type",
                     "unknown light type \"point\"; valid: sphere, quad, environment");
}

TEST(SceneLoaderErrors, BlackRadiance) {
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "sphere", "center": [0,0,0], "radius": 1, "radiance": [0,0,0]}]})",
                     "/lights/0/radiance", "at least one positive component");
}

TEST(SceneLoaderErrors, UnknownQuadSamplingListsValidOnes) {
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "quad", "origin": [0,0,0], "edge_u": [1,0,0], "edge_v": [0,1,0],
                         "radiance": [1,1,1], "sampling": "solid_angle"}]})",
                     "/lights/0/sampling", "valid: spherical_rectangle, area");
}

TEST(SceneLoaderErrors, SecondEnvironment) {
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "environment", "radiance": [1,1,1]},
                                    {"type": "environment", "radiance": [1,1,1]}]})",
                     "/lights/1", "only one environment light");
}

TEST(SceneLoaderErrors, EnvironmentWithRadianceAndFile) {
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "environment", "radiance": [1,1,1], "file": "sky.exr"}]})", "/lights/0",
                     "exactly one of \"radiance\"");
}

TEST(SceneLoaderErrors, EnvironmentMapMustBeLinear) {
  const std::string png = kAssets + "/gltf/BoxWithSpaces/glTF/glTF Logo With Spaces.png";
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "environment", "file": ")" + png + R"("}]})", "/lights/0/file",
                     "must be a linear .exr or .hdr file");
}

// Errors: whole files.

TEST(SceneLoaderErrors, EmptyScene) {
  EXPECT_SCENE_ERROR(R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [], "lights": []})", "",
                     "scene is empty");
}

TEST(SceneLoaderErrors, MissingSceneFile) {
  const std::string path = (test_dir() / "absent.json").string();
  try {
    load_scene(path);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file, path);
    EXPECT_EQ(e.location, "");
    EXPECT_EQ(e.detail, "no such scene file");
  }
}

TEST(SceneLoaderErrors, UnknownFileExtension) {
  const std::string path = write_file("scene.obj", "v 0 0 0\n");
  try {
    load_scene(path);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(e.detail.find("unknown scene file type \".obj\"; expected .json, .gltf or .glb"), std::string::npos);
  }
}

}  // namespace
}  // namespace lumis
