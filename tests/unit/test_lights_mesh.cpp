// Mesh light, both triangle sampling methods, one- and two-sided: chi-square of directions against the sum of pdf()
// over the ray's crossings of the mesh, the Monte Carlo solid angle against Van Oosterom-Strackee, sample().pdf ==
// pdf() (including triangles where spherical sampling falls back to area), the emissive-texture weights, and scale
// invariance.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <memory>
#include <vector>

#include "core/chi2.h"
#include "core/warp.h"
#include "lights/light.h"
#include "light_test_shapes.h"

namespace lumis {
namespace {

// Chi-square family: 6 (method, sidedness, receiver) cases, Sidak-corrected alpha 0.01 for the family (1% false
// failures per run); seeds fixed. The expected counts dominate the run time (adaptive quadrature along every
// triangle edge), so each method gets three of the four cases.
constexpr int kChiTests = 6;

// A tetrahedron with outward-facing (counter-clockwise seen from outside) faces, and uv0 for a texture.
TriangleMesh tetrahedron() {
  TriangleMesh m;
  const Vec3 c{0.2f, -0.1f, 0.3f};
  m.positions = {c + Vec3{0.6f, 0.5f, 0.4f}, c + Vec3{0.5f, -0.6f, -0.5f}, c + Vec3{-0.6f, 0.4f, -0.5f},
                 c + Vec3{-0.4f, -0.5f, 0.6f}};
  m.uv0 = {{0.1f, 0.1f}, {0.9f, 0.1f}, {0.1f, 0.9f}, {0.9f, 0.9f}};
  const uint32_t faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (int f = 0; f < 4; ++f) {
    uint32_t i0 = faces[f][0], i1 = faces[f][1], i2 = faces[f][2];
    const Vec3 n = cross(m.positions[i1] - m.positions[i0], m.positions[i2] - m.positions[i0]);
    if (dot(n, m.positions[i0] - c) < 0) std::swap(i1, i2);
    m.indices.insert(m.indices.end(), {i0, i1, i2});
  }
  return m;
}

// A 2x2 emissive texture (nearest), so that the four faces get different power-proportional probabilities.
Texture checker() {
  auto img = std::make_shared<Image>(2, 2, std::vector<std::string>{"R", "G", "B"});
  const float v[4] = {1.0f, 0.2f, 0.5f, 3.0f};
  for (int i = 0; i < 4; ++i)
    for (int ch = 0; ch < 3; ++ch) img->at(i % 2, i / 2, ch) = v[i];
  Texture t;
  t.image = img;
  t.nearest = true;
  return t;
}

double direction_pdf(const Light& light, const TriangleMesh& mesh, const LightSampleContext& ctx, Vec3 w) {
  double sum = 0;
  for (const Hit& h : test::mesh_hits(ctx.p, w, mesh)) sum += light.pdf(ctx, w, h);
  return sum;
}

struct Case {
  bool two_sided;
  LightSampleContext ctx;
  const char* what;
};
const Case kCases[] = {
    {false, {{1.9f, 0.35f, 0.25f}, {-1, 0, 0}}, "one-sided, near"},
    {false, {{-3.5f, 1.1f, -0.4f}, {0, 0, 0}}, "one-sided, far"},
    {true, {{1.7f, -0.55f, 0.1f}, {-1, 0, 0}}, "two-sided, near"},
    {true, {{0.2f, -0.05f, 0.25f}, {0, 0, 0}}, "two-sided, inside"},
};

TEST(MeshLight, DirectionsFollowPdf) {
  const TriangleMesh mesh = tetrahedron();
  for (TriangleSampling m : {TriangleSampling::Area, TriangleSampling::SphericalTriangle}) {
    for (const Case& c : kCases) {
      const bool inside = &c == &kCases[3], two_sided_near = &c == &kCases[2];
      if ((m == TriangleSampling::Area && two_sided_near) || (m == TriangleSampling::SphericalTriangle && inside))
        continue;
      const auto light = make_mesh_light(mesh, {1, 0.9f, 0.8f}, checker(), c.two_sided, m);
      DirectionalTest cfg;
      if (inside) {  // the whole sphere is lit: coarser cells keep the quadrature cheap
        cfg.cos_theta_bins = 20;
        cfg.phi_bins = 40;
      }
      cfg.samples = 150'000;
      cfg.num_tests = kChiTests;
      cfg.seed = m == TriangleSampling::Area ? 51 : 52;
      cfg.integration_resolution = 2;  // adaptive refinement does the work at the edges
      const auto r = chi_square_directions(
          [&](Pcg32& rng) -> std::optional<Vec3> {
            const auto s = light->sample(c.ctx, {rng.next_float(), rng.next_float()});
            if (!s) return std::nullopt;
            return s->wi;
          },
          [&](Vec3 w) { return direction_pdf(*light, mesh, c.ctx, w); }, cfg);
      EXPECT_TRUE(r.passed) << c.what << ": " << r.message;
      std::printf("%s, %s: %s\n", m == TriangleSampling::Area ? "area" : "spherical", c.what, r.message.c_str());
    }
  }
}

TEST(MeshLight, SolidAngleMatchesVanOosterom) {
  // E[1/pdf] = sum over the triangles that can emit toward the receiver of their solid angles; 100k samples,
  // compared within 5 standard errors (false failure ~ 6e-7 per comparison).
  const TriangleMesh mesh = tetrahedron();
  for (TriangleSampling m : {TriangleSampling::Area, TriangleSampling::SphericalTriangle}) {
    for (const Case& c : kCases) {
      const auto light = make_mesh_light(mesh, {1, 1, 1}, checker(), c.two_sided, m);
      double exact = 0;
      for (size_t t = 0; t < 4; ++t) {
        const Vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                   cc = mesh.positions[mesh.indices[3 * t + 2]];
        if (c.two_sided || dot(cross(b - a, cc - a), c.ctx.p - a) > 0) exact += triangle_solid_angle(c.ctx.p, a, b, cc);
      }
      const auto [mean, se] = test::mc_solid_angle(*light, c.ctx, Pcg32(61, 3));
      EXPECT_NEAR(mean, exact, 5 * se + 1e-5 * exact) << c.what;
      std::printf("%s, %s: MC solid angle %.5f +- %.5f, Van Oosterom-Strackee %.5f\n",
                  m == TriangleSampling::Area ? "area" : "spherical", c.what, mean, se, exact);
    }
  }
}

TEST(MeshLight, SamplePdfEqualsPdfWithPerTriangleFallback) {
  // A big triangle next to the receiver and a far one (5e-7 sr, below the 1e-6 sr limit): with the spherical
  // method the first is sampled by solid angle and the second falls back to area; pdf() must reproduce each choice.
  TriangleMesh mesh;
  mesh.positions = {{-1, -1, 1}, {1, -1, 1}, {0, 1, 1}, {0, 0, 1000}, {1, 0, 1000}, {0, 1, 1000}};
  mesh.indices = {0, 2, 1, 3, 5, 4};  // both face -z, toward the receiver
  const LightSampleContext ctx{{0.1f, 0.1f, 0}, {0, 0, 1}};
  for (TriangleSampling m : {TriangleSampling::Area, TriangleSampling::SphericalTriangle}) {
    const auto light = make_mesh_light(mesh, {2, 2, 2}, std::nullopt, false, m);
    Pcg32 rng(71, 1);
    int per_triangle[2] = {0, 0};
    for (int i = 0; i < 2000; ++i) {
      const auto s = light->sample(ctx, {rng.next_float(), rng.next_float()});
      ASSERT_TRUE(s.has_value());
      const auto hits = test::mesh_hits(ctx.p, s->wi, mesh);
      ASSERT_FALSE(hits.empty());
      const Hit* on = &hits.front();
      for (const Hit& h : hits)
        if (length(h.p - s->p_light) < length(on->p - s->p_light)) on = &h;
      ++per_triangle[on->prim_id];
      EXPECT_LT(length(on->p - s->p_light), 1e-3f * s->dist);
      EXPECT_FLOAT_EQ(light->pdf(ctx, s->wi, *on), s->pdf) << "triangle " << on->prim_id;
      EXPECT_EQ(light->le(*on, -s->wi), s->le);
    }
    EXPECT_GT(per_triangle[1], 0) << "the tiny triangle has a small but positive probability";
  }
}

// A cut-out (alphaMode MASK) emits nothing: rays pass through it, so light samples must not land there. Two
// triangles side by side, the second cut out by its vertex alpha: every sample lands on the first, and E[1/pdf] is
// the first one's solid angle alone; then alpha varying over one triangle. Means within 5 standard errors (false
// failure ~ 6e-7 per comparison).
TEST(MeshLight, CutOutEmitsNothing) {
  TriangleMesh mesh;
  mesh.positions = {{-1, -1, 1}, {0, -1, 1}, {0, 1, 1}, {0, -1, 1}, {1, -1, 1}, {0, 1, 1}};
  mesh.indices = {0, 2, 1, 3, 5, 4};  // both face -z, toward the receiver
  mesh.colors = {{1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 0}, {1, 1, 1, 0}, {1, 1, 1, 0}};
  mesh.alpha = AlphaMask{};
  const LightSampleContext ctx{{0.1f, 0.1f, 0}, {0, 0, 1}};
  const double exact = triangle_solid_angle(ctx.p, mesh.positions[0], mesh.positions[2], mesh.positions[1]);
  for (TriangleSampling m : {TriangleSampling::Area, TriangleSampling::SphericalTriangle}) {
    const auto light = make_mesh_light(mesh, {1, 1, 1}, std::nullopt, false, m);
    Pcg32 rng(81, 5);
    double sum = 0, sum2 = 0;
    const int n = 100'000;
    int empty = 0, in_cut_out = 0;
    for (int i = 0; i < n; ++i) {
      const auto s = light->sample(ctx, {rng.next_float(), rng.next_float()});
      if (!s) {
        ++empty;
        continue;
      }
      in_cut_out += s->p_light.x > 1e-5f;
      sum += 1.0 / s->pdf;
      sum2 += 1.0 / (double(s->pdf) * s->pdf);
    }
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    EXPECT_EQ(in_cut_out, 0);
    EXPECT_NEAR(mean, exact, 5 * se + 1e-5 * exact);
    EXPECT_NEAR(empty, n / 2, 0.02 * n) << "the two triangles have equal areas: half the samples are empty";
  }
  // Alpha varying over one triangle, 1 at its first corner and 0 at the others: what is left (alpha >= 0.5) is the
  // quarter at that corner, the triangle (v0, (v0 + v1) / 2, (v0 + v2) / 2).
  TriangleMesh tri;
  tri.positions = {{-1, -1, 1}, {0, 1, 1}, {1, -1, 1}};  // facing -z
  tri.indices = {0, 1, 2};
  tri.colors = {{1, 1, 1, 1}, {1, 1, 1, 0}, {1, 1, 1, 0}};
  tri.alpha = AlphaMask{};
  const Vec3 v0 = tri.positions[0], m1 = (v0 + tri.positions[1]) * 0.5f, m2 = (v0 + tri.positions[2]) * 0.5f;
  const double corner = triangle_solid_angle(ctx.p, v0, m1, m2);
  for (TriangleSampling m : {TriangleSampling::Area, TriangleSampling::SphericalTriangle}) {
    const auto light = make_mesh_light(tri, {1, 1, 1}, std::nullopt, false, m);
    const test::SolidAngleEstimate e = test::mc_solid_angle(*light, ctx, Pcg32(82, 5));
    EXPECT_NEAR(e.mean, corner, 5 * e.se + 1e-5 * corner);
  }
}

TEST(MeshLight, SidednessAndTextureWeights) {
  const TriangleMesh mesh = tetrahedron();
  const auto one = make_mesh_light(mesh, {1, 1, 1}, std::nullopt, false);
  const auto two = make_mesh_light(mesh, {1, 1, 1}, std::nullopt, true);
  Hit on;
  on.prim_id = 0;
  const Vec3 a = mesh.positions[mesh.indices[0]], b = mesh.positions[mesh.indices[1]],
             c = mesh.positions[mesh.indices[2]];
  const Vec3 n = normalize(cross(b - a, c - a));
  on.p = (a + b + c) / 3.0f;
  EXPECT_EQ(one->le(on, n), Color(1));
  EXPECT_TRUE(is_black(one->le(on, -n)));
  EXPECT_EQ(two->le(on, -n), Color(1));
  EXPECT_NEAR(two->power() / one->power(), 2.0f, 1e-5f);
  // Inside the closed one-sided mesh nothing is emitted toward the receiver.
  const LightSampleContext inside = kCases[3].ctx;
  EXPECT_FALSE(one->sample(inside, {0.3f, 0.6f}).has_value());
  EXPECT_EQ(one->pdf(inside, normalize(on.p - inside.p), on), 0.0f);
  // Importance: 0 only when the bounding sphere is below the horizon.
  EXPECT_EQ(one->importance({{0, 0, 5}, {0, 0, 1}}), 0.0f);
  EXPECT_GT(one->importance({{0, 0, 5}, {0, 0, -1}}), 0.0f);
  EXPECT_GT(one->importance({{0, 0, 1.1f}, {0, 0, 1}}), 0.0f) << "bounding sphere partly above the horizon";

  // A texture black at the triangle's centroid but bright at its corners still gets a positive probability.
  TriangleMesh tri;
  tri.positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  tri.indices = {0, 2, 1};
  tri.uv0 = {{0.1f, 0.1f}, {0.9f, 0.1f}, {0.1f, 0.9f}};
  auto img = std::make_shared<Image>(3, 3, std::vector<std::string>{"R", "G", "B"});
  for (int ch = 0; ch < 3; ++ch) {
    img->at(0, 0, ch) = 4;
    img->at(2, 0, ch) = 4;
    img->at(0, 2, ch) = 4;
  }
  Texture tex;
  tex.image = img;
  tex.nearest = true;
  const auto dark_centre = make_mesh_light(tri, {1, 1, 1}, tex, false);
  EXPECT_GT(dark_centre->power(), 0.0f);
  const auto s = dark_centre->sample({{0.2f, 0.2f, 0}, {0, 0, 1}}, {0.5f, 0.5f});
  ASSERT_TRUE(s.has_value());
  EXPECT_GT(s->pdf, 0.0f);
}

// Scaled by k (mesh and receiver), power scales by k^2 and a sample's solid-angle density and direction do not
// change, for both methods. At 1e12 the triangles' cross products have squares beyond float's range.
TEST(MeshLight, ScaleInvariant) {
  const TriangleMesh unit_mesh = tetrahedron();
  const LightSampleContext ctx{{0.1f, -2.0f, 0.3f}, {0, 1, 0}};
  for (TriangleSampling m : {TriangleSampling::Area, TriangleSampling::SphericalTriangle}) {
    const auto unit = make_mesh_light(unit_mesh, {1, 1, 1}, std::nullopt, false, m);
    // A u whose triangle faces the receiver (the others' samples are empty).
    Vec2 u{0.05f, 0.6f};
    while (u.x < 1 && !unit->sample(ctx, u)) u.x += 0.1f;
    const auto ref = unit->sample(ctx, u);
    ASSERT_TRUE(ref.has_value());
    for (float k : {1e-6f, 1e6f, 1e12f}) {
      TriangleMesh mesh = unit_mesh;
      for (Vec3& p : mesh.positions) p = p * k;
      const auto light = make_mesh_light(mesh, {1, 1, 1}, std::nullopt, false, m);
      EXPECT_NEAR(light->power() / (unit->power() * k * k), 1.0f, 1e-5f) << k;
      const auto s = light->sample({ctx.p * k, ctx.n}, u);
      ASSERT_TRUE(s.has_value()) << k;
      EXPECT_NEAR(s->pdf / ref->pdf, 1.0f, 1e-4f) << k;
      EXPECT_LT(length(s->wi - ref->wi), 1e-5f) << k;
    }
  }
}

}  // namespace
}  // namespace lumis

namespace lumis {
namespace {

bool same(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
bool same(Vec3 a, Vec3 b) { return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z); }

// sample_many (the spherical triangles side by side, core/spherical_triangle_batch.cpp) against sample() one receiver
// at a time, bit for bit: both methods, one- and two-sided, a textured light, receivers inside and outside the
// tetrahedron, far (area fallback) and at a corner, more receivers than a kernel chunk.
TEST(MeshLight, SampleManyEqualsSample) {
  const TriangleMesh mesh = tetrahedron();
  Pcg32 rng(13, 4);
  constexpr int n = 150;
  std::vector<LightSampleContext> ctx;
  std::vector<Vec2> u;
  for (int i = 0; i < n; ++i) {
    const Vec3 dir = normalize(Vec3{rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f});
    const float dists[] = {0.1f, 1.5f, 4.0f, 3000.0f};
    Vec3 p = Vec3{0.2f, -0.1f, 0.3f} + dir * dists[i % 4] * (0.5f + rng.next_float());
    if (i % 25 == 3) p = mesh.positions[1];
    ctx.push_back({p, normalize(Vec3{rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f})});
    u.push_back({rng.next_float(), rng.next_float()});
  }
  int compared = 0;
  for (TriangleSampling m : {TriangleSampling::Area, TriangleSampling::SphericalTriangle})
    for (bool two_sided : {false, true})
      for (bool textured : {false, true}) {
        const auto light = make_mesh_light(mesh, {1, 2, 3}, textured ? std::optional<Texture>(checker()) : std::nullopt,
                                           two_sided, m);
        std::vector<LightSample> out(n);
        bool ok[n];
        light->sample_many(ctx.data(), u.data(), n, out.data(), ok);
        for (int k = 0; k < n; ++k) {
          const std::optional<LightSample> ls = light->sample(ctx[k], u[k]);
          ASSERT_EQ(ok[k], ls.has_value()) << "lane " << k;
          if (!ls) continue;
          ++compared;
          ASSERT_TRUE(same(ls->wi, out[k].wi) && same(ls->dist, out[k].dist) && same(ls->pdf, out[k].pdf) &&
                      same(ls->p_light, out[k].p_light) && same(ls->n_light, out[k].n_light) &&
                      same(ls->p_error, out[k].p_error) && same(ls->le, out[k].le))
              << "lane " << k << (two_sided ? " two-sided" : " one-sided") << (textured ? " textured" : "");
        }
      }
  EXPECT_GT(compared, 400);  // of 1200 draws, those toward a face seen from its front
}

}  // namespace
}  // namespace lumis
