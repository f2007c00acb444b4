// Film: non-finite samples (NaN, +Inf, -Inf, and values that overflow when summed in float elsewhere) are dropped
// and counted per pixel, and never reach the mean, the variance or the sample count; AOV channels are the means of
// their samples. Deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/film.h"

namespace lumis {
namespace {

TEST(Film, DropsAndCountsNonFiniteSamples) {
  Film film(2, 1);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  film.add(0, 0, Color(1.0f));
  film.add(0, 0, Color(nan, 0, 0));
  film.add(0, 0, Color(0, inf, 0));
  film.add(0, 0, Color(0, 0, -inf));
  film.add(0, 0, Color(3.0f));
  film.add(0, 0, Color(3e38f) * 10.0f);  // overflows to +Inf before it reaches the film
  film.add(1, 0, Color(nan));
  EXPECT_EQ(film.dropped(), 5u);
  EXPECT_EQ(film.count(0, 0), 2u);
  EXPECT_EQ(film.count(1, 0), 0u);
  EXPECT_FLOAT_EQ(film.mean(0, 0)[0], 2.0f);
  EXPECT_FLOAT_EQ(film.mean(0, 0)[2], 2.0f);
  // Sample variance of {1, 3} is 2; of the mean, 1.
  EXPECT_FLOAT_EQ(film.variance_of_mean(0, 0)[1], 1.0f);
  // A pixel whose every sample was dropped is black, not NaN.
  EXPECT_EQ(film.mean(1, 0)[0], 0.0f);
  for (float v : film.to_image().data) EXPECT_TRUE(std::isfinite(v));
}

TEST(Film, VarianceBeyondFloatRangeIsTheLargestFloatNotInf) {
  // Finite samples near float's largest value: their squares and their variance exceed float's range.
  Film film(1, 1);
  film.add(0, 0, Color(0.0f));
  film.add(0, 0, Color(3e38f));
  EXPECT_EQ(film.dropped(), 0u);
  EXPECT_FLOAT_EQ(film.mean(0, 0)[0], 1.5e38f);
  EXPECT_EQ(film.variance_of_mean(0, 0)[0], std::numeric_limits<float>::max());
  for (float v : film.to_image().data) EXPECT_TRUE(std::isfinite(v));
}

// Each AOV channel is the mean of its samples, written under its own name.
TEST(Film, AovChannelsAreTheMeansOfTheirSamples) {
  Film film(1, 1, FilmOptions{true, true, true, true});
  AovSample a{Color(0.0f, 0.1f, 0.2f), Vec3(0, 1, 0), 1.0f}, b{Color(0.2f, 0.3f, 0.4f), Vec3(0, 0.2f, 1.6f), 5.0f};
  film.add(0, 0, Color(1.0f), &a);
  film.add(0, 0, Color(1.0f), &b);
  const Image img = film.to_image();
  auto channel = [&](const std::string& name) {
    for (int c = 0; c < img.channels; ++c)
      if (img.channel_names[c] == name) return img.at(0, 0, c);
    ADD_FAILURE() << "no channel " << name;
    return 0.0f;
  };
  EXPECT_NEAR(channel("albedo.R"), 0.1f, 1e-6f);
  EXPECT_NEAR(channel("albedo.G"), 0.2f, 1e-6f);
  EXPECT_NEAR(channel("albedo.B"), 0.3f, 1e-6f);
  EXPECT_NEAR(channel("N.X"), 0.0f, 1e-6f);
  EXPECT_NEAR(channel("N.Y"), 0.6f, 1e-6f);
  EXPECT_NEAR(channel("N.Z"), 0.8f, 1e-6f);
  EXPECT_NEAR(channel("Z"), 3.0f, 1e-6f);
}

// A sample with any non-finite AOV value is left out of the AOV means (and of their count), whichever comes first;
// its radiance still counts. Counting it, as the AOVs once did, would average a zero into the mean: 0.25, not 0.5.
TEST(Film, AovsLeaveOutSamplesWithNonFiniteValues) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const AovSample good{Color(0.5f), Vec3(0, 0, 1), 2.0f};
  const AovSample bad_all{Color(nan), Vec3(nan, 0, 1), nan};
  const AovSample bad_depth{Color(0.9f), Vec3(1, 0, 0), std::numeric_limits<float>::infinity()};
  for (const AovSample* bad : {&bad_all, &bad_depth}) {
    Film film(1, 1, FilmOptions{true, true, true, true});
    film.add(0, 0, Color(1.0f), bad);
    film.add(0, 0, Color(1.0f), &good);
    film.add(0, 0, Color(1.0f), bad);
    EXPECT_EQ(film.count(0, 0), 3u);
    const Image img = film.to_image();
    for (float v : img.data) EXPECT_TRUE(std::isfinite(v));
    // R G B, variance.RGB, albedo.RGB, N.XYZ, Z
    ASSERT_EQ(img.channels, 13);
    for (int c = 6; c < 9; ++c) EXPECT_FLOAT_EQ(img.at(0, 0, c), 0.5f) << img.channel_names[c];
    EXPECT_FLOAT_EQ(img.at(0, 0, 9), 0.0f);
    EXPECT_FLOAT_EQ(img.at(0, 0, 10), 0.0f);
    EXPECT_FLOAT_EQ(img.at(0, 0, 11), 1.0f);
    EXPECT_FLOAT_EQ(img.at(0, 0, 12), 2.0f);
  }
}

}  // namespace
}  // namespace lumis
