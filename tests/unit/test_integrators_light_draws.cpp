// draw_lights (integrators/path.cpp), the light choices and light samples of a bounce's lanes drawn together,
// against the selector and each light drawing for one receiver at a time, bit for bit: one sphere light (the
// vectorised paths), mixed lights (spheres, a quad, a mesh) grouped by the light chosen, and more lights than a
// batch has lanes (one receiver at a time), with lanes listed out of order and some lanes left out. Also the MIS
// weight (path.cpp's mis_weight) at extreme densities.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <string>
#include <vector>

#include "core/rng.h"
#include "integrators/path.h"

namespace lumis {
namespace {

bool same(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
bool same(Vec3 a, Vec3 b) { return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z); }

// expect_none: the importance strategy, which chooses no light for a receiver with every light below its horizon.
void expect_draws_match(Scene& scene, const std::string& name, bool expect_none) {
  scene.finalize();
  constexpr int n = PathBatch::kMaxLanes;
  Pcg32 rng(5, 9);
  std::vector<Hit> hits(n);
  std::vector<VertexDims> dims(n);
  for (int k = 0; k < n; ++k) {
    hits[k].p = {4 * rng.next_float() - 2, 3 * rng.next_float() - 0.5f, 4 * rng.next_float() - 2};
    hits[k].ng = normalize(Vec3{rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f});
    hits[k].front = rng.next_float() < 0.5f;
    hits[k].p_error = Vec3(1e-3f * rng.next_float());  // light_context offsets the receiver off the surface
    dims[k] = {rng.next_float(), {rng.next_float(), rng.next_float()}, 0, {0, 0}, 0};
  }
  // Every third lane left out, the rest listed backwards.
  std::vector<int> lanes;
  for (int k = n - 1; k >= 0; --k)
    if (k % 3 != 1) lanes.push_back(k);
  std::vector<LightDraw> out(n);
  draw_lights(scene, hits.data(), lanes.data(), static_cast<int>(lanes.size()), dims.data(), out.data());
  int drawn = 0, none = 0;
  for (const int k : lanes) {
    const std::string at = name + " lane " + std::to_string(k);
    const LightSampleContext ctx = light_context(hits[k]);
    const LightChoice c = scene.light_selector.sample(ctx, dims[k].choice).value_or(LightChoice{});
    ASSERT_TRUE(same(out[k].ctx.p, ctx.p) && same(out[k].ctx.n, ctx.n)) << at;  // make_vertex's receiver
    ASSERT_EQ(out[k].choice.index, c.index) << at;
    ASSERT_TRUE(same(out[k].choice.pmf, c.pmf)) << at;
    if (c.index < 0) {
      ++none;
      continue;
    }
    const std::optional<LightSample> ls = scene.lights[c.index]->sample(ctx, dims[k].light);
    ASSERT_EQ(out[k].ok, ls.has_value()) << at;
    if (!ls) continue;
    ++drawn;
    const LightSample& d = out[k].sample;
    ASSERT_TRUE(same(d.wi, ls->wi) && same(d.dist, ls->dist) && same(d.pdf, ls->pdf) && same(d.p_light, ls->p_light) &&
                same(d.n_light, ls->n_light) && same(d.p_error, ls->p_error) && same(d.le, ls->le))
        << at;
  }
  EXPECT_GT(drawn, 60) << name;  // of 171 receivers, about half face a light
  if (expect_none) {
    EXPECT_GT(none, 0) << name << ": some receivers have every light below the horizon";
  }
}

TEST(DrawLights, OneSphereEqualsOneReceiverAtATime) {
  Scene scene;
  scene.lights.push_back(make_sphere_light({0, 1.7f, 0}, 0.2f, {25, 25, 25}));
  expect_draws_match(scene, "one sphere", true);
}

TEST(DrawLights, MixedLightsEqualOneReceiverAtATime) {
  for (LightSelection strategy : {LightSelection::Importance, LightSelection::Power, LightSelection::Uniform}) {
    Scene scene;
    scene.lights.push_back(make_sphere_light({0, 1.7f, 0}, 0.2f, {25, 25, 25}));
    scene.lights.push_back(make_quad_light({-1, 2.5f, -1}, {2, 0, 0}, {0, 0, 2}, {5, 5, 5}));
    scene.lights.push_back(make_sphere_light({1.5f, 0.5f, 0.5f}, 0.1f, {40, 10, 10}));
    TriangleMesh panel;  // two triangles facing down: the spherical-triangle batch
    panel.positions = {{-0.5f, 2.9f, -0.5f}, {0.5f, 2.9f, -0.5f}, {0.5f, 2.9f, 0.5f}, {-0.5f, 2.9f, 0.5f}};
    panel.indices = {0, 1, 2, 0, 2, 3};
    scene.lights.push_back(make_mesh_light(panel, {4, 4, 4}, std::nullopt, false));
    scene.settings.light_selection = strategy;
    expect_draws_match(scene, light_selection_name(strategy), strategy == LightSelection::Importance);
  }
}

TEST(DrawLights, MoreLightsThanLanesEqualOneReceiverAtATime) {
  Scene scene;
  Pcg32 rng(2, 4);
  for (int i = 0; i < PathBatch::kMaxLanes + 44; ++i)
    scene.lights.push_back(make_sphere_light({6 * rng.next_float() - 3, 2 + rng.next_float(), 6 * rng.next_float() - 3},
                                             0.05f, {1, 1, 1}));
  expect_draws_match(scene, "many", false);
}

// The `mis` variant's light-strategy density at a direction sums every light whose solid angle holds it, visible
// or not: here 40 sphere lights in a row straight above the receiver, 80 crossings of light surfaces, beyond the
// 64 the query keeps on the stack. Uniform selection (1/40 each) and cap densities from 1.2 (the nearest sphere)
// to about 4500 per steradian (the farthest) sum to 1547; the bound is 1e-5 of that, 20 times a float sum's
// rounding. Before, the crossings past 64 were dropped: the density came out as 794.
TEST(LightStrategyPdf, CountsEveryLightOnADirectionThroughMoreThan64LightSurfaces) {
  Scene scene;
  scene.settings.light_selection = LightSelection::Uniform;
  constexpr int kSpheres = 40;
  for (int k = 0; k < kSpheres; ++k) {
    const Vec3 centre{0, 2.0f + 3.0f * k, 0};
    scene.geometry.add_sphere(Sphere{centre, 1, -1, k});
    scene.lights.push_back(make_sphere_light(centre, 1, {1, 1, 1}));
  }
  scene.finalize();
  Hit from;
  from.p = {0, 0, 0};
  from.ng = {0, 1, 0};
  from.front = true;
  const LightSampleContext ctx{from.p, from.ng};
  const Vec3 up{0, 1, 0};
  double expected = 0;
  for (int k = 0; k < kSpheres; ++k) {
    Hit on;  // the sphere's near side; a sphere's density is per direction
    on.p = {0, 1.0f + 3.0f * k, 0};
    on.ng = {0, -1, 0};
    on.front = true;
    on.light = k;
    expected += scene.light_selector.pmf(ctx, k) * scene.lights[k]->pdf(ctx, up, on);
  }
  PathCounters counters;
  const float pdf = light_strategy_pdf(scene, from, ctx, up, counters);
  EXPECT_NEAR(pdf, expected, 1e-5 * expected);
  EXPECT_EQ(counters.light_queries, 2u) << "the stack's 64 crossings, then all 80";
}

// The two weights of a pair of strategies sum to one, for both heuristics, also where a density's square is beyond
// float's range (a light smaller than 1e-10 of its distance has a density above 1.8e19 per steradian).
TEST(MisWeight, WeightsOfTwoStrategiesSumToOneAtAnyScale) {
  for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power}) {
    for (float scale : {1e-30f, 1.0f, 1e19f, 1e30f}) {
      const float a = 3 * scale, b = scale;
      const float wa = mis_weight(a, b, h), wb = mis_weight(b, a, h);
      EXPECT_NEAR(wa, h == MisHeuristic::Power ? 0.9f : 0.75f, 1e-6f) << scale;
      EXPECT_NEAR(wa + wb, 1.0f, 1e-6f) << scale;
    }
    EXPECT_EQ(mis_weight(0, 0, h), 0.0f);
    EXPECT_EQ(mis_weight(2, 0, h), 1.0f);
  }
}

}  // namespace
}  // namespace lumis
