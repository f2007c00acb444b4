// make_vertex (integrators/path.cpp) applies the shading-normal rule's third step (materials/shading.h,
// adapt_shading_frame) once it knows wo: a shading normal whose mirror reflection of wo would go below the
// geometric surface is bent toward the geometric normal, so glossy surfaces with interpolated or normal-mapped
// normals do not turn black at grazing angles; valid shading normals and flat geometry are left as they are.
#include <gtest/gtest.h>

#include <algorithm>

#include "integrators/path.h"
#include "materials/shading.h"

namespace lumis {
namespace {

// A glossy material and a hit at the origin on the plane z = 0 (front face +z) with shading normal ns.
struct GlossyPlane {
  Scene scene;
  Hit hit;
  explicit GlossyPlane(Vec3 ns) {
    scene.materials.push_back(make_ggx_material(Color(0.9f), 0.1f));
    hit.t = 1;
    hit.p = {0, 0, 0};
    hit.ng = {0, 0, 1};
    hit.ns = normalize(ns);
    hit.front = true;
    hit.material = 0;
  }
};

// The reflection of wo about the vertex's shading normal clears the geometric surface (world space).
float reflection_height(const Vertex& v) {
  const Vec3 wo = v.frame.to_world(v.wo);
  return dot(reflect(wo, v.frame.n), v.ng);
}

TEST(MakeVertex, BendsAShadingNormalThatMirrorsWoBelowTheSurface) {
  // ns leans toward +x; a ray arriving from +x low over the surface (travelling toward -x) sees wo above the
  // shading hemisphere, but its mirror image about ns points below the plane.
  GlossyPlane s(Vec3(0.3f, 0, 1));
  const Vec3 wo = normalize(Vec3(-1, 0, 0.5f));
  ASSERT_GT(dot(wo, s.hit.ns), 0.0f);
  ASSERT_LT(dot(reflect(wo, s.hit.ns), s.hit.ng), 0.0f);
  const std::optional<Vertex> v = make_vertex(s.scene, s.hit, -wo);
  ASSERT_TRUE(v.has_value());
  EXPECT_GT(v->wo.z, 0.0f);
  EXPECT_GE(reflection_height(*v), std::min(0.9f * wo.z, 0.01f) - 1e-5f);
  EXPECT_GT(dot(v->frame.n, Vec3(1, 0, 0)), 0.0f);  // bent toward ng, not replaced by it
  EXPECT_LT(dot(v->frame.n, s.hit.ng), 1.0f);
}

TEST(MakeVertex, KeepsAValidShadingNormal) {
  GlossyPlane s(Vec3(0.3f, 0, 1));
  const Vec3 wo = normalize(Vec3(0.5f, 0.2f, 1));  // seen from the side ns leans toward: nothing to fix
  const std::optional<Vertex> v = make_vertex(s.scene, s.hit, -wo);
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->frame.n, s.hit.ns);
}

TEST(MakeVertex, BackFaceHitsAreAdaptedOnTheirOwnSide) {
  // The same configuration seen from below: the hit is a back face, frame and ng flip, and the rule applies there.
  GlossyPlane s(Vec3(0.3f, 0, 1));
  s.hit.front = false;
  const Vec3 wo = normalize(Vec3(1, 0, -0.5f));  // toward the viewer below the plane
  const std::optional<Vertex> v = make_vertex(s.scene, s.hit, -wo);
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->ng, Vec3(0, 0, -1));
  EXPECT_GT(v->wo.z, 0.0f);
  EXPECT_GE(reflection_height(*v), std::min(0.9f * dot(wo, v->ng), 0.01f) - 1e-5f);
}

// The shading-normal rule's first step (docs/estimators.md): no light reaches or leaves a vertex through the
// geometric surface, whatever the shading normal says. A diffuse plane z = 0 whose shading normal leans 30 degrees
// toward +x, seen from straight above (so make_vertex keeps the shading normal): directions just below the plane
// toward +x are above the shading hemisphere, where the BSDF is not zero.
struct LeaningDiffusePlane {
  Scene scene;
  Hit hit;
  LeaningDiffusePlane() {
    scene.materials.push_back(make_diffuse_material(Color(0.8f)));
    hit.t = 1;
    hit.p = {0, 0, 0};
    hit.ng = {0, 0, 1};
    hit.ns = {0.5f, 0, 0.8660254f};
    hit.front = true;
    hit.material = 0;
  }
};

LightDraw light_from(Vec3 wi) {
  LightDraw d;
  d.choice = {0, 1.0f};
  d.ok = true;
  d.sample = LightSample(Color(1), wi, 1.0f, 1.0f, wi, -wi, 0.0f);
  return d;
}

TEST(ShadingNormalRule, NoNextEventLightFromBelowTheGeometricSurface) {
  LeaningDiffusePlane s;
  const std::optional<Vertex> v = make_vertex(s.scene, s.hit, {0, 0, -1});
  ASSERT_TRUE(v.has_value());
  ASSERT_EQ(v->frame.n, s.hit.ns);
  const Vec3 below = normalize(Vec3(1, 0, -0.2f)), above = normalize(Vec3(1, 0, 0.2f));
  ASSERT_GT(dot(below, s.hit.ns), 0.1f);  // the BSDF alone would reflect it
  PathCounters counters;
  for (const bool weighted : {false, true}) {
    EXPECT_FALSE(sample_direct(*v, light_from(below), weighted, MisHeuristic::Balance, counters).has_value());
    const std::optional<ShadowQuery> q =
        sample_direct(*v, light_from(above), weighted, MisHeuristic::Balance, counters);
    ASSERT_TRUE(q.has_value());  // the control: the same light just above the plane counts
    EXPECT_GT(q->value.x, 0.0f);
  }
}

TEST(ShadingNormalRule, NoBsdfContinuationBelowTheGeometricSurface) {
  // The cosine lobe around the leaning normal has part of its mass below the plane: those samples end the path,
  // and every continuation leaves above it. A 64 x 64 grid of u, no randomness.
  LeaningDiffusePlane s;
  const std::optional<Vertex> v = make_vertex(s.scene, s.hit, {0, 0, -1});
  ASSERT_TRUE(v.has_value());
  int continued = 0, ended = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const Vec2 u{(i + 0.5f) / 64, (j + 0.5f) / 64};
      const std::optional<Scatter> sc = scatter_bsdf(*v, 0.5f, u, turn_azimuth(u.x));
      if (!sc) {
        ++ended;
        continue;
      }
      ++continued;
      EXPECT_GT(dot(sc->wi, s.hit.ng), 0.0f);
    }
  EXPECT_GT(ended, 0);
  EXPECT_GT(continued, ended);
}

}  // namespace
}  // namespace lumis
