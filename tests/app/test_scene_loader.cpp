// The lumis JSON scene loader: the documented example and every shipped scene load and assemble as specified
// (bad input: test_scene_loader_errors.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <string>
#include <tuple>
#include <utility>

#include "core/image_io.h"
#include "tests/app/gltf_synthetic.h"
#include "tests/app/png_test_util.h"
#include "tests/app/scene_loader_test_util.h"

namespace lumis {
namespace {

using namespace scene_test;
using SceneLoader = LoaderTest;

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

TEST_F(SceneLoader, DocumentedExampleLoadsAndAssembles) {
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

TEST_F(SceneLoader, EveryShippedSceneLoads) {
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

TEST_F(SceneLoader, DefaultSceneIsTheSpecifiedCornellBox) {
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

TEST_F(SceneLoader, MissingSectionsTakeRenderSettingsDefaultsAndAFramingCamera) {
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

// In a tall image the horizontal field of view is the narrower one: the framing camera fits the scene's bounding
// sphere to it, so the sides are not cropped (and in a wide one, to the vertical field of view).
TEST_F(SceneLoader, FramingCameraFitsTheNarrowerFieldOfView) {
  for (const auto& [w, h] : {std::pair{100, 400}, std::pair{400, 100}}) {
    const std::string film = R"("film": {"width": )" + std::to_string(w) + R"(, "height": )" + std::to_string(h) + "}";
    const auto scene = load_scene(write_scene(scene_with(film)));
    const Camera& c = scene->camera;
    const float half_y = 0.5f * c.fov_y_degrees * kPi / 180;
    const float half_x = std::atan(std::tan(half_y) * float(w) / float(h));
    // The unit sphere's bounding box [-1, 1]^3 has a bounding sphere of radius sqrt(3) about the origin.
    const float seen = std::asin(std::sqrt(3.0f) / length(c.from - c.to));
    EXPECT_LT(seen, std::min(half_x, half_y)) << w << " x " << h;
    EXPECT_GT(seen, 0.9f * std::min(half_x, half_y)) << w << " x " << h << ": framed, not lost in the distance";
  }
}

TEST_F(SceneLoader, RenderKeysAreRead) {
  const auto scene = load_scene(write_scene(scene_with(
      R"("render": {"integrator": "mis", "spp": 16, "max_depth": 3, "rr_depth": 0, "sampler": "sobol", "seed": 7,
                    "light_selection": "power", "mis_heuristic": "power", "uniform_measure": "solid_angle",
                    "mis_light_probability": 0.25, "time": 0.05, "exposure": -1},
         "film": {"width": 64, "height": 32})")));
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
  EXPECT_EQ(s.time_budget, 0.05);  // exactly: read as a double, not rounded to float (0.0500000007)
  EXPECT_FLOAT_EQ(s.exposure, -1);
  EXPECT_EQ(s.width, 64);
  EXPECT_EQ(s.height, 32);
}

// The documented transform conventions: scale, then rotate X, Y, Z (degrees, right-handed), then translate; a
// "matrix" is row-major with the translation in the last column.
TEST_F(SceneLoader, TransformConventions) {
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
  // A small uniform scale is no more singular as a matrix than as "scale" (an absolute bound rejected it).
  p = mesh_vertex(R"({"matrix": [1e-5,0,0,0, 0,1e-5,0,0, 0,0,1e-5,0, 0,0,0,1]})");
  EXPECT_FLOAT_EQ(p[2].z, 1e-5f);
  p = mesh_vertex(R"({"scale": 1e-5})");
  EXPECT_FLOAT_EQ(p[2].z, 1e-5f);
}

TEST_F(SceneLoader, MirroringTransformKeepsTheFrontFace) {
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

// Normals transform by the inverse transpose: under a non-uniform scale they stay perpendicular to the surface. The
// triangle's edges (1, -1, 0) and (0, 0, 1) are perpendicular to its normal (1, 1, 0) / sqrt 2; scaled by (1, 2, 1)
// the edges become (1, -2, 0) and (0, 0, 1), and the normal must become (2, 1, 0) / sqrt 5 (transformed like a
// direction it would be (1, 2, 0) / sqrt 5, 37 degrees off).
TEST_F(SceneLoader, NormalsStayPerpendicularUnderNonUniformScale) {
  const auto scene = load_scene(write_scene(
      R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [{"type": "mesh", "material": "m",
          "positions": [[0,0,0], [1,-1,0], [0,0,1]], "normals": [[1,1,0], [1,1,0], [1,1,0]], "indices": [0,1,2],
          "transform": {"scale": [1, 2, 1]}}]})"));
  const TriangleMesh& m = scene->geometry.mesh(0);
  const Vec3 e1 = m.positions[1] - m.positions[0], e2 = m.positions[2] - m.positions[0];
  for (const Vec3& n : m.normals) {
    EXPECT_NEAR(length(n), 1.0f, 1e-6f);
    EXPECT_NEAR(dot(n, e1), 0.0f, 1e-6f);
    EXPECT_NEAR(dot(n, e2), 0.0f, 1e-6f);
    EXPECT_NEAR(n.x, 2 / std::sqrt(5.0f), 1e-6f);
  }
}

// A normal of any finite non-zero length is a direction ([1e-30, 1e-30, 0] too), and a transform at the edge of the
// coordinate range (scale 9e11: cofactors 8e23, squared past the float range) keeps smooth normals unit, not zero.
TEST_F(SceneLoader, NormalsSurviveTinyLengthsAndExtremeScales) {
  for (const char* scale : {"1", "9e11", "3e-12"}) {
    SCOPED_TRACE(scale);
    const auto scene = load_scene(write_scene(
        std::string(R"({"materials": {"m": {"type": "diffuse"}}, "camera": {"from": [0,0,1], "to": [0,0,0]},
          "shapes": [{"type": "mesh", "material": "m", "positions": [[0,0,0], [1,0,0], [0,1,0]],
          "normals": [[1e-30,0,1e-30], [-1e30,0,1e30], [0,0,1]], "indices": [0,1,2],
          "transform": {"scale": )") + scale + "}}]}"));
    const TriangleMesh& m = scene->geometry.mesh(0);
    const float h = std::sqrt(0.5f);
    const Vec3 expected[3] = {{h, 0, h}, {-h, 0, h}, {0, 0, 1}};
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(m.normals[i].x, expected[i].x, 1e-6f) << i;
      EXPECT_NEAR(m.normals[i].z, expected[i].z, 1e-6f) << i;
    }
  }
}

TEST_F(SceneLoader, EmissionMakesShapesLightsThatStayGeometry) {
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

// A quad that emits through a double-sided (or textured) material is a mesh light of its two triangles, and its
// `sampling` still applies (it was ignored without a word): by area the density toward points of one triangle
// varies with the point, uniformly in solid angle it does not.
TEST_F(SceneLoader, QuadSamplingAppliesToAQuadSampledAsAMeshLight) {
  for (const std::string sampling : {"area", "spherical_rectangle"}) {
    const auto scene = load_scene(write_scene(
        R"({"materials": {"glow": {"type": "pbr", "emissive": [1, 1, 1], "double_sided": true}},
            "shapes": [{"type": "quad", "origin": [0,0,0], "edge_u": [1,0,0], "edge_v": [0,1,0], "material": "glow",
                        "sampling": ")" + sampling + R"("}]})"));
    ASSERT_EQ(scene->lights.size(), 1u);
    ASSERT_EQ(scene->lights[0]->name(), "mesh");
    const LightSampleContext ctx{{0.2f, 0.3f, 1}, {0, 0, -1}};
    const auto a = scene->lights[0]->sample(ctx, {0.1f, 0.2f}), b = scene->lights[0]->sample(ctx, {0.1f, 0.9f});
    ASSERT_TRUE(a && b) << sampling;
    ASSERT_GT(length(a->p_light - b->p_light), 0.1f) << sampling;  // two points of the same triangle (same u.x)
    if (sampling == "area")
      EXPECT_GT(std::abs(a->pdf / b->pdf - 1), 0.05f) << a->pdf << " " << b->pdf;
    else
      EXPECT_NEAR(a->pdf / b->pdf, 1, 1e-5f) << a->pdf << " " << b->pdf;
  }
}

// A pbr material with non-zero emissive makes every shape using it a light with that radiance: a sphere, and a glTF
// mesh whose own material is replaced by it ("materials"); "emission" on the shape wins over it.
TEST_F(SceneLoader, EmissiveMaterialMakesEveryShapeUsingItALight) {
  const auto scene = load_scene(write_scene(
      R"({"materials": {"glow": {"type": "pbr", "emissive": [2, 3, 4]}},
          "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "glow"},
                     {"type": "sphere", "center": [5,0,0], "radius": 1, "material": "glow", "emission": [1,1,1]},
                     {"type": "gltf", "file": ")" + kBoxGlb + R"(", "materials": {"Red": "glow"},
                      "transform": {"translate": [10,0,0]}}]})"));
  ASSERT_EQ(scene->lights.size(), 3u);
  EXPECT_EQ(scene->geometry.sphere(0).light, 0);
  EXPECT_EQ(scene->geometry.sphere(1).light, 1);
  EXPECT_EQ(scene->geometry.mesh(2).light, 2);
  // Seen from +z, straight at each shape's surface facing +z.
  for (const auto& [x, light, radiance] : {std::tuple{0.0f, 0, Color(2, 3, 4)}, std::tuple{5.0f, 1, Color(1, 1, 1)},
                                           std::tuple{10.0f, 2, Color(2, 3, 4)}}) {
    Hit on;
    ASSERT_TRUE(scene->geometry.intersect(Ray(Vec3(x, 0.1f, 3), Vec3(0, 0, -1)), on)) << x;
    EXPECT_EQ(on.light, light) << x;
    EXPECT_EQ(scene->lights[light]->le(on, Vec3(0, 0, 1)), radiance) << x;
  }
}

// A glTF cut-out (alphaMode MASK) belongs to the geometry: it stays, with its cutoff, when "materials" replaces the
// shading.
TEST_F(SceneLoader, GltfCutoutsStayWhenTheMaterialIsReplaced) {
  const auto scene = load_scene(write_scene(
      R"({"materials": {"m": {"type": "diffuse"}},
          "shapes": [{"type": "gltf", "file": ")" + kAssets + R"(/gltf/AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf",
                      "materials": {"MatCutoff25": "m"}}]})"));
  int replaced = 0;
  for (size_t g = 0; g < scene->geometry.geometry_count(); ++g) {
    if (!scene->geometry.is_mesh(g) || scene->geometry.mesh(g).material != 0) continue;
    ++replaced;
    ASSERT_TRUE(scene->geometry.mesh(g).alpha.has_value());
    EXPECT_EQ(scene->geometry.mesh(g).alpha->cutoff, 0.25f);
  }
  EXPECT_GE(replaced, 1);
}

TEST_F(SceneLoader, FileTypeIsTheExtensionInAnyCase) {
  const std::string json = write_file("UPPER.JSON", example_with_box());
  EXPECT_EQ(load_scene(json)->settings.spp, 64);
  const std::string glb = (test_dir() / "BOX.GLB").string();
  std::filesystem::copy_file(kBoxGlb, glb, std::filesystem::copy_options::overwrite_existing);
  EXPECT_EQ(load_scene(glb)->lights.size(), 1u);  // read as glTF: the white sky a lone glTF file gets
  // Inside a JSON scene too: a glTF shape's file and an environment map.
  Image sky(4, 2, {"R", "G", "B"});
  for (float& v : sky.data) v = 0.5f;
  write_image((test_dir() / "Sky.Exr").string(), sky);
  const auto scene = load_scene(write_scene(R"({"shapes": [{"type": "gltf", "file": "BOX.GLB"}],
                                                "lights": [{"type": "environment", "file": "Sky.Exr"}]})"));
  EXPECT_EQ(scene->environment, 0);
  EXPECT_EQ(scene->geometry.geometry_count(), 1u);
}

// A quad's texture coordinates, as the scene format documents them: (0, 0) at origin, (1, 0) at origin + edge_u,
// (0, 1) at origin + edge_v; a hit at origin + 0.8 edge_u + 0.1 edge_v reads (0.8, 0.1).
TEST_F(SceneLoader, QuadTextureCoordinatesFollowItsEdges) {
  const auto scene = load_scene(write_scene(
      R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [{"type": "quad", "material": "m",
          "origin": [-1,0,-1], "edge_u": [2,0,0], "edge_v": [0,0,4]}]})"));
  for (const auto& [s, t] : {std::pair{0.8f, 0.1f}, std::pair{0.3f, 0.6f}}) {
    const Vec3 p = Vec3(-1, 0, -1) + Vec3(2, 0, 0) * s + Vec3(0, 0, 4) * t;
    Hit hit;
    ASSERT_TRUE(scene->geometry.intersect(Ray(p + Vec3(0, 1, 0), Vec3(0, -1, 0)), hit));
    EXPECT_NEAR(hit.uv[0].x, s, 1e-5f);
    EXPECT_NEAR(hit.uv[0].y, t, 1e-5f);
  }
}

// An environment map's "scale" and "rotation" reach the light: the loaded light's radiance equals that of the same
// map made with scale 2 and rotation 90 directly, in directions where the map without them reads differently.
TEST_F(SceneLoader, EnvironmentMapScaleAndRotationAreApplied) {
  auto sky = std::make_shared<Image>(8, 4, std::vector<std::string>{"R", "G", "B"});
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) sky->at(x, y, c) = 0.1f + 0.1f * x + 0.02f * y + 0.01f * c;
  write_image((test_dir() / "sky.exr").string(), *sky);
  const auto scene = load_scene(write_scene(
      R"({"lights": [{"type": "environment", "file": "sky.exr", "scale": 2, "rotation": 90}]})"));
  ASSERT_GE(scene->environment, 0);
  const Light& loaded = *scene->lights[scene->environment];
  const auto expected = make_image_environment(sky, 2, 90), plain = make_image_environment(sky, 1, 0);
  for (const Vec3 d : {Vec3(1, 0.2f, 0), Vec3(0, -0.3f, 1), Vec3(-1, 0.5f, -1)}) {
    const Vec3 w = normalize(d);
    const Color a = loaded.le_escaped(w), e = expected->le_escaped(w), p = plain->le_escaped(w);
    EXPECT_NEAR(a.x, e.x, 1e-6f);
    EXPECT_NEAR(a.y, e.y, 1e-6f);
    EXPECT_NEAR(a.z, e.z, 1e-6f);
    EXPECT_GT(std::abs(e.x - p.x), 0.05f) << "the test's map reads the same without scale and rotation";
  }
}

// One image file used as data (linear) by one material and as colour (sRGB) by another is decoded once for each use:
// a grey PNG of code 128 is 0.502 as roughness and metalness but 0.2159 as an albedo.
TEST_F(SceneLoader, AFileUsedAsDataAndAsColourIsDecodedForEach) {
  const unsigned char grey[4 * 3] = {128, 128, 128, 128, 128, 128, 128, 128, 128, 128, 128, 128};
  ASSERT_TRUE(test::write_png((test_dir() / "grey.png").string(), 2, 2, 3, grey));
  // The materials load in key order: "a" reads the file first, as data.
  const auto scene = load_scene(write_scene(
      R"({"materials": {"a": {"type": "pbr", "metallic_roughness_texture": "grey.png"},
                        "d": {"type": "diffuse", "albedo": [1, 1, 1], "texture": "grey.png"}},
          "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "d"}]})"));
  ASSERT_EQ(scene->materials.size(), 2u);
  Hit hit;
  hit.uv[0] = {0.5f, 0.5f};
  const Color albedo = scene->materials[1]->albedo(hit);
  EXPECT_NEAR(albedo.x, 0.2158605f, 1e-5f);
  EXPECT_NEAR(albedo.z, 0.2158605f, 1e-5f);
}

TEST_F(SceneLoader, EnvironmentMapAndTexturesLoad) {
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

}  // namespace
}  // namespace lumis
