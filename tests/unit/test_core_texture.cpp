// Texture::sample (core/texture.cpp): glTF uv orientation, texel centres, bilinear weights, wrap modes, nearest
// filtering, KHR_texture_transform before wrapping, and the implicit channels of 1-, 2- and 3-channel images.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/texture.h"

namespace lumis {
namespace {

/// W x H one-channel image whose texel (x, y) holds 10 y + x, so that every texel is recognisable.
std::shared_ptr<const Image> ramp(int w, int h) {
  auto img = std::make_shared<Image>(w, h, std::vector<std::string>{"Y"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img->at(x, y, 0) = static_cast<float>(10 * y + x);
  return img;
}

Texture make_texture(std::shared_ptr<const Image> img, WrapMode s = WrapMode::Repeat, WrapMode t = WrapMode::Repeat) {
  Texture tex;
  tex.image = std::move(img);
  tex.wrap_s = s;
  tex.wrap_t = t;
  return tex;
}

/// uv of the centre of texel (x, y) in a W x H image.
Vec2 centre(int x, int y, int w, int h) { return {(x + 0.5f) / w, (y + 0.5f) / h}; }

TEST(Texture, TexelCentresAreExactAndRowZeroIsTop) {
  const Texture tex = make_texture(ramp(4, 3));
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_NEAR(tex.sample(centre(x, y, 4, 3)).x, 10.0f * y + x, 1e-4f);
  // glTF: uv (0, 0) is the top-left corner, v grows downward, so small v reads row 0.
  EXPECT_NEAR(tex.sample({0.125f, 1.0f / 6}).x, 0.0f, 1e-4f);
  EXPECT_NEAR(tex.sample({0.125f, 5.0f / 6}).x, 20.0f, 1e-4f);
}

TEST(Texture, BilinearWeights) {
  const Texture tex = make_texture(ramp(4, 4), WrapMode::ClampToEdge, WrapMode::ClampToEdge);
  // A quarter of the way from texel (1, 1) to (2, 1) and three quarters from row 1 to row 2.
  const Vec2 a = centre(1, 1, 4, 4);
  const Vec2 uv{a.x + 0.25f / 4, a.y + 0.75f / 4};
  const float expected = 0.75f * 0.25f * 11 + 0.25f * 0.25f * 12 + 0.75f * 0.75f * 21 + 0.25f * 0.75f * 22;
  EXPECT_NEAR(tex.sample(uv).x, expected, 1e-4f);
  // Midway between four texels: their mean.
  EXPECT_NEAR(tex.sample({0.5f, 0.5f}).x, (11 + 12 + 21 + 22) / 4.0f, 1e-4f);
  // Bilinear interpolation reproduces a linear ramp exactly inside the image.
  for (float u = 0.2f; u < 0.8f; u += 0.07f)
    EXPECT_NEAR(tex.sample({u, centre(0, 2, 4, 4).y}).x, 4 * u - 0.5f + 20, 1e-4f);
}

TEST(Texture, RepeatWrapsAcrossTheSeam) {
  const Texture tex = make_texture(ramp(4, 2));
  // At u = 0 the left neighbour of texel 0 is texel 3 (the other side of the seam): their mean.
  EXPECT_NEAR(tex.sample({0.0f, 0.25f}).x, (0 + 3) / 2.0f, 1e-5f);
  // Periodic in both directions, for negative and far-away coordinates.
  for (const Vec2 uv : {Vec2(0.3f, 0.2f), Vec2(0.9f, 0.7f), Vec2(0.01f, 0.99f)})
    for (const Vec2 shift : {Vec2(1, 0), Vec2(-3, 2), Vec2(1000, -1000)})
      EXPECT_NEAR(tex.sample(uv + shift).x, tex.sample(uv).x, 2e-3f) << uv.x << "," << uv.y;
}

TEST(Texture, ClampToEdge) {
  const Texture tex = make_texture(ramp(4, 2), WrapMode::ClampToEdge, WrapMode::ClampToEdge);
  // Beyond the edge centre, reads stay on the edge texels.
  EXPECT_FLOAT_EQ(tex.sample({0.0f, 0.25f}).x, 0.0f);
  EXPECT_FLOAT_EQ(tex.sample({-5.0f, 0.25f}).x, 0.0f);
  EXPECT_FLOAT_EQ(tex.sample({1.0f, 0.25f}).x, 3.0f);
  EXPECT_FLOAT_EQ(tex.sample({7.5f, 9.0f}).x, 13.0f);
  EXPECT_FLOAT_EQ(tex.sample({-1e30f, 1e30f}).x, 10.0f);
}

TEST(Texture, MirroredRepeat) {
  const Texture tex = make_texture(ramp(4, 2), WrapMode::MirroredRepeat, WrapMode::ClampToEdge);
  // Mirror symmetry about u = 1 and about u = 0, period 2.
  for (const float d : {0.05f, 0.3f, 0.61f}) {
    EXPECT_NEAR(tex.sample({1 + d, 0.25f}).x, tex.sample({1 - d, 0.25f}).x, 1e-5f) << d;
    EXPECT_NEAR(tex.sample({-d, 0.25f}).x, tex.sample({d, 0.25f}).x, 1e-5f) << d;
    EXPECT_NEAR(tex.sample({2 + d, 0.25f}).x, tex.sample({d, 0.25f}).x, 1e-5f) << d;
  }
  // At the seams the edge texel meets its own mirror image: no blending with the far side.
  EXPECT_NEAR(tex.sample({1.0f, 0.25f}).x, 3.0f, 1e-6f);
  EXPECT_NEAR(tex.sample({0.0f, 0.25f}).x, 0.0f, 1e-6f);
  // Texel centres of the mirrored copy: u in [1, 2) reads texels 3, 2, 1, 0.
  EXPECT_FLOAT_EQ(tex.sample({1 + 0.5f / 4, 0.25f}).x, 3.0f);
  EXPECT_FLOAT_EQ(tex.sample({1 + 3.5f / 4, 0.25f}).x, 0.0f);
}

TEST(Texture, NearestFiltering) {
  Texture tex = make_texture(ramp(4, 2));
  tex.nearest = true;
  EXPECT_EQ(tex.sample({0.26f, 0.1f}).x, 1.0f);
  EXPECT_EQ(tex.sample({0.49f, 0.6f}).x, 11.0f);
  EXPECT_EQ(tex.sample({-0.01f, 0.1f}).x, 3.0f);  // repeat
  tex.wrap_s = WrapMode::MirroredRepeat;
  EXPECT_EQ(tex.sample({1.1f, 0.1f}).x, 3.0f);    // texel 4 of the period mirrors to texel 3
  EXPECT_EQ(tex.sample({-0.01f, 0.1f}).x, 0.0f);
  tex.wrap_s = WrapMode::ClampToEdge;
  EXPECT_EQ(tex.sample({3.0f, 0.1f}).x, 3.0f);
}

TEST(Texture, TransformAppliesBeforeWrapping) {
  Texture plain = make_texture(ramp(8, 8), WrapMode::MirroredRepeat, WrapMode::Repeat);
  Texture moved = plain;
  moved.transform.offset = {0.3f, -0.2f};
  moved.transform.rotation = 0.7f;
  moved.transform.scale = {2.0f, 0.5f};
  for (const Vec2 uv : {Vec2(0.1f, 0.2f), Vec2(0.7f, 0.9f), Vec2(0.45f, 0.05f)}) {
    EXPECT_NEAR(moved.sample(uv).x, plain.sample(moved.transform.apply(uv)).x, 1e-4f);
  }
  // Offset only: shifts by whole texels; scale 2 with repeat: tiles the texture twice.
  Texture shifted = plain;
  shifted.transform.offset = {1.0f / 8, 0};
  EXPECT_FLOAT_EQ(shifted.sample(centre(2, 3, 8, 8)).x, 33.0f);
  Texture tiled = make_texture(ramp(8, 8));
  tiled.transform.scale = {2, 2};
  EXPECT_NEAR(tiled.sample({0.3f, 0.2f}).x, tiled.sample({0.8f, 0.7f}).x, 1e-4f);
}

// KHR_texture_transform's rotation turns the uvs counter-clockwise as the uv map is drawn (u right, v down):
// u' = c u + s v, v' = -s u + c v, so +u turns toward -v. The GLSL listing in the extension's README reads the
// other way in a v-up space. This direction is the README's wording, and by the discussion in glTF issue #1563 the
// one Babylon.js, three.js and the sample model TextureTransformTest agree on (the model, rendered, is checked by
// GltfModels.TextureTransformArrowPointsAtTheCorrectMarker). Offset and scale around it: uv' = offset + R(scale * uv).
TEST(Texture, TransformRotationDirection) {
  TextureTransform t;
  t.rotation = kPi / 2;
  const Vec2 a = t.apply({0.25f, 0});
  EXPECT_NEAR(a.x, 0.0f, 1e-6f);
  EXPECT_NEAR(a.y, -0.25f, 1e-6f);
  const Vec2 b = t.apply({0, 0.25f});
  EXPECT_NEAR(b.x, 0.25f, 1e-6f);
  EXPECT_NEAR(b.y, 0.0f, 1e-6f);
  t.rotation = 0.392699f;  // the sample model's 22.5 degrees
  t.scale = {2, 0.5f};
  t.offset = {0.1f, 0.3f};
  const float c = std::cos(0.392699f), s = std::sin(0.392699f);
  const Vec2 d = t.apply({0.4f, 0.6f});
  EXPECT_NEAR(d.x, 0.1f + c * 0.8f + s * 0.3f, 1e-6f);
  EXPECT_NEAR(d.y, 0.3f - s * 0.8f + c * 0.3f, 1e-6f);
}

TEST(Texture, ImplicitChannels) {
  auto grey = std::make_shared<Image>(1, 1, std::vector<std::string>{"Y"});
  grey->at(0, 0, 0) = 0.25f;
  Vec4 v = make_texture(grey).sample({0.5f, 0.5f});
  EXPECT_NEAR(v.x, 0.25f, 1e-6f);
  EXPECT_NEAR(v.y, 0.25f, 1e-6f);
  EXPECT_NEAR(v.z, 0.25f, 1e-6f);
  EXPECT_NEAR(v.w, 1.0f, 1e-6f);

  auto grey_alpha = std::make_shared<Image>(1, 1, std::vector<std::string>{"Y", "A"});
  grey_alpha->at(0, 0, 0) = 0.5f;
  grey_alpha->at(0, 0, 1) = 0.75f;
  v = make_texture(grey_alpha).sample({0.2f, 0.9f});
  EXPECT_NEAR(v.y, 0.5f, 1e-6f);
  EXPECT_NEAR(v.w, 0.75f, 1e-6f);

  auto rgb = std::make_shared<Image>(1, 1, std::vector<std::string>{"R", "G", "B"});
  rgb->at(0, 0, 0) = 0.1f;
  rgb->at(0, 0, 1) = 0.2f;
  rgb->at(0, 0, 2) = 0.3f;
  v = make_texture(rgb).sample({0.7f, 0.1f});
  EXPECT_NEAR(v.y, 0.2f, 1e-6f);
  EXPECT_NEAR(v.z, 0.3f, 1e-6f);
  EXPECT_NEAR(v.w, 1.0f, 1e-6f);

  auto rgba = std::make_shared<Image>(2, 1, std::vector<std::string>{"R", "G", "B", "A"});
  for (int c = 0; c < 4; ++c) rgba->at(0, 0, c) = 0.1f * (c + 1), rgba->at(1, 0, c) = 0.2f * (c + 1);
  v = make_texture(rgba, WrapMode::ClampToEdge).sample({0.5f, 0.5f});
  EXPECT_NEAR(v.w, 0.6f, 1e-6f);
  EXPECT_NEAR(v.x, 0.15f, 1e-6f);

  // No pixels: neutral under multiplication.
  v = Texture{}.sample({0.5f, 0.5f});
  EXPECT_EQ(v.x, 1.0f);
  EXPECT_EQ(v.w, 1.0f);
}

TEST(Texture, NonFiniteUvDoesNotCrash) {
  const Texture tex = make_texture(ramp(4, 4));
  for (const Vec2 uv : {Vec2(NAN, 0.5f), Vec2(INFINITY, -INFINITY), Vec2(1e38f, -1e38f)}) {
    const Vec4 v = tex.sample(uv);
    EXPECT_TRUE(std::isfinite(v.x));
  }
}

}  // namespace
}  // namespace lumis
