// Quad light, both sampling methods: chi-square of directions against pdf() (built from a hit on the scene's
// two-triangle mesh), the Monte Carlo solid angle against the four-angle formula, sample().pdf == pdf(), the
// area fallback (tiny solid angle, non-rectangular parallelogram), one-sidedness and the horizon, scale invariance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/chi2.h"
#include "core/warp.h"
#include "lights/light.h"
#include "light_test_shapes.h"

namespace lumis {
namespace {

// Chi-square family: 2 methods x (2 directional receivers + 1 grazing in quad coordinates) + 1 parallelogram = 7
// tests, Sidak-corrected alpha 0.01 for the family (1% false failures per run); seeds fixed.
constexpr int kChiTests = 7;
const Vec3 kOrigin{-0.5f, 1.0f, -0.4f}, kEdgeU{1.0f, 0, 0}, kEdgeV{0, 0, 0.8f};  // faces -y (cross(u, v) = -y)
const Color kRadiance{5, 5, 4};

const LightSampleContext kReceivers[] = {
    {{0.1f, 0.3f, 0.0f}, {0, 1, 0}},                  // near, below the quad
    {{2.5f, -3.0f, 1.0f}, {0, 1, 0}},                 // far and oblique
    {{-2.0f, 0.97f, 0.0f}, {1, 0, 0}},                // grazing: 3 cm below the plane, 1.5 m to the side
};

double direction_pdf(const Light& light, const TriangleMesh& mesh, const LightSampleContext& ctx, Vec3 w) {
  const auto hits = test::mesh_hits(ctx.p, w, mesh);
  return hits.empty() ? 0.0 : light.pdf(ctx, w, hits.front());
}

void chi_square_quad(const Light& light, const TriangleMesh& mesh, const LightSampleContext& ctx, uint64_t seed) {
  DirectionalTest cfg;
  cfg.samples = 200'000;
  cfg.num_tests = kChiTests;
  cfg.seed = seed;
  cfg.integration_resolution = 2;  // adaptive refinement does the work at the edges
  const auto r = chi_square_directions(
      [&](Pcg32& rng) -> std::optional<Vec3> {
        const auto s = light.sample(ctx, {rng.next_float(), rng.next_float()});
        if (!s) return std::nullopt;
        return s->wi;
      },
      [&](Vec3 w) { return direction_pdf(light, mesh, ctx, w); }, cfg);
  EXPECT_TRUE(r.passed) << r.message;
  std::printf("quad from (%g, %g, %g): %s\n", ctx.p.x, ctx.p.y, ctx.p.z, r.message.c_str());
}

TEST(QuadLight, DirectionsFollowPdfBothMethods) {
  const TriangleMesh mesh = test::quad_mesh(kOrigin, kEdgeU, kEdgeV);
  for (QuadSampling m : {QuadSampling::Area, QuadSampling::SphericalRectangle}) {
    const auto light = make_quad_light(kOrigin, kEdgeU, kEdgeV, kRadiance, m);
    for (int i = 0; i < 2; ++i) chi_square_quad(*light, mesh, kReceivers[i], m == QuadSampling::Area ? 31 : 32);
  }
}

TEST(QuadLight, GrazingReceiverInQuadCoordinates) {
  // Seen from 3 cm below its plane the quad is a sliver thinner than one histogram cell, where the directional
  // test's expected-count quadrature is off by percents; count the samples per cell of an 8 x 8 grid on the quad
  // instead, against closed forms: the sub-rectangle's share of the solid angle (spherical) or of the area (area).
  const LightSampleContext ctx = kReceivers[2];
  constexpr int kGrid = 8;
  for (QuadSampling m : {QuadSampling::Area, QuadSampling::SphericalRectangle}) {
    const auto light = make_quad_light(kOrigin, kEdgeU, kEdgeV, kRadiance, m);
    const double total = rectangle_solid_angle(ctx.p, kOrigin, kEdgeU, kEdgeV);
    std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, 0.0);
    const int n = 200'000;
    Pcg32 rng(m == QuadSampling::Area ? 34 : 35, 1);
    for (int i = 0; i < n; ++i) {
      const auto s = light->sample(ctx, {rng.next_float(), rng.next_float()});
      ASSERT_TRUE(s.has_value());
      const Vec3 q = s->p_light - kOrigin;
      const int a = std::clamp(static_cast<int>(dot(q, kEdgeU) / dot(kEdgeU, kEdgeU) * kGrid), 0, kGrid - 1);
      const int b = std::clamp(static_cast<int>(dot(q, kEdgeV) / dot(kEdgeV, kEdgeV) * kGrid), 0, kGrid - 1);
      observed[a * kGrid + b] += 1;
    }
    for (int a = 0; a < kGrid; ++a)
      for (int b = 0; b < kGrid; ++b) {
        const Vec3 o = kOrigin + kEdgeU * (float(a) / kGrid) + kEdgeV * (float(b) / kGrid);
        const double share =
            m == QuadSampling::Area
                ? 1.0 / (kGrid * kGrid)
                : rectangle_solid_angle(ctx.p, o, kEdgeU / float(kGrid), kEdgeV / float(kGrid)) / total;
        expected[a * kGrid + b] = share * n;
      }
    const auto r = chi_square_test(observed, expected, 0.01, kChiTests);
    EXPECT_TRUE(r.passed) << r.message;
    std::printf("%s, grazing, quad coordinates: %s\n", m == QuadSampling::Area ? "area" : "spherical",
                r.message.c_str());
  }
}

TEST(QuadLight, ParallelogramFallsBackToArea) {
  const Vec3 ev{0.5f, 0, 0.8f};  // not orthogonal to kEdgeU
  const TriangleMesh mesh = test::quad_mesh(kOrigin, kEdgeU, ev);
  const auto light = make_quad_light(kOrigin, kEdgeU, ev, kRadiance, QuadSampling::SphericalRectangle);
  // (A receiver whose view puts no corner of the quad within a few percent of a histogram cell edge: the
  // expected-count quadrature cannot see a sliver that thin, and a sample there fails the test outright.)
  const LightSampleContext ctx{{0.2f, 0.35f, 0.1f}, {0, 1, 0}};
  chi_square_quad(*light, mesh, ctx, 33);
  // Area sampling: the pdf varies over the quad (a spherical-rectangle pdf would be constant).
  float lo = INFINITY, hi = 0;
  for (Vec2 u : {Vec2{0.01f, 0.01f}, Vec2{0.99f, 0.01f}, Vec2{0.01f, 0.99f}, Vec2{0.99f, 0.99f}}) {
    const auto s = light->sample(ctx, u);
    ASSERT_TRUE(s.has_value());
    lo = std::min(lo, s->pdf);
    hi = std::max(hi, s->pdf);
  }
  EXPECT_GT(hi / lo, 1.2f);
}

TEST(QuadLight, SolidAngleMatchesFourAngleFormula) {
  // Mean of 1/pdf over 100k samples: exact for the spherical rectangle, an estimate for area sampling compared
  // within 5 standard errors (false failure ~ 6e-7 per comparison).
  for (QuadSampling m : {QuadSampling::Area, QuadSampling::SphericalRectangle}) {
    const auto light = make_quad_light(kOrigin, kEdgeU, kEdgeV, kRadiance, m);
    for (const auto& ctx : kReceivers) {
      const double exact = rectangle_solid_angle(ctx.p, kOrigin, kEdgeU, kEdgeV);
      const auto [mean, se] = test::mc_solid_angle(*light, ctx, Pcg32(41, 7));
      EXPECT_NEAR(mean, exact, 5 * se + 1e-5 * exact);
      std::printf("%s from (%g, %g, %g): MC solid angle %.6f +- %.6f, four-angle %.6f\n",
                  m == QuadSampling::Area ? "area" : "spherical", ctx.p.x, ctx.p.y, ctx.p.z, mean, se, exact);
    }
  }
}

// Quads far smaller than their distance, up to 1e13 times (edges of 1e-13 at ~2.5 units), from 121 receivers on a
// grid below: both methods' mean 1/pdf is the solid angle, area cos / d^2 for the squares (exact to 1e-9 at these
// sizes), and so is the selection importance over luminance; the methods agree for a 0.5 x 1e-12 sliver. The
// four-angle formula is rounding noise there: it made the 1e-13 square ~1e-6 sr from one receiver in twenty, 1e20
// times too bright; and the importance, from corners summed in float, was 0 (never chosen). Area sampling of such a
// quad has no variance to speak of: 1e-4 relative.
TEST(QuadLight, TinyQuadsKeepTheirSolidAngle) {
  const Vec3 o{0, 2, -1.5f};
  struct Size {
    float u, v;
  };
  for (Size e : {Size{1e-4f, 1e-4f}, Size{1e-7f, 1e-7f}, Size{1e-10f, 1e-10f}, Size{1e-13f, 1e-13f},
                 Size{0.5f, 1e-12f}})
    for (int i = 0; i < 121; ++i) {
      const LightSampleContext ctx{{0.4f * float(i % 11) - 2, 0, 0.4f * float(i / 11) - 2}, {0, 1, 0}};
      double mean[2], importance = 0;
      int k = 0;
      for (QuadSampling m : {QuadSampling::Area, QuadSampling::SphericalRectangle}) {
        const auto light = make_quad_light(o, {e.u, 0, 0}, {0, 0, e.v}, kRadiance, m);
        mean[k++] = test::mc_solid_angle(*light, ctx, Pcg32(43, 3), 100).mean;
        importance = light->importance(ctx) / luminance(kRadiance);
      }
      const Vec3 to = o - ctx.p;
      const double d2 = length_squared(to), expected = double(e.u) * e.v * (to.y / std::sqrt(d2)) / d2;
      ASSERT_NEAR(mean[1] / mean[0], 1.0, 1e-4) << "edges " << e.u << " x " << e.v << ", receiver " << i;
      if (e.u == e.v) {
        ASSERT_NEAR(mean[1] / expected, 1.0, 1e-4) << "edges " << e.u << ", receiver " << i;
        ASSERT_NEAR(importance / expected, 1.0, 1e-4) << "importance, edges " << e.u << ", receiver " << i;
      }
    }
}

TEST(QuadLight, SamplePdfEqualsPdfIncludingFallback) {
  // The tiny quad is ~1e-9 sr from the receiver, so the spherical method falls back to area sampling there.
  struct Case {
    Vec3 o, u, v;
    LightSampleContext ctx;
  };
  const Case cases[] = {
      {kOrigin, kEdgeU, kEdgeV, kReceivers[0]},
      {kOrigin, kEdgeU, kEdgeV, kReceivers[2]},
      {{100, 50, 0}, {0, 0, 0.001f}, {0, 0.001f, 0}, {{0, 0, 0}, {1, 0, 0}}},
  };
  for (QuadSampling m : {QuadSampling::Area, QuadSampling::SphericalRectangle}) {
    for (const Case& c : cases) {
      const auto light = make_quad_light(c.o, c.u, c.v, kRadiance, m);
      const TriangleMesh mesh = test::quad_mesh(c.o, c.u, c.v);
      Pcg32 rng(5, 9);
      for (int i = 0; i < 300; ++i) {
        const auto s = light->sample(c.ctx, {rng.next_float(), rng.next_float()});
        ASSERT_TRUE(s.has_value());
        Hit on;
        on.p = s->p_light;
        on.ng = s->n_light;
        on.prim_id = 7;  // the quad must not look at prim_id
        EXPECT_FLOAT_EQ(light->pdf(c.ctx, s->wi, on), s->pdf);
        EXPECT_EQ(light->le(on, -s->wi), kRadiance);
        EXPECT_FALSE(test::mesh_hits(c.ctx.p, s->wi, mesh).empty()) << "sampled direction misses the quad";
      }
    }
  }
}

TEST(QuadLight, OneSidedAndHorizon) {
  const auto light = make_quad_light(kOrigin, kEdgeU, kEdgeV, kRadiance);
  const LightSampleContext above{{0, 2, 0}, {0, -1, 0}};
  EXPECT_FALSE(light->sample(above, {0.5f, 0.5f}).has_value());
  Hit on;
  on.p = kOrigin + kEdgeU * 0.5f + kEdgeV * 0.5f;
  EXPECT_EQ(light->pdf(above, {0, -1, 0}, on), 0.0f);
  EXPECT_EQ(light->importance(above), 0.0f);
  EXPECT_TRUE(is_black(light->le(on, {0, 1, 0})));
  EXPECT_EQ(light->le(on, {0, -1, 0}), kRadiance);
  // Below the quad but with the normal pointing away: every corner below the horizon.
  EXPECT_EQ(light->importance({{0, 0, 0}, {0, -1, 0}}), 0.0f);
  // Tilted so that one corner rises above the horizon: positive.
  EXPECT_GT(light->importance({{0, 0.99f, 0}, normalize(Vec3{0.05f, -1, 0})}), 0.0f);
  const LightSampleContext below{{0, 0, 0}, {0, 1, 0}};
  EXPECT_NEAR(light->importance(below) / (rectangle_solid_angle(below.p, kOrigin, kEdgeU, kEdgeV) *
                                          luminance(kRadiance)),
              1.0f, 1e-4f);
  EXPECT_NEAR(light->power(), kPi * 0.8f * luminance(kRadiance), 1e-4f);
}

// Scaled by k (light and receiver), power scales by k^2 and the solid-angle density and direction of a sample do
// not change. At 1e12 the edges' cross product has a square beyond float's range (area and normal computed
// naively come out infinite and zero), at 1e-6 the receiver is a micrometre from the quad.
TEST(QuadLight, ScaleInvariant) {
  const auto unit = make_quad_light(kOrigin, kEdgeU, kEdgeV, kRadiance);
  const LightSampleContext ctx = kReceivers[0];
  const auto ref = unit->sample(ctx, {0.3f, 0.6f});
  ASSERT_TRUE(ref.has_value());
  for (float k : {1e-6f, 1e6f, 1e12f}) {
    const auto light = make_quad_light(kOrigin * k, kEdgeU * k, kEdgeV * k, kRadiance);
    EXPECT_NEAR(light->power() / (unit->power() * k * k), 1.0f, 1e-5f) << k;
    const auto s = light->sample({ctx.p * k, ctx.n}, {0.3f, 0.6f});
    ASSERT_TRUE(s.has_value()) << k;
    EXPECT_NEAR(s->pdf / ref->pdf, 1.0f, 1e-4f) << k;
    EXPECT_LT(length(s->wi - ref->wi), 1e-5f) << k;
    EXPECT_NEAR(s->dist / (ref->dist * k), 1.0f, 1e-4f) << k;
  }
}

}  // namespace
}  // namespace lumis
