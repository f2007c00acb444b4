// glTF textures on small synthetic files written here: embedded (data: URI, .glb bufferView) and external images,
// samplers, KHR_texture_transform, sRGB and linear decoding, grey images, a texture whose UV set the primitive lacks.
// The rest of the loader's synthetic files are in test_gltf_files.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "app/gltf_loader.h"
#include "core/image_io.h"
#include "tests/app/gltf_synthetic.h"
#include "tests/app/gltf_test_util.h"
#include "tests/app/png_test_util.h"

namespace fs = std::filesystem;
using namespace lumis;
using namespace lumis::gltf_test;

TEST_F(GltfFiles, TexturesEmbeddedExternalSamplersAndTransforms) {
  // A 2x1 RGBA PNG: used embedded (data: URI) and external, both decoded by OpenImageIO.
  const std::string png = (dir_ / "tex.png").string();
  const unsigned char px[8] = {200, 100, 50, 128, 0, 255, 10, 255};
  ASSERT_TRUE(test::write_png(png, 2, 1, 4, px));
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
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_NE(s.warnings[0].find("KHR_materials_volume"), std::string::npos);
  // The triangle has no texture coordinates: its textures read uv (0, 0), which is named (once, by the first).
  EXPECT_EQ(s.warnings[1], "meshes[0].primitives[0]: its material's baseColorTexture reads TEXCOORD_1, which the "
                           "primitive does not have; every point reads the texture at uv (0, 0)");
}

// A texture read through TEXCOORD_1 on a primitive that has TEXCOORD_0 only: a warning (once the whole quad came
// out the colour of one texel, silently); through TEXCOORD_0, none.
TEST_F(GltfFiles, ATextureWithoutItsUvSetIsNamed) {
  const unsigned char px[4] = {255, 0, 0, 255};
  ASSERT_TRUE(test::write_png(file("red.png"), 1, 1, 4, px));
  Triangle t;
  const size_t uv = t.bin.add<float>({0, 0, 1, 0, 0, 1});
  const std::string views = t.views.substr(0, t.views.size() - 1) + "," + Triangle::view(uv, 24) + "]";
  const std::string acc = t.accessors.substr(0, t.accessors.size() - 1) +
                          R"(,{"bufferView":3,"componentType":5126,"count":3,"type":"VEC2"}])";
  const std::string prim = R"({"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":3},"indices":2,"material":0})";
  for (const int set : {0, 1}) {
    const std::string extra = R"(,"images":[{"uri":"red.png"}],"textures":[{"source":0}],"materials":[)"
                              R"({"emissiveFactor":[1,1,1],"emissiveTexture":{"index":0,"texCoord":)" +
                              std::to_string(set) + "}}]";
    const GltfScene s = load_gltf(simple("uv.gltf", t.bin, views, acc, prim, R"({"mesh":0})", extra));
    if (set == 0) {
      EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
      continue;
    }
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_EQ(s.warnings[0], "meshes[0].primitives[0]: its material's emissiveTexture reads TEXCOORD_1, which the "
                             "primitive does not have; every point reads the texture at uv (0, 0)");
  }
}

// The same PNG or JPEG bytes give the same texels whether the image is an external file, a bufferView of a .glb or a
// data: URI: OpenImageIO decodes all three (tinygltf's stb_image, once used for embedded images, decodes JPEG
// differently by up to a few 8-bit levels).
TEST_F(GltfFiles, EmbeddedImagesDecodeExactlyAsExternalOnes) {
  // A colourful JPEG (libjpeg's default 4:2:0 chroma subsampling, where decoders differ most) and an RGBA PNG.
  Image pattern(61, 37, {"R", "G", "B", "A"});
  for (int y = 0; y < pattern.height; ++y)
    for (int x = 0; x < pattern.width; ++x)
      for (int c = 0; c < 4; ++c) pattern.at(x, y, c) = float(((x * 37 + y * 91 + c * 53) ^ (x * y)) % 256) / 255;
  write_image((dir_ / "tex.jpg").string(), pattern);
  const std::string png = (dir_ / "tex.png").string();
  {
    std::vector<unsigned char> px(pattern.data.size());
    for (size_t i = 0; i < px.size(); ++i) px[i] = static_cast<unsigned char>(std::lround(pattern.data[i] * 255));
    ASSERT_TRUE(test::write_png(png, pattern.width, pattern.height, 4, px.data()));
  }
  const std::string prim = R"({"attributes":{"POSITION":0,"NORMAL":1},"indices":2,"material":0})";
  // Base colour (sRGB-decoded) and metallic-roughness (linear) from the one image.
  const std::string textures = R"(,"textures":[{"source":0}],"materials":[{"pbrMetallicRoughness":)"
                               R"({"baseColorTexture":{"index":0},"metallicRoughnessTexture":{"index":0}}}])";
  for (const std::string name : {"tex.jpg", "tex.png"}) {
    SCOPED_TRACE(name);
    const std::string mime = name == "tex.jpg" ? "image/jpeg" : "image/png";
    const std::vector<unsigned char> bytes = file_bytes((dir_ / name).string());
    Triangle t;
    const GltfScene external = load_gltf(simple("external.gltf", t.bin, t.views, t.accessors, prim, R"({"mesh":0})",
                                                R"(,"images":[{"uri":")" + name + "\"}]" + textures));
    const GltfScene data_uri = load_gltf(
        simple("data.gltf", t.bin, t.views, t.accessors, prim, R"({"mesh":0})",
               R"(,"images":[{"uri":"data:)" + mime + ";base64," + base64(bytes) + "\"}]" + textures));
    // The .glb: the image in bufferView 3 of the BIN chunk.
    Bin bin = t.bin;
    const size_t at = bin.add<uint8_t>({});
    bin.bytes.insert(bin.bytes.end(), bytes.begin(), bytes.end());
    const std::string views = t.views.substr(0, t.views.size() - 1) + "," + Triangle::view(at, bytes.size()) + "]";
    const std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
                             R"("meshes":[{"primitives":[)" + prim + R"(]}],"buffers":[{"byteLength":)" +
                             std::to_string(bin.bytes.size()) + R"(}],"bufferViews":)" + views +
                             R"(,"accessors":)" + t.accessors + R"(,"images":[{"bufferView":3,"mimeType":")" + mime +
                             "\"}]" + textures + "}";
    const GltfScene binary = load_gltf(write("binary.glb", make_glb(json, bin.bytes)));
    for (const GltfScene* s : {&data_uri, &binary}) {
      for (int k = 0; k < 2; ++k) {
        const PbrParams &a = external.materials[0].params, &b = s->materials[0].params;
        const Image& x = *(k == 0 ? a.base_color_texture : a.metallic_roughness_texture)->image;
        const Image& y = *(k == 0 ? b.base_color_texture : b.metallic_roughness_texture)->image;
        ASSERT_EQ(x.channel_names, y.channel_names);
        ASSERT_EQ(x.data.size(), y.data.size());
        size_t differ = 0;
        for (size_t i = 0; i < x.data.size(); ++i) differ += x.data[i] != y.data[i];
        EXPECT_EQ(differ, 0u) << (s == &binary ? ".glb" : "data: URI") << (k == 0 ? ", sRGB" : ", linear");
      }
    }
    EXPECT_EQ(external.materials[0].params.base_color_texture->image->channels, name == "tex.png" ? 4 : 3);
  }
}

// Grey textures become RGB: a grey PNG's one channel fills R, G and B; a grey + alpha PNG's second channel is its
// alpha, which stays linear while the grey is decoded from sRGB.
TEST_F(GltfFiles, GreyTexturesBecomeRgb) {
  const unsigned char grey_px[2] = {40, 220}, grey_alpha_px[4] = {40, 60, 220, 250};
  ASSERT_TRUE(test::write_png(file("grey.png"), 2, 1, 1, grey_px));
  ASSERT_TRUE(test::write_png(file("grey_alpha.png"), 2, 1, 2, grey_alpha_px));
  Triangle t;
  const std::string extra =
      R"(,"images":[{"uri":"grey.png"},{"uri":"grey_alpha.png"}],"textures":[{"source":0},{"source":1}],)"
      R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}},)"
      R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":1}}}])";
  const std::string prim = R"({"attributes":{"POSITION":0,"NORMAL":1},"indices":2,"material":0})";
  const GltfScene s = load_gltf(simple("g.gltf", t.bin, t.views, t.accessors, prim, R"({"mesh":0})", extra));
  ASSERT_EQ(s.materials.size(), 2u);
  const Image& grey = *s.materials[0].params.base_color_texture->image;
  const Image& grey_alpha = *s.materials[1].params.base_color_texture->image;
  ASSERT_EQ(grey.channels, 3);
  ASSERT_EQ(grey_alpha.channels, 4);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(grey.at(1, 0, c), srgb_to_linear(220 / 255.0f), 1e-6f) << c;
    EXPECT_NEAR(grey_alpha.at(0, 0, c), srgb_to_linear(40 / 255.0f), 1e-6f) << c;
    EXPECT_NEAR(grey_alpha.at(1, 0, c), srgb_to_linear(220 / 255.0f), 1e-6f) << c;
  }
  EXPECT_NEAR(grey_alpha.at(0, 0, 3), 60 / 255.0f, 1e-6f);
  EXPECT_NEAR(grey_alpha.at(1, 0, 3), 250 / 255.0f, 1e-6f);
}
