// Materials (materials/diffuse.cpp, ggx.cpp, pbr.cpp) and the shading-normal rule (materials/shading.cpp):
// textures and vertex colours reach the BSDF, metallic-roughness channels, normal maps with and without tangents,
// handedness, normal_scale, and the clamps that keep shading normals usable.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "materials/material.h"
#include "materials/shading.h"

namespace lumis {
namespace {

/// A hit on the plane z = 0 seen from above, tangent +x (handedness +1), uv (0.5, 0.5).
Hit plane_hit() {
  Hit h;
  h.p = Vec3(0, 0, 0);
  h.ng = h.ns = Vec3(0, 0, 1);
  h.tangent = Vec4(1, 0, 0, 1);
  h.uv[0] = h.uv[1] = Vec2(0.5f, 0.5f);
  return h;
}

/// 1 x 1 texture of constant RGBA.
Texture constant_texture(float r, float g, float b, float a = 1) {
  auto img = std::make_shared<Image>(1, 1, std::vector<std::string>{"R", "G", "B", "A"});
  img->at(0, 0, 0) = r;
  img->at(0, 0, 1) = g;
  img->at(0, 0, 2) = b;
  img->at(0, 0, 3) = a;
  Texture t;
  t.image = img;
  return t;
}

/// Normal-map texel encoding unit tangent-space normal n.
Texture normal_texel(Vec3 n) { return constant_texture(0.5f * n.x + 0.5f, 0.5f * n.y + 0.5f, 0.5f * n.z + 0.5f); }

void expect_orthonormal(const Frame& f) {
  EXPECT_NEAR(length(f.s), 1.0f, 1e-5f);
  EXPECT_NEAR(length(f.t), 1.0f, 1e-5f);
  EXPECT_NEAR(length(f.n), 1.0f, 1e-5f);
  EXPECT_NEAR(dot(f.s, f.t), 0.0f, 1e-5f);
  EXPECT_NEAR(dot(f.s, f.n), 0.0f, 1e-5f);
  EXPECT_NEAR(dot(f.t, f.n), 0.0f, 1e-5f);
  EXPECT_NEAR(dot(cross(f.s, f.t), f.n), 1.0f, 1e-5f);  // right-handed
}

void expect_same_bsdf(const Bsdf& a, const Bsdf& b) {
  const Vec3 dirs[] = {Vec3(0, 0, 1), normalize(Vec3(0.3f, 0.2f, 0.9f)), normalize(Vec3(-0.5f, 0.1f, 0.4f)),
                       normalize(Vec3(-0.3f, -0.2f, 0.9f))};
  for (const Vec3 wo : dirs)
    for (const Vec3 wi : dirs) {
      const Color fa = a.f(wo, wi), fb = b.f(wo, wi);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(fa[k], fb[k], 1e-5f * std::max(1.0f, std::abs(fb[k])));
      EXPECT_NEAR(a.pdf(wo, wi), b.pdf(wo, wi), 1e-5f * std::max(1.0f, b.pdf(wo, wi)));
    }
}

TEST(DiffuseMaterial, TextureAndVertexColourMultiplyAlbedo) {
  Hit hit = plane_hit();
  hit.color = Vec4(0.5f, 1, 1, 1);
  const auto m = make_diffuse_material(Color(0.8f, 0.6f, 0.4f), constant_texture(0.5f, 0.5f, 1));
  const Color a = m->albedo(hit);
  EXPECT_NEAR(a.x, 0.8f * 0.5f * 0.5f, 1e-6f);
  EXPECT_NEAR(a.y, 0.6f * 0.5f, 1e-6f);
  EXPECT_NEAR(a.z, 0.4f, 1e-6f);
  const ShadingPoint sp = m->shade(hit);
  expect_same_bsdf(sp.bsdf, DiffuseBsdf{a});
  EXPECT_NEAR(sp.frame.n.z, 1.0f, 1e-6f);
  expect_orthonormal(sp.frame);
}

TEST(GgxMaterial, RoughnessIsSquaredAndClamped) {
  const Hit hit = plane_hit();
  expect_same_bsdf(make_ggx_material(Color(0.9f), 0.5f)->shade(hit).bsdf, GgxBsdf{Color(0.9f), 0.25f});
  expect_same_bsdf(make_ggx_material(Color(0.9f), 0.0f)->shade(hit).bsdf, GgxBsdf{Color(0.9f), kMinGgxAlpha});
}

TEST(PbrMaterial, TexturesFeedTheBsdf) {
  Hit hit = plane_hit();
  hit.color = Vec4(1, 0.5f, 1, 1);
  PbrParams p;
  p.base_color = Color(0.8f, 0.8f, 0.6f);
  p.base_color_texture = constant_texture(0.5f, 1, 1, 0.3f);
  p.metallic = 0.5f;
  p.roughness = 0.8f;
  p.metallic_roughness_texture = constant_texture(0.9f /* ignored */, 0.5f /* roughness */, 0.6f /* metallic */);
  const auto m = make_pbr_material(p);
  const Color base = m->albedo(hit);
  EXPECT_NEAR(base.x, 0.4f, 1e-6f);
  EXPECT_NEAR(base.y, 0.4f, 1e-6f);
  EXPECT_NEAR(base.z, 0.6f, 1e-6f);
  expect_same_bsdf(m->shade(hit).bsdf, make_pbr_bsdf(base, 0.5f * 0.6f, 0.8f * 0.5f));
}

TEST(PbrMaterial, TexCoordSelectsUvSet) {
  Hit hit = plane_hit();
  auto img = std::make_shared<Image>(2, 1, std::vector<std::string>{"R", "G", "B"});
  img->at(0, 0, 0) = img->at(0, 0, 1) = img->at(0, 0, 2) = 0.2f;
  img->at(1, 0, 0) = img->at(1, 0, 1) = img->at(1, 0, 2) = 0.7f;
  Texture t;
  t.image = img;
  t.nearest = true;
  t.tex_coord = 1;
  hit.uv[0] = Vec2(0.25f, 0.5f);
  hit.uv[1] = Vec2(0.75f, 0.5f);
  PbrParams p;
  p.base_color_texture = t;
  EXPECT_NEAR(make_pbr_material(p)->albedo(hit).x, 0.7f, 1e-6f);
}

TEST(NormalMap, FlatTexelKeepsTheNormal) {
  Hit hit = plane_hit();
  hit.ns = normalize(Vec3(0.1f, 0, 1));
  PbrParams p;
  p.normal_texture = normal_texel(Vec3(0, 0, 1));
  const Frame f = make_pbr_material(p)->shade(hit).frame;
  EXPECT_NEAR(dot(f.n, hit.ns), 1.0f, 1e-5f);
  expect_orthonormal(f);
}

TEST(NormalMap, TiltFollowsTangentAndHandedness) {
  const float s = std::sin(0.5f), c = std::cos(0.5f);
  PbrParams p;
  p.normal_texture = normal_texel(Vec3(0, s, c));  // tilted toward the bitangent
  Hit hit = plane_hit();
  hit.tangent = Vec4(0, 1, 0, 1);  // tangent +y: bitangent = n x t = -x
  Frame f = make_pbr_material(p)->shade(hit).frame;
  EXPECT_NEAR(f.n.x, -s, 1e-5f);  // float texel: exact up to rounding
  EXPECT_NEAR(f.n.z, c, 1e-5f);
  EXPECT_NEAR(f.s.y, 1.0f, 1e-5f);  // s keeps following the tangent
  expect_orthonormal(f);
  hit.tangent.w = -1;  // mirrored UVs flip the bitangent
  f = make_pbr_material(p)->shade(hit).frame;
  EXPECT_NEAR(f.n.x, s, 1e-5f);
  // Tilt along the tangent.
  p.normal_texture = normal_texel(Vec3(s, 0, c));
  f = make_pbr_material(p)->shade(hit).frame;
  EXPECT_NEAR(f.n.y, s, 1e-5f);
}

TEST(NormalMap, ScaleScalesXY) {
  const float s = std::sin(0.4f), c = std::cos(0.4f);
  PbrParams p;
  p.normal_texture = normal_texel(Vec3(s, 0, c));
  p.normal_scale = 0;
  const Hit hit = plane_hit();
  EXPECT_NEAR(make_pbr_material(p)->shade(hit).frame.n.z, 1.0f, 1e-5f);
  p.normal_scale = 2;
  const Vec3 n = make_pbr_material(p)->shade(hit).frame.n;
  EXPECT_NEAR(n.x / n.z, 2 * s / c, 1e-3f);
}

TEST(NormalMap, WithoutTangentsUsesTheFrameOfTheNormal) {
  PbrParams p;
  p.normal_texture = normal_texel(normalize(Vec3(0.3f, 0.2f, 1)));
  Hit hit = plane_hit();
  hit.ns = hit.ng = normalize(Vec3(0.2f, -0.4f, 1));
  hit.tangent = Vec4(0, 0, 0, 0);
  const Frame base = Frame::from_normal(hit.ns);
  const Vec3 expected = normalize(base.s * 0.3f + base.t * 0.2f + base.n * 1.0f);
  const Frame f = make_pbr_material(p)->shade(hit).frame;
  EXPECT_NEAR(dot(f.n, expected), 1.0f, 1e-4f);
  expect_orthonormal(f);
}

TEST(ShadingRule, NormalMapNeverPointsBehindTheSurface) {
  PbrParams p;
  p.normal_texture = normal_texel(normalize(Vec3(1, 0, -0.2f)));  // below the tangent plane
  const Hit hit = plane_hit();
  const Frame f = make_pbr_material(p)->shade(hit).frame;
  EXPECT_GE(dot(f.n, hit.ng), kMinShadingCosine - 1e-5f);
  EXPECT_GT(f.n.x, 0.99f);  // bent only as far as needed, in the plane of the tilt
  expect_orthonormal(f);
  // Exact antipode: still a valid normal.
  const Vec3 n = bend_toward(Vec3(0, 0, -1), Vec3(0, 0, 1), kMinShadingCosine);
  EXPECT_NEAR(n.z, kMinShadingCosine, 1e-6f);
  EXPECT_NEAR(length(n), 1.0f, 1e-6f);
}

// Rule 1: vertex normals that disagree with the winding (ng) are turned to the front face's side. Left behind
// it, rule 3 bent them through ng by an amount that depended on wo (a quad with such normals read 0.41-1.16 of
// its flat twin under nee_mis).
TEST(ShadingRule, VertexNormalAgainstTheWindingIsTurnedOver) {
  Hit hit = plane_hit();
  hit.ns = normalize(Vec3(0.05f, 0, -1));
  for (const auto& material : {make_diffuse_material(Color(0.8f)), make_pbr_material(PbrParams{})}) {
    const Frame f = material->shade(hit).frame;
    EXPECT_NEAR(dot(f.n, normalize(Vec3(-0.05f, 0, 1))), 1.0f, 1e-6f);
    expect_orthonormal(f);
  }
}

TEST(ShadingRule, AdaptKeepsValidFramesAndFixesInvalidOnes) {
  const Vec3 ng(0, 0, 1);
  // Valid configuration: unchanged.
  const Frame tilted = Frame::from_normal(normalize(Vec3(0.2f, 0, 1)));
  const Vec3 wo = normalize(Vec3(0.5f, 0.1f, 1));
  const Frame same = adapt_shading_frame(tilted, ng, wo);
  EXPECT_EQ(same.n, tilted.n);
  // Strongly tilted normal, grazing view from the side it leans away from: wo is below the shading hemisphere.
  const Frame leaning = Frame::from_normal(normalize(Vec3(1, 0, 0.5f)));
  const Vec3 grazing = normalize(Vec3(-1, 0, 0.1f));
  ASSERT_LT(dot(grazing, leaning.n), 0.0f);
  const Frame fixed = adapt_shading_frame(leaning, ng, grazing);
  EXPECT_GT(dot(grazing, fixed.n), 0.0f);
  EXPECT_GT(dot(reflect(grazing, fixed.n), ng), 0.0f);
  EXPECT_GT(fixed.n.x, 0.0f);  // bent toward ng, not past it
  expect_orthonormal(fixed);
  // wo above n but its mirror image below the surface: bent until the reflection clears the surface.
  const Frame mild = Frame::from_normal(normalize(Vec3(0.3f, 0, 1)));
  const Vec3 low = normalize(Vec3(-1, 0, 0.5f));
  ASSERT_GT(dot(low, mild.n), 0.0f);
  ASSERT_LT(dot(reflect(low, mild.n), ng), 0.0f);
  const Frame cleared = adapt_shading_frame(mild, ng, low);
  EXPECT_GE(dot(reflect(low, cleared.n), ng), std::min(0.9f * low.z, 0.01f) - 1e-5f);
  EXPECT_LT(dot(reflect(low, cleared.n), ng), 0.05f);  // the least bend that works
}

}  // namespace
}  // namespace lumis
