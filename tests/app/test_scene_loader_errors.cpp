// The lumis JSON scene loader on bad input: each kind fails with the exact location (JSON pointer or line:column)
// and the telling part of the message (scenes that load: test_scene_loader.cpp).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>

#include "app/json_reader.h"
#include "core/image_io.h"

#include "tests/app/gltf_synthetic.h"
#include "tests/app/scene_loader_test_util.h"

namespace lumis {
namespace {

using namespace scene_test;
using SceneLoaderErrors = LoaderTest;

// The one-sphere scene with material "m" defined as `material`.
std::string scene_with_material(const std::string& material) {
  return scene_with("", R"("center": [0,0,0], "radius": 1, "material": "m")", material);
}

// Syntax (line:column).

TEST_F(SceneLoaderErrors, SyntaxErrorGivesLineAndColumn) {
  // Line 2 lacks its comma; the parser gives up at the last character of the string "render" on line 3 (the
  // same place nlohmann's own message names).
  const SceneError e = load_error("{\n  \"film\": {\"width\": 5}\n  \"render\": {}\n}");
  EXPECT_EQ(e.location, "3:10") << e.what();
  EXPECT_NE(e.detail.find("invalid JSON"), std::string::npos) << e.what();
  EXPECT_NE(e.detail.find("expected '}'"), std::string::npos) << e.what();
}

// The column counts characters, as an editor does, not bytes: "é" is two bytes in UTF-8 (it read 1:28 here).
TEST_F(SceneLoaderErrors, SyntaxErrorColumnCountsCharactersNotBytes) {
  EXPECT_EQ(load_error("{\"materials\": {\"eee\": 1 x}}").location, "1:25");
  EXPECT_EQ(load_error("{\"materials\": {\"\u00e9\u00e9\u00e9\": 1 x}}").location, "1:25");
  EXPECT_EQ(load_error("{\"a\": \"\u00e9\",\n \"\u20ac\": 1 x}").location, "2:9");  // a new line starts again
}

// What nlohmann quotes ("last read: '...'") is made printable: ill-formed UTF-8 and control bytes are written \xNN
// (they once reached the terminal raw), well-formed UTF-8 is kept.
TEST_F(SceneLoaderErrors, SyntaxErrorQuotesOnlyPrintableText) {
  const SceneError e = load_error("{\"e\u00e9\": \"\xff\xfe\"}");
  EXPECT_EQ(e.location, "1:9") << e.what();
  EXPECT_NE(e.detail.find("ill-formed UTF-8 byte; last read: '\"\\xff'"), std::string::npos) << e.detail;
  EXPECT_EQ(json_syntax_detail("[json.exception.parse_error.101] parse error at line 1, column 9: syntax error while "
                               "parsing value - x; last read: '\"\u00e9\x01\x7f\xc3'"),
            "syntax error while parsing value - x; last read: '\"\u00e9\\x01\\x7f\\xc3'");
}

TEST_F(SceneLoaderErrors, TruncatedFileGivesPositionAtTheEnd) {
  const SceneError e = load_error("{\n  \"film\": {\"width\": 5}");
  EXPECT_EQ(e.location, "2:23") << e.what();
  EXPECT_NE(e.detail.find("end of input"), std::string::npos) << e.what();
}

TEST_F(SceneLoaderErrors, OverflowingNumberIsRejectedWithPosition) {
  const SceneError e = load_error("{\"film\": {\"width\": 1e999}}");
  EXPECT_EQ(e.location, "1:24") << e.what();  // the last digit of 1e999
  EXPECT_NE(e.detail.find("number overflow"), std::string::npos) << e.what();
}

TEST_F(SceneLoaderErrors, DuplicateKey) {
  EXPECT_SCENE_ERROR(scene_with(R"("film": {"width": 64, "width": 32})"), "/film/width", "duplicate key");
}

// A key holding "~" or "/" is escaped in the pointer as RFC 6901 says: "~" as "~0", "/" as "~1".
TEST_F(SceneLoaderErrors, PointerEscapesTildeAndSlashInKeys) {
  EXPECT_SCENE_ERROR(scene_with_material(R"("a~b/c~1": {"type": "diffuse", "albedo": [2, 0, 0]})"),
                     "/materials/a~0b~1c~01/albedo/0", "expected a number in [0, 1]");
  EXPECT_SCENE_ERROR(scene_with(R"("film": {"width": 64, "~/": 1})"), "/film/~0~1", "unknown key \"~/\"");
}

// Errors: structure, types and unknown keys.

TEST_F(SceneLoaderErrors, TopLevelMustBeAnObject) {
  EXPECT_SCENE_ERROR("[1, 2]", "", "expected an object, found an array of 2 elements");
}

TEST_F(SceneLoaderErrors, UnknownTopLevelKeyListsValidKeys) {
  const SceneError e = load_error(R"({"shape": []})");
  EXPECT_EQ(e.location, "/shape");
  EXPECT_NE(e.detail.find("unknown key \"shape\" (did you mean \"shapes\"?)"), std::string::npos) << e.what();
  EXPECT_NE(e.detail.find("valid keys: version, camera, film, render, materials, shapes, lights"), std::string::npos)
      << e.what();
}

TEST_F(SceneLoaderErrors, UnknownShapeKey) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radus": 1, "material": "m")"), "/shapes/0/radus",
                     "did you mean \"radius\"");
}

TEST_F(SceneLoaderErrors, UnsupportedVersion) {
  EXPECT_SCENE_ERROR(scene_with(R"("version": 2)"), "/version", "expected 1, found the number 2");
}

TEST_F(SceneLoaderErrors, WrongTypeForWidth) {
  EXPECT_SCENE_ERROR(scene_with(R"("film": {"width": "512"})"), "/film/width",
                     "expected an integer >= 1, found the string \"512\"");
}

TEST_F(SceneLoaderErrors, ZeroWidth) {
  EXPECT_SCENE_ERROR(scene_with(R"("film": {"width": 0})"), "/film/width", "found the number 0");
}

TEST_F(SceneLoaderErrors, AbsurdResolution) {
  EXPECT_SCENE_ERROR(scene_with(R"("film": {"width": 512, "height": 100000})"), "/film/height",
                     "absurd resolution 512 x 100000: at most 16384 pixels per side");
}

TEST_F(SceneLoaderErrors, ZeroSpp) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"spp": 0})"), "/render/spp", "expected an integer in [1, 1073741824]");
}

TEST_F(SceneLoaderErrors, FractionalSpp) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"spp": 1.5})"), "/render/spp", "found the number 1.5");
}

TEST_F(SceneLoaderErrors, UnknownIntegratorListsValidOnes) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"integrator": "path"})"), "/render/integrator",
                     "unknown integrator \"path\"; valid: uniform, bsdf, light, mis, nee_mis");
}

TEST_F(SceneLoaderErrors, UnknownSamplerListsValidOnes) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"sampler": "sobel"})"), "/render/sampler",
                     "unknown sampler \"sobel\" (did you mean \"sobol\"?); valid: independent, stratified, sobol");
}

TEST_F(SceneLoaderErrors, UnknownLightSelectionListsValidOnes) {
  EXPECT_SCENE_ERROR(scene_with(R"("render": {"light_selection": "best"})"), "/render/light_selection",
                     "valid: uniform, power, importance");
}

// [0, 1) at both ends, with what was found (below 0 it used to say [0, 1], and 1 said nothing of what it found).
TEST_F(SceneLoaderErrors, ProbabilityOutOfRange) {
  const std::string expected = "expected a probability in [0, 1) (1 would lose indirect light), found the number ";
  for (const char* v : {"1.5", "1", "-0.1", "0.99999999999"})
    EXPECT_SCENE_ERROR(scene_with(std::string(R"("render": {"mis_light_probability": )") + v + "}"),
                       "/render/mis_light_probability", expected + v);
}

// Errors: cameras.

TEST_F(SceneLoaderErrors, CameraWithoutDirection) {
  EXPECT_SCENE_ERROR(scene_with(R"("camera": {"from": [0,0,5], "to": [0,0,5]})"), "/camera/to", "must differ");
}

// An "up" along the viewing direction leaves the image's orientation undefined (its frame would be NaN).
TEST_F(SceneLoaderErrors, CameraUpAlongTheViewingDirection) {
  EXPECT_SCENE_ERROR(scene_with(R"("camera": {"from": [0,5,0], "to": [0,0,0]})"), "/camera/to",
                     "\"up\" must not be zero or parallel to the viewing direction");
  EXPECT_SCENE_ERROR(scene_with(R"("camera": {"from": [0,0,5], "to": [0,0,0], "up": [0,0,-2]})"), "/camera/up",
                     "parallel to the viewing direction");
  EXPECT_SCENE_ERROR(scene_with(R"("camera": {"from": [0,0,5], "to": [0,0,0], "up": [0,0,0]})"), "/camera/up",
                     "must not be zero");
}

TEST_F(SceneLoaderErrors, FieldOfViewOutOfRange) {
  EXPECT_SCENE_ERROR(scene_with(R"("camera": {"from": [0,0,5], "to": [0,0,0], "fov": 180})"), "/camera/fov",
                     "strictly between 0 and 180");
}

// Errors: materials.

TEST_F(SceneLoaderErrors, UnknownMaterialTypeListsValidOnes) {
  EXPECT_SCENE_ERROR(scene_with_material(R"("m": {"type": "glass"})"),
                     "/materials/m/type", "unknown material type \"glass\"; valid: diffuse, pbr, ggx");
}

TEST_F(SceneLoaderErrors, AlbedoAboveOne) {
  EXPECT_SCENE_ERROR(scene_with_material(R"("m": {"type": "diffuse", "albedo": [0.5, 1.5, 0.5]})"),
                     "/materials/m/albedo/1", "expected a number in [0, 1], found the number 1.5");
}

TEST_F(SceneLoaderErrors, ColorWithTwoComponents) {
  EXPECT_SCENE_ERROR(scene_with_material(R"("m": {"type": "diffuse", "albedo": [0.5, 0.5]})"),
                     "/materials/m/albedo", "expected an array of 3 numbers, found an array of 2 elements");
}

TEST_F(SceneLoaderErrors, MisspelledPbrKey) {
  EXPECT_SCENE_ERROR(scene_with_material(R"("m": {"type": "pbr", "roughnes": 0.5})"),
                     "/materials/m/roughnes", "did you mean \"roughness\"");
}

TEST_F(SceneLoaderErrors, MissingTextureFile) {
  EXPECT_SCENE_ERROR(scene_with_material(R"("m": {"type": "diffuse", "texture": "no-such.png"})"),
                     "/materials/m/texture", "file not found");
}

// Errors: shapes.

TEST_F(SceneLoaderErrors, NegativeRadius) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": -1, "material": "m")"), "/shapes/0/radius",
                     "found the number -1");
}

TEST_F(SceneLoaderErrors, RadiusBeyondFloatRange) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1e39, "material": "m")"), "/shapes/0/radius",
                     "a finite number within float range");
}

TEST_F(SceneLoaderErrors, UnknownMaterialReference) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1, "material": "gol")"), "/shapes/0/material",
                     "unknown material \"gol\"; defined materials: m");
}

TEST_F(SceneLoaderErrors, ShapeWithoutMaterial) {
  EXPECT_SCENE_ERROR(scene_with("", R"("center": [0,0,0], "radius": 1)"), "/shapes/0",
                     "missing required key \"material\"");
}

TEST_F(SceneLoaderErrors, UnknownShapeTypeListsValidOnes) {
  EXPECT_SCENE_ERROR(R"({"shapes": [{"type": "cube"}]})", "/shapes/0/type",
                     "unknown shape type \"cube\"; valid: sphere, quad, mesh, gltf");
}

TEST_F(SceneLoaderErrors, DegenerateQuad) {
  EXPECT_SCENE_ERROR(R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [{"type": "quad", "origin": [0,0,0],
                         "edge_u": [1,0,0], "edge_v": [2,0,0], "material": "m"}]})",
                     "/shapes/0/edge_v", "not parallel");
}

TEST_F(SceneLoaderErrors, MeshIndexOutOfRange) {
  EXPECT_SCENE_ERROR(R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [{"type": "mesh", "material": "m",
                         "positions": [[0,0,0], [1,0,0], [0,1,0]], "indices": [0, 1, 3]}]})",
                     "/shapes/0/indices/2", "expected an integer in [0, 2], found the number 3");
}

TEST_F(SceneLoaderErrors, MissingGltfFile) {
  EXPECT_SCENE_ERROR(R"({"shapes": [{"type": "gltf", "file": "missing.glb"}]})", "/shapes/0/file",
                     "file not found");
}

TEST_F(SceneLoaderErrors, GltfFileMustBeAGltfOrGlbFile) {
  write_file("ok.json", "{}");
  EXPECT_SCENE_ERROR(R"({"shapes": [{"type": "gltf", "file": "ok.json"}]})", "/shapes/0/file",
                     "expected a .gltf or .glb file, found \".json\"");
  write_file("model", "{}");
  EXPECT_SCENE_ERROR(R"({"shapes": [{"type": "gltf", "file": "model"}]})", "/shapes/0/file",
                     "expected a .gltf or .glb file, found no extension");
  EXPECT_SCENE_ERROR(R"({"shapes": [{"type": "gltf", "file": ".."}]})", "/shapes/0/file",
                     "is a folder, expected a file");
}

TEST_F(SceneLoaderErrors, TextureThatIsAFolder) {
  EXPECT_SCENE_ERROR(scene_with_material(R"("m": {"type": "diffuse", "texture": ".."})"), "/materials/m/texture",
                     "is a folder, expected a file");
}

// An error inside an included glTF file names the scene's shape as well as the file and its glTF path.
TEST_F(SceneLoaderErrors, ErrorInsideAGltfFileNamesTheShape) {
  const std::string gltf = write_file("Model.GLTF", R"({"asset": {"version": "1.0"}})");
  // The extension in any case.
  const SceneError e = load_error(R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [
      {"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}, {"type": "gltf", "file": "Model.GLTF"}]})");
  EXPECT_EQ(e.location, "/shapes/1/file") << e.what();
  EXPECT_EQ(e.detail, "in " + gltf + ":asset.version: glTF version \"1.0\": lumis reads glTF 2.0 (major version 2)");
}

// A glTF file with no triangles (points only) would add nothing to the scene: an error, as a mesh shape with no
// triangle left is, and as the file on its own is ("scene is empty"). It rendered black with only a warning.
TEST_F(SceneLoaderErrors, GltfFileWithoutTrianglesIsAnError) {
  const gltf_test::Triangle t;
  write_file("points.gltf", std::string(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)") +
                                R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},)" +
                                R"("mode":0}]}],"buffers":[)" + t.bin.buffer_json() + R"(],"bufferViews":)" + t.views +
                                R"(,"accessors":)" + t.accessors + "}");
  EXPECT_SCENE_ERROR(R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [
      {"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}, {"type": "gltf", "file": "points.gltf"}]})",
                     "/shapes/1/file", "the glTF file has no triangle meshes, so the shape would add nothing");
}

TEST_F(SceneLoaderErrors, GltfMaterialNameNotInFile) {
  EXPECT_SCENE_ERROR(R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [{"type": "gltf", "file": ")" + kBoxGlb +
                         R"(", "materials": {"Blue": "m"}}]})",
                     "/shapes/0/materials/Blue", "no material named \"Blue\"; its materials: \"Red\"");
}

TEST_F(SceneLoaderErrors, MatrixTogetherWithTranslate) {
  EXPECT_SCENE_ERROR(R"({"shapes": [{"type": "gltf", "file": ")" + kBoxGlb +
                         R"(", "transform": {"translate": [1,0,0], "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}}]})",
                     "/shapes/0/transform/translate", "\"matrix\" replaces translate/rotate/scale");
}

// Singular relative to the matrix's own scale: the third column lies in the plane of the first two.
TEST_F(SceneLoaderErrors, MatrixThatFlattensTheShape) {
  EXPECT_SCENE_ERROR(R"({"shapes": [{"type": "gltf", "file": ")" + kBoxGlb +
                         R"(", "transform": {"matrix": [1e3,0,1e3,0, 0,1e3,1e3,0, 0,0,1e-4,0, 0,0,0,1]}}]})",
                     "/shapes/0/transform/matrix", "the matrix is singular");
}

// Errors: lights.

TEST_F(SceneLoaderErrors, UnknownLightTypeListsValidOnes) {
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "point"}]})", "/lights/0/type",
                     "unknown light type \"point\"; valid: sphere, quad, environment");
}

TEST_F(SceneLoaderErrors, BlackRadiance) {
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "sphere", "center": [0,0,0], "radius": 1, "radiance": [0,0,0]}]})",
                     "/lights/0/radiance", "at least one positive component");
}

TEST_F(SceneLoaderErrors, UnknownQuadSamplingListsValidOnes) {
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "quad", "origin": [0,0,0], "edge_u": [1,0,0], "edge_v": [0,1,0],
                         "radiance": [1,1,1], "sampling": "solid_angle"}]})",
                     "/lights/0/sampling", "valid: spherical_rectangle, area");
}

TEST_F(SceneLoaderErrors, SecondEnvironment) {
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "environment", "radiance": [1,1,1]},
                                    {"type": "environment", "radiance": [1,1,1]}]})",
                     "/lights/1", "only one environment light");
}

TEST_F(SceneLoaderErrors, EnvironmentWithRadianceAndFile) {
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "environment", "radiance": [1,1,1], "file": "sky.exr"}]})", "/lights/0",
                     "exactly one of \"radiance\"");
}

TEST_F(SceneLoaderErrors, EnvironmentMapMustBeLinear) {
  const std::string png = kAssets + "/gltf/BoxWithSpaces/glTF/glTF Logo With Spaces.png";
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "environment", "file": ")" + png + R"("}]})", "/lights/0/file",
                     "must be a linear .exr or .hdr file");
}

// The extension is checked first, then the contents: OpenImageIO reads a PNG named .exr as a PNG, whose 8-bit values
// would have been taken as linear radiance.
TEST_F(SceneLoaderErrors, EnvironmentMapMustBeLinearByItsContentsToo) {
  Image img(2, 2, {"R", "G", "B"});
  const std::string png = (test_dir() / "map.png").string(), disguised = (test_dir() / "map-png.exr").string();
  write_image(png, img);
  std::filesystem::copy_file(png, disguised, std::filesystem::copy_options::overwrite_existing);
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "environment", "file": ")" + disguised + R"("}]})", "/lights/0/file",
                     "must be a linear .exr or .hdr file; this one is named \".exr\" but holds a png image");
  std::filesystem::copy_file(png, test_dir() / "map", std::filesystem::copy_options::overwrite_existing);
  EXPECT_SCENE_ERROR(R"({"lights": [{"type": "environment", "file": ")" + (test_dir() / "map").string() + R"("}]})",
                     "/lights/0/file", "must be a linear .exr or .hdr file, found a name without an extension");
}

// An EXR of 2x2 grey texels with texel (1, 1) set to `bad` in R, written next to the test's scene.
std::string exr_with_texel(float bad) {
  Image img(2, 2, {"R", "G", "B"});
  for (float& v : img.data) v = 0.5f;
  img.at(1, 1, 0) = bad;
  const std::string path = (test_dir() / "map.exr").string();
  write_image(path, img);
  return path;
}

TEST_F(SceneLoaderErrors, EnvironmentMapTexelsMustBeFiniteAndNonNegative) {
  const std::pair<float, const char*> cases[] = {{-1.0f, "-1"},
                                                  {-1e-9f, "-1e-09"},  // once "-0.000000"
                                                  {std::numeric_limits<float>::quiet_NaN(), "nan"},
                                                  {std::numeric_limits<float>::infinity(), "inf"}};
  for (const auto& [bad, printed] : cases) {
    const std::string map = exr_with_texel(bad);
    EXPECT_SCENE_ERROR(R"({"lights": [{"type": "environment", "file": ")" + map + R"("}]})", "/lights/0/file",
                       "pixel (1, 1) channel R is " + std::string(printed) + ": expected finite values >= 0");
  }
}

TEST_F(SceneLoaderErrors, ColourTextureTexelsMustBeFiniteAndNonNegative) {
  for (float bad : {-1.0f, std::numeric_limits<float>::quiet_NaN()}) {
    const std::string map = exr_with_texel(bad);
    for (const char* key : {"base_color_texture", "emissive_texture"})
      EXPECT_SCENE_ERROR(
          scene_with_material(R"("m": {"type": "pbr", ")" + std::string(key) + R"(": ")" + map + R"("})"),
          "/materials/m/" + std::string(key), "expected finite values >= 0");
  }
  // A non-colour texture may hold negative numbers, never NaN.
  EXPECT_SCENE_ERROR(scene_with_material(R"("m": {"type": "pbr", "normal_texture": ")" + exr_with_texel(NAN) + R"("})"),
                     "/materials/m/normal_texture", "expected finite values");
}

// Errors: whole files.

TEST_F(SceneLoaderErrors, EmptyScene) {
  EXPECT_SCENE_ERROR(R"({"materials": {"m": {"type": "diffuse"}}, "shapes": [], "lights": []})", "",
                     "scene is empty");
}

TEST_F(SceneLoaderErrors, MalformedCameraIsNamedBeforeAnEmptyScene) {
  EXPECT_SCENE_ERROR(R"({"camera": 3})", "/camera", "expected an object");
}

TEST_F(SceneLoaderErrors, MissingSceneFile) {
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

// A pipe or a device would block or stream forever: refused before anything reads it, as a scene and as a texture.
TEST_F(SceneLoaderErrors, PipesAndDevicesAreRefused) {
  const std::string pipe = (test_dir() / "pipe.json").string();
  std::filesystem::remove(pipe);  // test folders are named by process id and not always removed
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  for (const std::string& path : {pipe, std::string("/dev/zero")}) {
    try {
      load_scene(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.detail, "is not a regular file (a pipe, device or socket), expected a scene file") << path;
    }
  }
  EXPECT_SCENE_ERROR(scene_with_material(R"("m": {"type": "diffuse", "texture": "pipe.json"})"),
                     "/materials/m/texture", "is not a regular file (a pipe, device or socket)");
  EXPECT_SCENE_ERROR(scene_with_material(R"("m": {"type": "diffuse", "texture": "/dev/zero"})"),
                     "/materials/m/texture", "is not a regular file (a pipe, device or socket)");
}

TEST_F(SceneLoaderErrors, UnknownFileExtension) {
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
