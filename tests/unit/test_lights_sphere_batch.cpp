// The sphere light's batch path against its one-receiver path, bit for bit: the cap kernel at every instruction
// set this CPU runs (sphere_cap::run), SphereLight::sample_many (inside, on and outside the sphere, tiny and huge
// caps, more receivers than a kernel chunk, a zero radius) and LightSelector::sample_many (the one-sphere fast
// path and the one-at-a-time fallback). A lane that differed would make lockstep renders differ from single paths.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/simd.h"
#include "lights/light_selection.h"
#include "lights/sphere_cap.h"

namespace lumis {
namespace {

const Vec3 kCenter{0.3f, 1.2f, -0.5f};
constexpr float kRadius = 0.4f;

bool same(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
bool same(Vec3 a, Vec3 b) { return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z); }

// Receivers at every kind of distance from the sphere: inside, on it, just outside, near, far (caps down to
// ~1e-8 sr), with random normals (some facing away).
std::vector<LightSampleContext> receivers(int n, uint64_t seed) {
  Pcg32 rng(seed, 3);
  std::vector<LightSampleContext> out;
  for (int i = 0; i < n; ++i) {
    const Vec3 dir = normalize(Vec3{rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f});
    const float scales[] = {0.5f, 1.0f, 1.0001f, 1.5f, 10.0f, 4000.0f};
    const float dist = kRadius * scales[i % 6] * (i % 6 == 1 || i % 6 == 2 ? 1.0f : 0.5f + rng.next_float());
    const Vec3 n = normalize(Vec3{rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f});
    out.push_back({kCenter + dir * dist, n});
  }
  return out;
}

std::vector<Vec2> numbers(int n, uint64_t seed) {
  Pcg32 rng(seed, 5);
  std::vector<Vec2> u;
  for (int i = 0; i < n; ++i) u.push_back({rng.next_float(), rng.next_float()});
  u[0] = {0, 0};
  u[1] = {0.99999994f, 0.99999994f};
  return u;
}

TEST(SphereLightBatch, EveryKernelEqualsSampleOneReceiverAtATime) {
  const std::unique_ptr<Light> light = make_sphere_light(kCenter, kRadius, {3, 2, 1});
  constexpr int n = 61;  // not a multiple of any vector width
  for (int level = 0; level <= simd_level(); ++level)
    for (uint64_t seed = 1; seed <= 20; ++seed) {
      const std::vector<LightSampleContext> ctx = receivers(n, seed);
      const std::vector<Vec2> u = numbers(n, seed);
      sphere_cap::Batch b;
      b.c = kCenter, b.r = kRadius;
      for (int k = 0; k < n; ++k)
        b.px[k] = ctx[k].p.x, b.py[k] = ctx[k].p.y, b.pz[k] = ctx[k].p.z, b.ux[k] = u[k].x, b.uy[k] = u[k].y;
      sphere_cap::run(b, n, level);
      for (int k = 0; k < n; ++k) {
        if (length_squared(kCenter - ctx[k].p) <= kRadius * kRadius) continue;  // inside: sampled by area
        const std::string at = "kernel " + std::to_string(level) + " seed " + std::to_string(seed) + " lane " +
                               std::to_string(k);
        const std::optional<LightSample> ls = light->sample(ctx[k], u[k]);
        ASSERT_TRUE(ls) << at;
        ASSERT_TRUE(same(ls->wi, {b.wx[k], b.wy[k], b.wz[k]})) << at;
        ASSERT_TRUE(same(ls->dist, b.t[k])) << at;
        ASSERT_TRUE(same(ls->p_light, {b.lx[k], b.ly[k], b.lz[k]})) << at;
        ASSERT_TRUE(same(ls->n_light, {b.nx[k], b.ny[k], b.nz[k]})) << at;
        ASSERT_TRUE(same(ls->pdf, 1 / (2 * kPi * b.one_minus_cos_max[k]))) << at;
      }
    }
}

TEST(SphereLightBatch, SampleManyEqualsSample) {
  for (float radius : {kRadius, 0.0f}) {
    const std::unique_ptr<Light> light = make_sphere_light(kCenter, radius, {3, 2, 1});
    constexpr int n = 150;  // more than two kernel chunks
    const std::vector<LightSampleContext> ctx = receivers(n, 9);
    const std::vector<Vec2> u = numbers(n, 9);
    std::vector<LightSample> out(n);
    bool ok[n];
    light->sample_many(ctx.data(), u.data(), n, out.data(), ok);
    int outside = 0, inside = 0;
    for (int k = 0; k < n; ++k) {
      const std::optional<LightSample> ls = light->sample(ctx[k], u[k]);
      ASSERT_EQ(ok[k], ls.has_value()) << "radius " << radius << " lane " << k;
      if (!ls) continue;
      (length_squared(kCenter - ctx[k].p) <= radius * radius ? inside : outside) += 1;
      ASSERT_TRUE(same(ls->wi, out[k].wi) && same(ls->dist, out[k].dist) && same(ls->pdf, out[k].pdf) &&
                  same(ls->p_light, out[k].p_light) && same(ls->n_light, out[k].n_light) &&
                  same(ls->p_error, out[k].p_error) && same(ls->le, out[k].le))
          << "lane " << k;
    }
    if (radius > 0) {  // the receivers reach both branches
      EXPECT_GT(inside, 20);
      EXPECT_GT(outside, 80);
    }
  }
}

TEST(LightSelectorBatch, SampleManyEqualsSample) {
  std::vector<std::unique_ptr<Light>> owned;
  owned.push_back(make_sphere_light(kCenter, kRadius, {3, 2, 1}));
  owned.push_back(make_sphere_light({-2, 0, 1}, 0.2f, {30, 30, 30}));
  owned.push_back(make_quad_light({-1, 3, -1}, {2, 0, 0}, {0, 0, 2}, {1, 1, 1}));
  constexpr int n = 150;
  const std::vector<LightSampleContext> ctx = receivers(n, 4);
  std::vector<float> u(n);
  Pcg32 rng(11, 2);
  for (float& v : u) v = rng.next_float();
  for (size_t count : {size_t{1}, size_t{3}})  // one sphere: the vectorised test; three lights: one at a time
    for (LightSelection strategy : {LightSelection::Importance, LightSelection::Uniform, LightSelection::Power}) {
      std::vector<const Light*> lights;
      for (size_t i = 0; i < count; ++i) lights.push_back(owned[i].get());
      const LightSelector selector(lights, strategy);
      std::vector<LightChoice> out(n);
      selector.sample_many(ctx.data(), u.data(), n, out.data());
      int none = 0;
      for (int k = 0; k < n; ++k) {
        const LightChoice c = selector.sample(ctx[k], u[k]).value_or(LightChoice{});
        none += c.index < 0;
        ASSERT_EQ(out[k].index, c.index) << light_selection_name(strategy) << " " << count << " lane " << k;
        ASSERT_TRUE(same(out[k].pmf, c.pmf)) << light_selection_name(strategy) << " " << count << " lane " << k;
      }
      // Receivers inside the sphere or with the sphere below their horizon have no light to choose.
      if (count == 1 && strategy == LightSelection::Importance) {
        EXPECT_GT(none, 10);
      }
    }
}

}  // namespace
}  // namespace lumis
