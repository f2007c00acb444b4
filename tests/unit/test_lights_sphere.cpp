// Sphere light: chi-square of sampled directions against pdf() from near, far, grazing and inside receivers; the
// Monte Carlo solid angle (mean of 1/pdf) against 2 pi (1 - cos alpha); sample().pdf == pdf(); one-sidedness and
// the horizon rule of importance(); the normals of spheres far smaller than their distance.
#include <gtest/gtest.h>

#include <cmath>

#include "core/chi2.h"
#include "core/frame.h"
#include "lights/light.h"
#include "light_test_shapes.h"

namespace lumis {
namespace {

// Chi-square family: 4 receivers, Sidak-corrected alpha 0.01 for the family (1% false failures per run), seeds fixed.
constexpr int kChiTests = 4;
const Vec3 kCenter{0.3f, -0.2f, 0.1f};
constexpr float kRadius = 0.5f;
const Color kRadiance{2, 3, 4};

// pdf of a direction: a sphere's density is per direction, so one crossing of the ray (here the far one, to show
// that either will do) is asked, as the integrator does after merging a sphere's two hits.
double direction_pdf(const Light& light, const LightSampleContext& ctx, Vec3 w) {
  const auto hits = test::sphere_hits(ctx.p, w, kCenter, kRadius);
  return hits.empty() ? 0.0 : light.pdf(ctx, w, hits.back());
}

const LightSampleContext kReceivers[] = {
    {kCenter + Vec3{0.8f, 0.1f, 0.05f}, {0, 1, 0}},     // near: cap half-angle ~ 37 degrees
    {kCenter + Vec3{-6, 1, 0.2f}, {0, 0, 0}},           // far: ~0.02 sr
    {kCenter + Vec3{0, 0.55f, 0.3f}, {0, 1, 0}},        // grazing: just outside, cap nearly a hemisphere
    {kCenter + Vec3{0.1f, 0.2f, -0.1f}, {0, 0, 1}},     // inside: area sampling
};

TEST(SphereLight, DirectionsFollowPdf) {
  const auto light = make_sphere_light(kCenter, kRadius, kRadiance);
  for (const auto& ctx : kReceivers) {
    DirectionalTest cfg;
    cfg.samples = 200'000;
    cfg.num_tests = kChiTests;
    cfg.seed = 21;
    cfg.integration_resolution = 2;  // adaptive refinement does the work at the edges
    const auto r = chi_square_directions(
        [&](Pcg32& rng) -> std::optional<Vec3> {
          const auto s = light->sample(ctx, {rng.next_float(), rng.next_float()});
          if (!s) return std::nullopt;
          return s->wi;
        },
        [&](Vec3 w) { return direction_pdf(*light, ctx, w); }, cfg);
    EXPECT_TRUE(r.passed) << r.message;
    std::printf("sphere from (%g, %g, %g): %s\n", ctx.p.x, ctx.p.y, ctx.p.z, r.message.c_str());
  }
}

TEST(SphereLight, SolidAngleMatchesCapFormula) {
  // Receivers at distances d with r/d from 0.99 to 1e-4 (a cap of 3e-8 sr, where 1 - cos in float would be 0).
  for (double ratio : {0.99, 0.5, 0.1, 1e-2, 1e-4}) {
    const auto light = make_sphere_light({0, 0, 0}, 1.0f, kRadiance);
    const LightSampleContext ctx{{static_cast<float>(1 / ratio), 0, 0}, {0, 0, 0}};
    const double exact = 2 * M_PI * (1 - std::sqrt(1 - ratio * ratio));
    Pcg32 rng(5, 5);
    double sum = 0;
    const int n = 1000;
    for (int i = 0; i < n; ++i) {
      const auto s = light->sample(ctx, {rng.next_float(), rng.next_float()});
      ASSERT_TRUE(s.has_value());
      sum += 1.0 / s->pdf;
    }
    EXPECT_NEAR(sum / n / exact, 1.0, 1e-5) << "r/d = " << ratio;
    std::printf("r/d = %g: MC solid angle %.9g, closed form %.9g\n", ratio, sum / n, exact);
  }
}

TEST(SphereLight, InsideAreaSamplingCoversTheSphere) {
  // From inside, E[1/pdf] over the area samples is the full 4 pi; 100k samples, tolerance 5 standard errors
  // (false failure ~ 6e-7).
  const auto light = make_sphere_light(kCenter, kRadius, kRadiance);
  const LightSampleContext ctx = kReceivers[3];
  Pcg32 rng(8, 1);
  double sum = 0, sum2 = 0;
  const int n = 100'000;
  for (int i = 0; i < n; ++i) {
    const auto s = light->sample(ctx, {rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s.has_value());
    EXPECT_TRUE(is_black(s->le)) << "one-sided: nothing reaches the inside";
    sum += 1.0 / s->pdf;
    sum2 += 1.0 / (double(s->pdf) * s->pdf);
  }
  const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean, 4 * M_PI, 5 * se);
  std::printf("inside: MC solid angle %.5f +- %.5f, 4 pi = %.5f\n", mean, se, 4 * M_PI);
}

TEST(SphereLight, SamplePdfEqualsPdf) {
  const auto light = make_sphere_light(kCenter, kRadius, kRadiance);
  Pcg32 rng(9, 2);
  for (const auto& ctx : kReceivers) {
    for (int i = 0; i < 500; ++i) {
      const auto s = light->sample(ctx, {rng.next_float(), rng.next_float()});
      ASSERT_TRUE(s.has_value());
      EXPECT_NEAR(length(s->wi), 1.0f, 1e-5f);
      EXPECT_NEAR(length(s->p_light - kCenter), kRadius, 1e-4f);
      EXPECT_NEAR(length(s->p_light - ctx.p), s->dist, 1e-4f);
      Hit on;
      on.p = s->p_light;
      on.ng = s->n_light;
      EXPECT_FLOAT_EQ(light->pdf(ctx, s->wi, on), s->pdf);
      EXPECT_EQ(s->le, light->le(on, -s->wi));
    }
  }
}

// Spheres up to 1e15 times smaller than their distance: every cap sample emits toward the receiver, and its normal
// is a unit vector facing it, distributed as the visible hemisphere's projection (cosine-weighted about the
// direction to the receiver: mean cos 2/3, variance 1/18; each lateral component mean 0, variance 1/4), compared
// within 5 standard errors (false failure ~6e-7 each, 12 comparisons). Where floats still resolve the sphere
// (radius 1e-3 at 2.5), the normal is the sampled point's. The normal used to be (point - centre) / r: below
// ~1e-6 of the distance, vectors of any length and direction, half of them facing away, so tiny lights were dark.
TEST(SphereLight, TinySpheresFaceTheReceiver) {
  const Vec3 c{0.3f, 2, -1.5f};
  const LightSampleContext ctx{{0, 0, 0}, {0, 1, 0}};
  const Vec3 z = normalize(c - ctx.p);
  const Frame frame = Frame::from_normal(z);
  for (float r : {1e-3f, 1e-6f, 1e-10f, 1e-15f}) {
    const auto light = make_sphere_light(c, r, kRadiance);
    Pcg32 rng(12, 4);
    const int n = 20'000;
    double cos_sum = 0, x_sum = 0, y_sum = 0;
    for (int i = 0; i < n; ++i) {
      const auto s = light->sample(ctx, {rng.next_float(), rng.next_float()});
      ASSERT_TRUE(s.has_value());
      ASSERT_EQ(s->le, kRadiance) << "r " << r << " sample " << i;
      ASSERT_NEAR(length(s->n_light), 1.0f, 1e-5f) << "r " << r << " sample " << i;
      ASSERT_GT(dot(s->n_light, -s->wi), -1e-6f) << "r " << r << " sample " << i;
      if (r >= 1e-3f) {
        ASSERT_LT(length(s->n_light - (s->p_light - c) / r), 1e-3f) << "sample " << i;
      }
      const Vec3 local = frame.to_local(s->n_light);
      cos_sum += -local.z, x_sum += local.x, y_sum += local.y;
    }
    EXPECT_NEAR(cos_sum / n, 2.0 / 3, 5 * std::sqrt(1.0 / 18 / n)) << "r " << r;
    EXPECT_NEAR(x_sum / n, 0, 5 * std::sqrt(0.25 / n)) << "r " << r;
    EXPECT_NEAR(y_sum / n, 0, 5 * std::sqrt(0.25 / n)) << "r " << r;
  }
}

TEST(SphereLight, OneSidedAndHorizon) {
  const auto light = make_sphere_light(kCenter, kRadius, kRadiance);
  Hit on;
  on.p = kCenter + Vec3{0, kRadius, 0};
  on.ng = {0, 1, 0};
  EXPECT_EQ(light->le(on, {0, 1, 0}), kRadiance);
  EXPECT_EQ(light->le(on, normalize(Vec3{1, 0.2f, 0})), kRadiance);
  EXPECT_TRUE(is_black(light->le(on, {0, -1, 0})));
  // Horizon: n.(c - p) < -r -> 0; partly above -> positive and equal to the cap solid angle x luminance.
  const Vec3 p = kCenter + Vec3{0, 2, 0};
  EXPECT_EQ(light->importance({p, {0, 1, 0}}), 0.0f);
  EXPECT_GT(light->importance({p, normalize(Vec3{1, -0.2f, 0})}), 0.0f);
  // The centre below the horizon (n.(c - p) = -0.39) but the top of the sphere above it (-0.39 > -r = -0.5): the
  // light still reaches p, so it must stay selectable.
  EXPECT_GT(light->importance({p, normalize(Vec3{1, 0.2f, 0})}), 0.0f);
  EXPECT_EQ(light->importance({p, normalize(Vec3{1, 0.3f, 0})}), 0.0f);  // -0.57 < -0.5: wholly below
  const float cap = 2 * kPi * (1 - std::sqrt(1 - 0.25f * 0.25f));
  EXPECT_NEAR(light->importance({p, {0, 0, 0}}) / (cap * luminance(kRadiance)), 1.0f, 1e-4f);
  EXPECT_EQ(light->importance(kReceivers[3]), 0.0f) << "inside a one-sided sphere nothing arrives";
  EXPECT_NEAR(light->power(), kPi * 4 * kPi * kRadius * kRadius * luminance(kRadiance), 1e-3f);
}

}  // namespace
}  // namespace lumis
