// Light selection: names, pmfs summing to 1, sample().pmf == pmf(), chosen indices following the pmf (chi-square),
// zero probability below the horizon, nullopt when nothing can contribute, the >64-light path, and the sphere
// lights' devirtualised importance equal to their own importance().
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/chi2.h"
#include "lights/light_selection.h"

namespace lumis {
namespace {

// Chi-square family: 4 tests (uniform, power, importance, 100 lights), Sidak-corrected alpha 0.01 for the family
// (1% false failures per run); 200k draws each, fixed seeds.
constexpr int kChiTests = 4;

struct Scene {
  std::vector<std::unique_ptr<Light>> owned;
  std::vector<const Light*> lights;
  void add(std::unique_ptr<Light> l) {
    lights.push_back(l.get());
    owned.push_back(std::move(l));
  }
};

// Receiver at the origin facing +y. Light 1 is entirely below its horizon (n.(c - p) = -2 < -r = -0.5).
Scene make_scene() {
  Scene s;
  s.add(make_sphere_light({0, 2, 0}, 0.5f, {4, 4, 4}));
  s.add(make_sphere_light({0, -2, 0}, 0.5f, {50, 50, 50}));
  s.add(make_sphere_light({3, 0.2f, 0}, 0.5f, {10, 5, 1}));        // straddles the horizon
  s.add(make_quad_light({-1, 3, -1}, {2, 0, 0}, {0, 0, 2}, {1, 1, 1}));  // faces -y
  s.add(make_constant_environment({0.1f, 0.1f, 0.2f}));
  return s;
}
const LightSampleContext kCtx{{0, 0, 0}, {0, 1, 0}};

void check_frequencies(const LightSelector& sel, const LightSampleContext& ctx, uint64_t seed) {
  const int n = static_cast<int>(sel.size());
  std::vector<double> observed(n, 0.0), expected(n, 0.0);
  Pcg32 rng(seed, 3);
  const int draws = 200'000;
  for (int i = 0; i < draws; ++i) {
    const auto c = sel.sample(ctx, rng.next_float());
    ASSERT_TRUE(c.has_value());
    ASSERT_GT(c->pmf, 0.0f);
    EXPECT_EQ(c->pmf, sel.pmf(ctx, c->index));
    observed[c->index] += 1;
  }
  for (int j = 0; j < n; ++j) expected[j] = double(sel.pmf(ctx, j)) * draws;
  const auto r = chi_square_test(observed, expected, 0.01, kChiTests);
  EXPECT_TRUE(r.passed) << r.message;
  std::printf("%d lights: %s\n", n, r.message.c_str());
}

TEST(LightSelection, Names) {
  for (LightSelection s : {LightSelection::Uniform, LightSelection::Power, LightSelection::Importance})
    EXPECT_EQ(parse_light_selection(light_selection_name(s)), s);
  EXPECT_FALSE(parse_light_selection("bvh").has_value());
  EXPECT_STREQ(light_selection_name(LightSelection::Importance), "importance");
}

TEST(LightSelection, PmfsSumToOneAndMatchSampling) {
  const Scene s = make_scene();
  uint64_t seed = 91;
  for (LightSelection strategy : {LightSelection::Uniform, LightSelection::Power, LightSelection::Importance}) {
    const LightSelector sel(s.lights, strategy);
    double sum = 0;
    for (int j = 0; j < static_cast<int>(sel.size()); ++j) sum += sel.pmf(kCtx, j);
    EXPECT_NEAR(sum, 1.0, 1e-6) << light_selection_name(strategy);
    EXPECT_EQ(sel.pmf(kCtx, -1), 0.0f);
    EXPECT_EQ(sel.pmf(kCtx, 99), 0.0f);
    check_frequencies(sel, kCtx, seed++);
  }
}

TEST(LightSelection, StrategiesWeighAsDocumented) {
  const Scene s = make_scene();
  const LightSelector uniform(s.lights, LightSelection::Uniform);
  for (int j = 0; j < 5; ++j) EXPECT_FLOAT_EQ(uniform.pmf(kCtx, j), 0.2f);
  const LightSelector power(s.lights, LightSelection::Power);
  double total_power = 0;
  for (const Light* l : s.lights) total_power += l->power();
  for (int j = 0; j < 5; ++j) EXPECT_NEAR(power.pmf(kCtx, j), s.lights[j]->power() / total_power, 1e-6);
  const LightSelector importance(s.lights, LightSelection::Importance);
  double total_imp = 0;
  for (const Light* l : s.lights) total_imp += l->importance(kCtx);
  for (int j = 0; j < 5; ++j)
    EXPECT_NEAR(importance.pmf(kCtx, j), s.lights[j]->importance(kCtx) / total_imp, 1e-6);
  // Below the horizon: never chosen; straddling: chosen; with no normal, the one below counts again.
  EXPECT_EQ(importance.pmf(kCtx, 1), 0.0f);
  EXPECT_GT(importance.pmf(kCtx, 2), 0.0f);
  EXPECT_GT(importance.pmf({kCtx.p, {0, 0, 0}}, 1), 0.0f);
  EXPECT_GT(importance.pmf(kCtx, 4), 0.0f) << "the environment is never entirely below a horizon";
}

// The importance strategy evaluates sphere lights through their parameters (no virtual call each): its pmf must be
// exactly what every light's own importance() gives, bit for bit, for spheres mixed with other kinds, at receivers
// inside, outside and around the spheres, with and without a horizon.
TEST(LightSelection, SphereFastPathEqualsEachLightsImportance) {
  const Scene s = make_scene();
  EXPECT_TRUE(s.lights[0]->sphere().has_value());
  EXPECT_FALSE(s.lights[3]->sphere().has_value());  // the quad
  EXPECT_FALSE(s.lights[4]->sphere().has_value());  // the environment
  // In the scene's order (spheres first) and reversed (spheres last), so a sphere's slot is not its rank.
  std::vector<const Light*> lights = s.lights;
  Pcg32 rng(41, 7);
  for (int trial = 0; trial < 2000; ++trial) {
    if (trial == 1000) std::reverse(lights.begin(), lights.end());
    const LightSelector sel(lights, LightSelection::Importance);
    const Vec3 p{8 * rng.next_float() - 4, 8 * rng.next_float() - 4, 4 * rng.next_float() - 2};
    const Vec3 n = trial % 7 == 0 ? Vec3(0) : normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f,
                                                             rng.next_float() - 0.5f));
    const LightSampleContext ctx{p, n};
    float c[5], total = 0;
    for (int j = 0; j < 5; ++j) {
      const float v = lights[j]->importance(ctx);
      c[j] = std::isfinite(v) && v > 0 ? v : 0.0f;
      total += c[j];
    }
    for (int j = 0; j < 5; ++j) ASSERT_EQ(sel.pmf(ctx, j), total > 0 ? c[j] / total : 0.0f) << trial << " " << j;
  }
}

TEST(LightSelection, NothingCanContribute) {
  Scene s;
  s.add(make_sphere_light({0, -2, 0}, 0.5f, {1, 1, 1}));
  s.add(make_quad_light({-1, -3, -1}, {2, 0, 0}, {0, 0, 2}, {1, 1, 1}));
  const LightSelector sel(s.lights, LightSelection::Importance);
  for (float u : {0.0f, 0.3f, kOneMinusEpsilon}) EXPECT_FALSE(sel.sample(kCtx, u).has_value());
  EXPECT_EQ(sel.pmf(kCtx, 0), 0.0f);
  EXPECT_FALSE(LightSelector({}, LightSelection::Uniform).sample(kCtx, 0.5f).has_value());
  // u at the very top of [0, 1) still lands on a light with positive importance.
  const Scene full = make_scene();
  const LightSelector imp(full.lights, LightSelection::Importance);
  const auto top = imp.sample(kCtx, kOneMinusEpsilon);
  ASSERT_TRUE(top.has_value());
  EXPECT_GT(imp.pmf(kCtx, top->index), 0.0f);
}

TEST(LightSelection, ManyLightsRecomputedSearch) {
  // 100 lights exceed the 64-entry stack cache: the search recomputes importances and must agree with pmf().
  Scene s;
  Pcg32 rng(92, 1);
  for (int i = 0; i < 100; ++i) {
    const Vec3 c{8 * rng.next_float() - 4, 8 * rng.next_float() - 4, 8 * rng.next_float() - 4};
    s.add(make_sphere_light(c * 2.0f, 0.1f + 0.3f * rng.next_float(), Color(0.5f + 4 * rng.next_float())));
  }
  const LightSelector sel(s.lights, LightSelection::Importance);
  double sum = 0;
  int zero = 0;
  for (int j = 0; j < 100; ++j) {
    sum += sel.pmf(kCtx, j);
    zero += sel.pmf(kCtx, j) == 0;
  }
  EXPECT_NEAR(sum, 1.0, 1e-5);
  EXPECT_GT(zero, 10) << "about half the spheres lie below the horizon";
  check_frequencies(sel, kCtx, 93);
}

}  // namespace
}  // namespace lumis
