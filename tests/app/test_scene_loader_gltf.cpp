// A glTF file loaded on its own (`lumis render model.glb`): the framing camera and white sky it gets without a camera
// or a lamp, its emissive meshes as lights, and the image shape its camera's aspectRatio gives (the JSON scene loader:
// test_scene_loader.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "app/render_overrides.h"
#include "tests/app/gltf_synthetic.h"
#include "tests/app/scene_loader_test_util.h"

namespace lumis {
namespace {

using namespace scene_test;
using SceneLoader = LoaderTest;

TEST_F(SceneLoader, GltfFileAloneGetsFramingCameraAndWhiteSky) {
  const auto scene = load_scene(kBoxGlb);
  ASSERT_GE(scene->environment, 0);
  EXPECT_TRUE(scene->lights[scene->environment]->is_environment());
  EXPECT_EQ(scene->lights.size(), 1u);
  // Box.glb spans [-0.5, 0.5]^3: the camera is outside its bounding sphere, looking at the centre.
  EXPECT_LT(length(scene->camera.to), 1e-5f);
  EXPECT_GT(length(scene->camera.from), std::sqrt(0.75f));
}

// `--camera 0` is "the default": for a file without cameras, the framing camera (with a warning), not an error; any
// other number still is one.
TEST_F(SceneLoader, CameraZeroOfAFileWithoutCamerasIsTheFramingCamera) {
  const auto framed = load_scene(kBoxGlb);
  const auto zero = load_scene(kBoxGlb, SceneLoadOptions{"0"});
  EXPECT_EQ(zero->camera.from, framed->camera.from);
  EXPECT_EQ(zero->camera.to, framed->camera.to);
  EXPECT_THROW(load_scene(kBoxGlb, SceneLoadOptions{"1"}), std::invalid_argument);
}

TEST_F(SceneLoader, GltfEmissiveMeshesBecomeMeshLightsAndNoSkyIsAdded) {
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

// A glTF camera's aspectRatio sets the image's shape: 512 pixels across, the height following (16:9 -> 512 x 288).
TEST_F(SceneLoader, GltfCameraAspectRatioSetsTheImageHeight) {
  const auto scene = load_scene(kAssets + "/gltf/MultiUVTest/glTF/MultiUVTest.gltf");
  EXPECT_EQ(scene->settings.width, 512);
  EXPECT_EQ(scene->settings.height, 288);
}

// An extreme aspectRatio clamps the height to 1..16384 pixels, with a warning: 1e-30 (a very tall image) gives
// 16384, as 1e-3 does, and 1e30 gives 1.
TEST_F(SceneLoader, GltfCameraExtremeAspectRatioClampsTheHeight) {
  const gltf_test::Triangle t;
  for (const auto& [aspect, height] : {std::pair{"1e-30", 16384}, std::pair{"1e-3", 16384}, std::pair{"1e30", 1}}) {
    const std::string file = write_file(
        "tall.gltf", R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],"nodes":[{"mesh":0},)"
                     R"({"camera":0,"translation":[0.3,0.3,3]}],"cameras":[{"type":"perspective","perspective":)"
                     R"({"yfov":0.8,"znear":0.01,"aspectRatio":)" + std::string(aspect) +
                         R"(}}],"meshes":[{"primitives":[)" + gltf_test::Triangle::prim + R"(]}],"buffers":[)" +
                         t.bin.buffer_json() + R"(],"bufferViews":)" + t.views + R"(,"accessors":)" + t.accessors +
                         "}");
    testing::internal::CaptureStderr();
    const auto scene = load_scene(file);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(scene->settings.width, 512) << aspect;
    EXPECT_EQ(scene->settings.height, height) << aspect;
    // Said, since the image then lacks the camera's shape; 1e30 was once a silent 512 x 1.
    EXPECT_NE(err.find("warning: nodes[1]'s aspectRatio "), std::string::npos) << aspect << ": " << err;
    EXPECT_NE(err.find("its height is clamped to 1...16384"), std::string::npos) << aspect << ": " << err;
    testing::internal::CaptureStderr();
    load_scene(file, SceneLoadOptions{"", true});  // --width or --height given: the shape is the user's
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << aspect;
    // --width alone keeps the camera's ratio, not the clamped 512 x 16384 (a 2 x 64 image at 1e-3, it once was).
    RenderOverrides two_wide;
    two_wide.width = 2;
    RenderSettings s = scene->settings;
    if (std::string(aspect) == "1e-3") {
      apply_overrides(two_wide, s);
      EXPECT_EQ(s.height, 2000);
    } else {  // 1e-30 and 1e30: no height in 1...16384 keeps it; said in the camera's terms
      try {
        apply_overrides(two_wide, s);
        ADD_FAILURE() << aspect << ": " << s.width << " x " << s.height;
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("--width 2 alone keeps the camera's aspect ratio 1e"),
                  std::string::npos) << e.what();
      }
    }
  }
  testing::internal::CaptureStderr();
  load_scene(kAssets + "/gltf/MultiUVTest/glTF/MultiUVTest.gltf");  // 16:9, as asked: no warning
  EXPECT_EQ(testing::internal::GetCapturedStderr().find("aspectRatio"), std::string::npos);
}

// Inside a JSON scene a glTF file's cameras are not read, since the scene's own camera is used: one that lumis refuses
// in the file alone (yfov 4 radians) is no error there, and an orthographic one is not reported as skipped.
TEST_F(SceneLoader, GltfCamerasAreNotReadInsideAJsonScene) {
  const gltf_test::Triangle t;
  const std::string file = write_file(
      "cams.gltf", std::string(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2]}],"nodes":[{"mesh":0},)"
                   R"({"camera":0,"translation":[0,0,3]},{"camera":1}],"cameras":[{"type":"perspective",)"
                   R"("perspective":{"yfov":4.0,"znear":0.01}},{"type":"orthographic","orthographic":)"
                   R"({"xmag":1,"ymag":1,"znear":0.01,"zfar":10}}],"meshes":[{"primitives":[)") +
                       gltf_test::Triangle::prim + R"(]}],"buffers":[)" + t.bin.buffer_json() +
                       R"(],"bufferViews":)" + t.views + R"(,"accessors":)" + t.accessors + "}");
  try {
    load_scene(file);
    ADD_FAILURE() << "the file alone loaded with a yfov of 4 radians";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.location, "cameras[0].perspective.yfov");
  }
  testing::internal::CaptureStderr();
  const auto scene = load_scene(write_scene(R"({"camera": {"from": [0,0,3], "to": [0,0,0]},
      "shapes": [{"type": "gltf", "file": "cams.gltf"}]})"));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(err.find("camera"), std::string::npos) << err;
  EXPECT_EQ(scene->camera.from, Vec3(0, 0, 3));
}

// Emission read from a texture is usually a decal (the helmet's visor display), too weak to light a model: a file
// whose only emission is textured gets the white sky too, and its textured emitters stay lights.
TEST_F(SceneLoader, GltfWithOnlyTexturedEmissionStillGetsTheSky) {
  const auto scene = load_scene(kAssets + "/gltf/DamagedHelmet/glTF-Binary/DamagedHelmet.glb");
  ASSERT_GE(scene->environment, 0);
  EXPECT_TRUE(scene->lights[scene->environment]->is_environment());
  EXPECT_GT(scene->lights.size(), 1u);
}

}  // namespace
}  // namespace lumis
