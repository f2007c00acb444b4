// glTF loader errors on small synthetic files: component types as core glTF 2.0 allows them, and every error path
// named by its glTF path (accessors, buffers and their files, versions, nodes, images).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "app/gltf_loader.h"
#include "app/scene_loader.h"
#include "app/scene_error.h"
#include "tests/app/gltf_synthetic.h"
#include "tests/app/gltf_test_util.h"

namespace fs = std::filesystem;
using namespace lumis;
using namespace lumis::gltf_test;

// Component types as core glTF 2.0 allows them where the accessor is used (KHR_mesh_quantization, which allows
// more, is not supported): an unsigned-byte POSITION was read as small integers, and its triangles dropped.
TEST_F(GltfFiles, ComponentTypesAreThoseOfCoreGltf) {
  Triangle t;
  // accessors[3]: the positions' bytes as normalized unsigned bytes (VEC3), [4] as plain unsigned bytes (VEC2).
  const std::string acc = t.accessors.substr(0, t.accessors.size() - 1) +
                          R"(,{"bufferView":0,"componentType":5121,"normalized":true,"count":3,"type":"VEC3"})"
                          R"(,{"bufferView":0,"componentType":5121,"count":3,"type":"VEC2"}])";
  auto with = [&](const std::string& from, const std::string& to) {
    std::string a = acc;
    a.replace(a.find(from), from.size(), to);
    return a;
  };
  const std::string quantization = "other types need KHR_mesh_quantization, which lumis does not support";
  expect_error(simple("pos.gltf", t.bin, t.views, with(R"("componentType":5126)", R"("componentType":5121)"),
                      Triangle::prim),
               {"pos.gltf:accessors[0].componentType: UNSIGNED_BYTE, expected FLOAT (used by "
                "meshes[0].primitives[0].attributes.POSITION)",
                quantization});
  expect_error(simple("normal.gltf", t.bin, t.views, acc, R"({"attributes":{"POSITION":0,"NORMAL":3}})"),
               {"accessors[3].componentType: normalized UNSIGNED_BYTE, expected FLOAT", "attributes.NORMAL"});
  expect_error(simple("uv.gltf", t.bin, t.views, acc, R"({"attributes":{"POSITION":0,"TEXCOORD_0":4}})"),
               {"accessors[4].componentType: UNSIGNED_BYTE, expected FLOAT, normalized UNSIGNED_BYTE or normalized "
                "UNSIGNED_SHORT (used by meshes[0].primitives[0].attributes.TEXCOORD_0)",
                quantization});
  // KHR_mesh_quantization allows no other types for COLOR_0: the message does not send the author to it.
  try {
    load_gltf(simple("color.gltf", t.bin, t.views, with(R"("normalized":true,)", ""),
                     R"({"attributes":{"POSITION":0,"COLOR_0":3}})"));
    ADD_FAILURE() << "plain unsigned-byte COLOR_0 accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.detail, "UNSIGNED_BYTE, expected FLOAT, normalized UNSIGNED_BYTE or normalized UNSIGNED_SHORT (used "
                        "by meshes[0].primitives[0].attributes.COLOR_0)");
  }
  // Allowed as COLOR_0 in the first primitive, not as NORMAL in the second (the decoded accessor is shared).
  expect_error(simple("shared.gltf", t.bin, t.views, acc,
                      R"({"attributes":{"POSITION":0,"COLOR_0":3}},{"attributes":{"POSITION":0,"NORMAL":3}})"),
               {"accessors[3].componentType", "meshes[0].primitives[1].attributes.NORMAL"});
  try {
    load_gltf(simple("index.gltf", t.bin, t.views, with(R"("componentType":5123)", R"("componentType":5126)"),
                     Triangle::prim));
    ADD_FAILURE() << "float indices accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.location, "accessors[2].componentType");
    EXPECT_EQ(e.detail, "FLOAT, expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT (used by "
                        "meshes[0].primitives[0].indices)");
  }
  expect_error(simple("norm.gltf", t.bin, t.views,
                      with(R"("componentType":5123)", R"("componentType":5125,"normalized":true)"), Triangle::prim),
               {"accessors[2].normalized", "not allowed for FLOAT or UNSIGNED_INT"});
  // EXT_mesh_gpu_instancing: TRANSLATION is FLOAT.
  expect_error(simple("inst.gltf", t.bin, t.views, acc, Triangle::prim,
                      R"({"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":3}}}})"),
               {"accessors[3].componentType", "EXT_mesh_gpu_instancing.attributes.TRANSLATION"});
}

// tinygltf copies the document into its own values recursively: 20,000 levels of "extras" overflowed the stack
// (a crash, exit 139). Nesting beyond 512 levels is refused with its line and column, in a .gltf and in a .glb's
// JSON chunk; brackets inside strings do not count, and 512 levels still load.
TEST_F(GltfFiles, DeeplyNestedJsonIsRefusedNotACrash) {
  Triangle t;
  auto with_extras = [&](const std::string& name, const std::string& extras) {
    return simple(name, t.bin, t.views, t.accessors, Triangle::prim, R"({"mesh":0})", R"(,"extras":)" + extras);
  };
  auto nested = [](size_t levels) { return std::string(levels, '[') + std::string(levels, ']'); };
  const std::string deep = with_extras("deep.gltf", nested(20000));
  // The first '[' of the extras opens level 2 (the document's '{' is level 1): level 513 is 511 brackets further.
  std::ifstream in(deep, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string column = std::to_string(text.find('[', text.find("\"extras\"")) + 511 + 1);
  expect_error(deep, {"deep.gltf: the JSON nests deeper than 512 levels (at line:column 1:" + column +
                      "); lumis reads at most 512"});
  expect_error(write("deep.glb", make_glb(R"({"asset":{"version":"2.0"},"extras":)" + nested(20000) + "}", {})),
               {"deep.glb: the JSON chunk nests deeper than 512 levels"});
  EXPECT_EQ(load_gltf(with_extras("deep511.gltf", nested(511))).meshes.size(), 1u);  // 512 levels in all
  EXPECT_EQ(load_gltf(with_extras("quoted.gltf", "\"" + std::string(20000, '[') + "\\\"{\"")).meshes.size(), 1u);
  // An escaped quote does not end the string: the brackets after it are still inside.
  EXPECT_EQ(load_gltf(with_extras("escaped.gltf", "\"\\\"" + std::string(20000, '[') + "\"")).meshes.size(), 1u);
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
  expect_error(write("junk.gltf", "{ this is not json"), {"junk.gltf:1:4: invalid JSON: syntax error"});
  std::string glb("glTF\x02\0\0\0\xe8\x03\0\0\x08\0\0\0JSON{}      ", 28);
  expect_error(write("short.glb", glb), {"invalid .glb"});
  expect_error((dir_ / "absent.gltf").string(), {"no such file"});
  expect_error(simple("req.gltf", t.bin, t.views, t.accessors, R"({"attributes":{"POSITION":0}})", R"({"mesh":0})",
                      R"(,"extensionsRequired":["KHR_draco_mesh_compression"])"),
               {"extensionsRequired: required extension KHR_draco_mesh_compression is not supported"});
  // Every unsupported one is named (once only the first), the supported ones are not.
  expect_error(simple("reqs.gltf", t.bin, t.views, t.accessors, R"({"attributes":{"POSITION":0}})", R"({"mesh":0})",
                      R"(,"extensionsRequired":["KHR_draco_mesh_compression","KHR_texture_transform",)"
                      R"("EXT_meshopt_compression"])"),
               {"extensionsRequired: required extensions KHR_draco_mesh_compression, EXT_meshopt_compression are not "
                "supported"});
  // Buffer files: missing (the path looked for named), of the wrong size, in a .gltf or a .glb.
  auto tri = [&](const std::string& buffer, const std::string& asset = R"({"version":"2.0"})") {
    return R"({"asset":)" + asset + R"(,"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"bufferViews":)" + t.views +
           R"(,"accessors":)" + t.accessors + R"(,"buffers":[)" + buffer + "]}";
  };
  const std::string length = R"({"byteLength":)" + std::to_string(t.bin.bytes.size());
  expect_error(write("nobuf.gltf", tri(length + R"(,"uri":"no%20such.bin"})")),
               {"nobuf.gltf:buffers[0].uri: buffer file 'no%20such.bin' not found (looked for",
                (dir_ / "no such.bin").string()});
  expect_error(write("nobuf.glb", make_glb(tri(length + R"(,"uri":"nope.bin"})"), {})),
               {"nobuf.glb:buffers[0].uri", (dir_ / "nope.bin").string()});
  write("short.bin", std::string(t.bin.bytes.begin(), t.bin.bytes.begin() + 40));
  expect_error(write("short.gltf", tri(length + R"(,"uri":"short.bin"})")),
               {"short.gltf:buffers[0].byteLength: is 78, but the file", "has 40 bytes"});
  // A buffer or image that is a pipe would block tinygltf's read forever: refused, and said to be one; a folder
  // (the URI ".") is said to be a folder, not "not found".
  ASSERT_EQ(::mkfifo((dir_ / "pipe.bin").c_str(), 0600), 0);
  expect_error(write("pipe.gltf", tri(length + R"(,"uri":"pipe.bin"})")),
               {"pipe.gltf:buffers[0].uri: buffer file 'pipe.bin' is not a regular file (a pipe, device or socket)"});
  ASSERT_EQ(::mkfifo((dir_ / "pipe.png").c_str(), 0600), 0);
  expect_error(simple("pipeimg.gltf", t.bin, t.views, t.accessors, prim, R"({"mesh":0})",
                      R"(,"images":[{"uri":"pipe.png"}])" + mat),
               {"pipeimg.gltf:images[0]: image file 'pipe.png' is not a regular file (a pipe, device or socket)"});
  expect_error(write("dot.gltf", tri(length + R"(,"uri":"."})")),
               {"dot.gltf:buffers[0].uri: buffer file '.' is a folder"});
  std::filesystem::create_directories(dir_ / "texdir.png");
  expect_error(simple("dirimg.gltf", t.bin, t.views, t.accessors, prim, R"({"mesh":0})",
                      R"(,"images":[{"uri":"texdir.png"}])" + mat),
               {"dirimg.gltf:images[0]: image file 'texdir.png' is a folder"});
  // tinygltf falls back to the working folder; lumis looks only where the file says.
  write("cwd.bin", std::string(t.bin.bytes.begin(), t.bin.bytes.end()));
  fs::create_directories(dir_ / "sub");
  const std::string sub = write("sub/cwd.gltf", tri(length + R"(,"uri":"cwd.bin"})"));
  const fs::path cwd = fs::current_path();
  fs::current_path(dir_);
  expect_error(sub, {"buffers[0].uri", (dir_ / "sub" / "cwd.bin").string()});
  fs::current_path(cwd);

  // glTF 2.0 only: asset.version's major version, and minVersion.
  expect_error(write("v1.gltf", tri(t.bin.buffer_json(), R"({"version":"1.0"})")),
               {"v1.gltf:asset.version: glTF version \"1.0\": lumis reads glTF 2.0"});
  expect_error(write("v3.gltf", tri(t.bin.buffer_json(), R"({"version":"3.0"})")), {"asset.version", "3.0"});
  expect_error(write("min.gltf", tri(t.bin.buffer_json(), R"({"version":"2.0","minVersion":"2.1"})")),
               {"asset.minVersion", "2.1"});
  // A glTF 1.0 file proper (objects keyed by id where 2.0 has arrays), which tinygltf cannot read.
  expect_error(write("gltf1.gltf", R"({"asset":{"version":"1.0"},"scene":"s","scenes":{"s":{"nodes":["n"]}},)"
                                   R"("nodes":{"n":{"meshes":["m"]}},"buffers":{"b":{"uri":"b.bin"}}})"),
               {"gltf1.gltf:asset.version", "1.0"});

  // A real .glb cut short.
  if (fs::exists(kAssets / "Box/glTF-Binary/Box.glb")) {
    std::ifstream in(model("Box/glTF-Binary/Box.glb"), std::ios::binary);
    const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(all.size(), 100u);
    expect_error(write("cut.glb", all.substr(0, all.size() - 40)), {"invalid .glb"});
    expect_error(write("cut2.glb", all.substr(0, 30)), {"invalid .glb"});
  }
}

// Found by review (2026-12-06): material factors outside [0, 1] are clamped at load, before a texture multiplies
// them (the BSDF clamps only the product: a factor of 2 with a texel of 0.3 gave 0.6) and before the alpha cutoff
// sees the base alpha; a .glb buffer with "uri": "" is its BIN chunk to tinygltf, so another fault in the file is
// not blamed on the uri; one camera object in two nodes is ambiguous by its name.
TEST_F(GltfFiles, FactorsClampedAtLoadGlbEmptyUriAndSharedCameraNames) {
  Triangle t;
  const std::string mat = R"(,"materials":[{"pbrMetallicRoughness":{"baseColorFactor":[2,0.5,-1,3],)"
                          R"("metallicFactor":-1,"roughnessFactor":5}}])";
  const GltfScene s = load_gltf(simple("f.gltf", t.bin, t.views, t.accessors,
                                       R"({"attributes":{"POSITION":0,"NORMAL":1},"indices":2,"material":0})",
                                       R"({"mesh":0})", mat));
  ASSERT_GE(s.materials.size(), 1u);
  const PbrParams& p = s.materials[0].params;
  EXPECT_EQ(p.base_color[0], 1.0f);
  EXPECT_EQ(p.base_color[1], 0.5f);
  EXPECT_EQ(p.base_color[2], 0.0f);
  EXPECT_EQ(p.base_alpha, 1.0f);
  EXPECT_EQ(p.metallic, 0.0f);
  EXPECT_EQ(p.roughness, 1.0f);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("materials[0].pbrMetallicRoughness: a factor outside [0, 1] is clamped"),
            std::string::npos) << s.warnings[0];

  // A .glb whose buffer says "uri": "" renders from its BIN chunk; with a bufferView lacking byteLength, the error
  // is tinygltf's about that, not "buffers[0].uri: is empty".
  const std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
                           R"("meshes":[{"primitives":[)" + std::string(Triangle::prim) + R"(]}],"bufferViews":)" +
                           t.views + R"(,"accessors":)" + t.accessors + R"(,"buffers":[{"byteLength":)" +
                           std::to_string(t.bin.bytes.size()) + R"(,"uri":""}]})";
  EXPECT_EQ(load_gltf(write("empty-uri.glb", make_glb(json, t.bin.bytes))).meshes.size(), 1u);
  std::string broken = json;
  broken.replace(broken.find(R"(,"byteLength":36)"), 16, "");
  try {
    load_gltf(write("empty-uri-broken.glb", make_glb(broken, t.bin.bytes)));
    ADD_FAILURE() << "a bufferView without byteLength accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).find("is empty"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("byteLength"), std::string::npos) << e.what();
  }

  // Camera object 0, named "Lens", in nodes 1 to 6: "Lens" is ambiguous, even though node 3 has no name of its own
  // (it once took the object's and was chosen silently), and so is "Twin", the name of two nodes; the other node
  // names and the numbers are not. A node named "9" is found by name: there is no camera 9.
  const std::string cams =
      R"(,"cameras":[{"name":"Lens","type":"perspective","perspective":{"yfov":0.8,"znear":0.01}}])";
  std::string text = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2,3,4,5,6]}],"nodes":[{"mesh":0},)"
                     R"({"name":"Left","camera":0,"translation":[0,0,3]},)"
                     R"({"name":"Right","camera":0,"translation":[1,0,3]},)"
                     R"({"camera":0,"translation":[2,0,3]},{"name":"9","camera":0,"translation":[3,0,3]},)"
                     R"({"name":"Twin","camera":0,"translation":[4,0,3]},)"
                     R"({"name":"Twin","camera":0,"translation":[5,0,3]}],"meshes":[{"primitives":[)" +
                     std::string(Triangle::prim) + R"(]}],"buffers":[)" + t.bin.buffer_json() + R"(],"bufferViews":)" +
                     t.views + R"(,"accessors":)" + t.accessors + cams + "}";
  const std::string two = write("cams.gltf", text);
  EXPECT_EQ(load_scene(two, SceneLoadOptions{"Right"})->camera.from, Vec3(1, 0, 3));
  EXPECT_EQ(load_scene(two, SceneLoadOptions{"2"})->camera.from, Vec3(2, 0, 3));
  EXPECT_EQ(load_scene(two, SceneLoadOptions{"9"})->camera.from, Vec3(3, 0, 3));
  const std::pair<const char*, std::string> ambiguous[] = {
      {"Lens", "camera 'Lens' of " + two + " is in several nodes: 0 (nodes[1]), 1 (nodes[2]), 2 (nodes[3]), 3 "
               "(nodes[4]), 4 (nodes[5]), 5 (nodes[6]); give the number or the node's name"},
      {"Twin", "several camera nodes of " + two + " are named 'Twin': 4 (nodes[5]), 5 (nodes[6]); give the number"}};
  for (const auto& [name, says] : ambiguous) {
    try {
      load_scene(two, SceneLoadOptions{name});
      ADD_FAILURE() << "an ambiguous camera name accepted: " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  }
}
