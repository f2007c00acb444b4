// Solid angles of triangles and rectangles (closed forms against each other and known values), and the Arvo and
// Urena et al. warps: chi-square of their directions against 1/solid angle inside the polygon, inversion round
// trips, and the geometry-only failure rule the lights rely on.
#include <gtest/gtest.h>

#include <cmath>

#include "core/chi2.h"
#include "core/warp.h"
#include "light_test_shapes.h"

namespace lumis {
namespace {

// Chi-square family of this file: 6 tests (3 triangles, 3 rectangles), Sidak-corrected alpha 0.01 overall, so a
// correct sampler fails this executable with probability 1%; fixed seeds make a run reproducible.
constexpr int kChiTests = 6;

struct Tri {
  Vec3 p, a, b, c;
};

double inside_triangle_pdf(const Tri& t, Vec3 w) {
  if (!test::triangle_hit(t.p, w, t.a, t.b, t.c, 0)) return 0;
  return 1.0 / triangle_solid_angle(t.p, t.a, t.b, t.c);
}

TEST(SphericalPolygons, TriangleSolidAngleKnownValues) {
  // An octant: pi/2.
  EXPECT_NEAR(triangle_solid_angle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), kPi / 2, 1e-6);
  EXPECT_NEAR(triangle_solid_angle({0, 0, 0}, {5, 0, 0}, {0, 0, 2}, {0, 3, 0}), kPi / 2, 1e-6);
  // A cube face from the centre is 4 pi / 6, and two triangles make it.
  const Vec3 o{0, 0, 0}, c00{-1, -1, 1}, c10{1, -1, 1}, c11{1, 1, 1}, c01{-1, 1, 1};
  EXPECT_NEAR(triangle_solid_angle(o, c00, c10, c11) + triangle_solid_angle(o, c00, c11, c01), 4 * kPi / 6, 1e-6);
  EXPECT_NEAR(rectangle_solid_angle(o, c00, {2, 0, 0}, {0, 2, 0}), 4 * kPi / 6, 1e-6);
  // From the other side of the plane the (unsigned) solid angle is the same.
  EXPECT_NEAR(rectangle_solid_angle({0, 0, 2}, c00, {2, 0, 0}, {0, 2, 0}), 4 * kPi / 6, 1e-6);
  // Degenerate: receiver in the plane outside the polygon.
  EXPECT_NEAR(triangle_solid_angle({5, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 0, 1e-7);
}

TEST(SphericalPolygons, RectangleMatchesTwoTrianglesFromManyPoints) {
  Pcg32 rng(7, 1);
  const Vec3 origin{-0.3f, 0.2f, 1.5f}, ex{1.2f, 0, 0}, ey{0, 0.7f, 0};
  for (int i = 0; i < 200; ++i) {
    const Vec3 p{4 * rng.next_float() - 2, 4 * rng.next_float() - 2, 3 * rng.next_float() - 1};
    const float rect = rectangle_solid_angle(p, origin, ex, ey);
    const float tris = triangle_solid_angle(p, origin, origin + ex, origin + ex + ey) +
                       triangle_solid_angle(p, origin, origin + ex + ey, origin + ey);
    EXPECT_NEAR(rect, tris, 2e-5f * std::max(1.0f, tris)) << "p = " << p.x << "," << p.y << "," << p.z;
  }
  // A tiny, far rectangle: four-angle formula (double inside) against the small-angle limit area cos / d^2.
  const float far = rectangle_solid_angle({0, 0, 0}, {-0.005f, -0.005f, 100}, {0.01f, 0, 0}, {0, 0.01f, 0});
  EXPECT_NEAR(far / 1e-8f, 1.0f, 1e-3f);
}

TEST(SphericalPolygons, TriangleWarpChiSquare) {
  // The small, far triangle's vertices lie well inside histogram cells.
  const Tri cases[] = {
      {{0, 0, 0}, {1, -0.5f, 0.2f}, {1.2f, 0.8f, -0.1f}, {0.8f, 0.1f, 1.0f}},    // ~0.8 sr, near
      {{0, 0, 0}, {4, -0.3f, -0.2f}, {4.1f, 0.5f, 0.1f}, {3.9f, 0.1f, 0.7f}},    // small, far
      {{0, 0, 0.05f}, {-3, -3, 0}, {4, -2, 0}, {0, 4, 0}},                        // huge, receiver 5 cm above
  };
  for (const Tri& t : cases) {
    const float omega = triangle_solid_angle(t.p, t.a, t.b, t.c);
    DirectionalTest cfg;
    cfg.samples = 300'000;
    cfg.num_tests = kChiTests;
    cfg.seed = 11;
    cfg.integration_resolution = 2;  // adaptive refinement does the work at the edges
    const auto r = chi_square_directions(
        [&](Pcg32& rng) -> std::optional<Vec3> {
          const Vec2 u{rng.next_float(), rng.next_float()};
          const auto s = sample_spherical_triangle(t.p, t.a, t.b, t.c, u);
          if (!s) return std::nullopt;
          EXPECT_FLOAT_EQ(s->pdf, 1 / omega);
          return s->w;
        },
        [&](Vec3 w) { return inside_triangle_pdf(t, w); }, cfg);
    EXPECT_TRUE(r.passed) << "solid angle " << omega << ": " << r.message;
    std::printf("triangle, solid angle %.4f sr: %s\n", omega, r.message.c_str());
  }
}

TEST(SphericalPolygons, TriangleInverseRoundTrip) {
  const Tri t{{0.1f, -0.2f, 0}, {1, -0.5f, 0.2f}, {1.2f, 0.8f, -0.1f}, {0.8f, 0.1f, 1.0f}};
  Pcg32 rng(3, 3);
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec2 u{rng.next_float(), rng.next_float()};
    const auto s = sample_spherical_triangle(t.p, t.a, t.b, t.c, u);
    ASSERT_TRUE(s.has_value());
    const Vec2 back = invert_spherical_triangle(t.p, t.a, t.b, t.c, s->w);
    worst = std::max({worst, double(std::abs(back.x - u.x)), double(std::abs(back.y - u.y))});
  }
  EXPECT_LT(worst, 2e-3) << "worst |u - invert(sample(u))|";
}

TEST(SphericalPolygons, FailureDependsOnGeometryOnly) {
  // Tiny (1e-8 sr), in-plane and degenerate triangles fail for every u; a normal one succeeds for every u
  // including the corners of [0,1)^2. The quad and mesh lights reproduce sample()'s choice in pdf() this way.
  const Vec2 corners[] = {{0, 0}, {kOneMinusEpsilon, 0}, {0, kOneMinusEpsilon}, {kOneMinusEpsilon, kOneMinusEpsilon},
                          {0.5f, 0.5f}, {1e-7f, 0.3f}};
  for (Vec2 u : corners) {
    EXPECT_FALSE(sample_spherical_triangle({0, 0, 0}, {100, 0, 0}, {100, 0.01f, 0}, {100, 0, 0.01f}, u));
    EXPECT_FALSE(sample_spherical_triangle({0.2f, 0.2f, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, u));
    EXPECT_FALSE(sample_spherical_triangle({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, u));
    EXPECT_TRUE(sample_spherical_triangle({0, 0, 0}, {1, -0.5f, 0.2f}, {1.2f, 0.8f, -0.1f}, {0.8f, 0.1f, 1}, u));
    EXPECT_FALSE(sample_spherical_rectangle({0, 0, 0}, {100, 0, 0}, {0, 0.001f, 0}, {0, 0, 0.001f}, u));
    EXPECT_FALSE(sample_spherical_rectangle({0.5f, 0.5f, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, u));
    EXPECT_TRUE(sample_spherical_rectangle({0, 0, 0}, {1, -1, -1}, {0, 2, 0}, {0, 0, 2}, u));
  }
}

// The pdf-only functions the lights' pdf() use: present exactly when sampling succeeds, and the very density the
// sample reports, over receivers all around (including ones that fail: in the plane, too far, degenerate).
TEST(SphericalPolygons, PdfWithoutSamplingEqualsTheSamplesPdf) {
  Pcg32 rng(17, 5);
  const Vec3 a{1, -0.5f, 0.2f}, b{1.2f, 0.8f, -0.1f}, c{0.8f, 0.1f, 1}, o{1, -1, -1}, ex{0, 2, 0}, ey{0, 0, 2};
  int present_tri = 0, absent_tri = 0, present_rect = 0, absent_rect = 0;
  for (int i = 0; i < 4000; ++i) {
    // Receivers from 1e-4 to 1e4 units away, some exactly in the polygons' planes.
    const float r = std::pow(10.0f, -4 + 8 * rng.next_float());
    Vec3 p = sample_uniform_sphere({rng.next_float(), rng.next_float()}) * r + Vec3{1, 0, 0.3f};
    if (i % 10 == 0) p.x = 1;  // the rectangle's plane
    const Vec2 u{rng.next_float(), rng.next_float()};
    const auto st = sample_spherical_triangle(p, a, b, c, u);
    const auto pt = spherical_triangle_pdf(p, a, b, c);
    ASSERT_EQ(st.has_value(), pt.has_value()) << "receiver " << p.x << " " << p.y << " " << p.z;
    if (st) {
      ASSERT_EQ(st->pdf, *pt);
    }
    (pt ? present_tri : absent_tri)++;
    const auto sr = sample_spherical_rectangle(p, o, ex, ey, u);
    const auto pr = spherical_rectangle_pdf(p, o, ex, ey);
    ASSERT_EQ(sr.has_value(), pr.has_value()) << "receiver " << p.x << " " << p.y << " " << p.z;
    if (sr) {
      ASSERT_EQ(sr->pdf, *pr);
    }
    (pr ? present_rect : absent_rect)++;
  }
  // Both outcomes occur, so the test compares something either way.
  EXPECT_GT(present_tri, 100);
  EXPECT_GT(absent_tri, 100);
  EXPECT_GT(present_rect, 100);
  EXPECT_GT(absent_rect, 100);
  EXPECT_FALSE(spherical_triangle_pdf({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}));
}

TEST(SphericalPolygons, RectangleWarpChiSquare) {
  struct Rect {
    Vec3 p, o, ex, ey;
  };
  const Rect cases[] = {
      {{0, 0, 0}, {1, -0.6f, -0.3f}, {0, 1.1f, 0}, {0.3f, 0, 0.9f}},              // tilted, near
      {{0, 0, 0}, {5, -0.4f, -0.2f}, {0, 0.8f, 0}, {0, 0, 0.5f}},                 // far
      {{0, 0, 0}, {0.05f, -3, -2}, {0, 6, 0}, {0, 0, 5}},                         // huge, receiver 5 cm off
  };
  for (const Rect& r : cases) {
    const TriangleMesh quad = test::quad_mesh(r.o, r.ex, r.ey);
    const float omega = rectangle_solid_angle(r.p, r.o, r.ex, r.ey);
    DirectionalTest cfg;
    cfg.samples = 300'000;
    cfg.num_tests = kChiTests;
    cfg.seed = 12;
    cfg.integration_resolution = 2;  // adaptive refinement does the work at the edges
    const auto res = chi_square_directions(
        [&](Pcg32& rng) -> std::optional<Vec3> {
          const auto s = sample_spherical_rectangle(r.p, r.o, r.ex, r.ey, {rng.next_float(), rng.next_float()});
          if (!s) return std::nullopt;
          return s->w;
        },
        [&](Vec3 w) { return test::mesh_hits(r.p, w, quad).empty() ? 0.0 : 1.0 / omega; }, cfg);
    EXPECT_TRUE(res.passed) << "solid angle " << omega << ": " << res.message;
    std::printf("rectangle, solid angle %.4f sr: %s\n", omega, res.message.c_str());
  }
}

}  // namespace
}  // namespace lumis
