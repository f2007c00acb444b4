// The render options shared by `lumis render`, `compare` and `bench` (app/render_overrides.h): each one given on the
// command line replaces its scene-file setting, and only that one; names are checked; options that none of the
// chosen integrators reads are named in a warning. The command-line parsing itself is in tests/cli/outputs.sh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "app/render_overrides.h"
#include "app/scene_error.h"
#include "app/scene_loader.h"

using namespace lumis;

namespace {

/// Settings that differ from every value the tests below override to.
RenderSettings scene_settings() {
  RenderSettings s;
  s.width = 400;
  s.height = 100;  // 4:1
  return s;
}

}  // namespace

TEST(RenderOptions, EachOverrideReplacesItsSettingAndNoOther) {
  const RenderSettings base = scene_settings();
  {  // nothing given: nothing changes
    RenderSettings s = base;
    apply_overrides({}, s);
    EXPECT_EQ(s.spp, base.spp);
    EXPECT_EQ(s.width, 400);
    EXPECT_EQ(s.height, 100);
  }
  RenderOverrides o;
  o.spp = 7;
  o.seed = 4000000000u;
  o.max_depth = 2;
  o.rr_depth = 0;  // 0 (off) is a value, not "not given"
  o.threads = 3;
  o.time = 0.05;
  o.exposure = -2;
  o.mis_light_probability = 0.25f;
  o.integrator = "uniform";
  o.sampler = "sobol";
  o.light_selection = "power";
  o.mis_heuristic = "power";
  o.uniform_measure = "solid-angle";
  RenderSettings s = base;
  apply_overrides(o, s);
  EXPECT_EQ(s.spp, 7u);
  EXPECT_EQ(s.seed, 4000000000u);
  EXPECT_EQ(s.max_depth, 2);
  EXPECT_EQ(s.rr_depth, 0);
  EXPECT_EQ(s.threads, 3);
  EXPECT_EQ(s.time_budget, 0.05);  // exactly: a float would make it 0.0500000007 in compare's report
  EXPECT_EQ(s.exposure, -2.0f);
  EXPECT_EQ(s.mis_light_probability, 0.25f);
  EXPECT_EQ(s.integrator, "uniform");
  EXPECT_EQ(s.sampler, SamplerType::Sobol);
  EXPECT_EQ(s.light_selection, LightSelection::Power);
  EXPECT_EQ(s.mis_heuristic, MisHeuristic::Power);
  EXPECT_EQ(s.uniform_measure, UniformMeasure::SolidAngle);
  EXPECT_EQ(s.width, 400);  // not given: the scene's size
  EXPECT_EQ(s.height, 100);
  // The other spellings and values: the scene file's names for the measure, and back to the defaults.
  o = {};
  o.uniform_measure = "theta_phi";
  o.mis_heuristic = "balance";
  o.sampler = "independent";
  o.light_selection = "uniform";
  apply_overrides(o, s);
  EXPECT_EQ(s.uniform_measure, UniformMeasure::ThetaPhi);
  EXPECT_EQ(s.mis_heuristic, MisHeuristic::Balance);
  EXPECT_EQ(s.sampler, SamplerType::Independent);
  EXPECT_EQ(s.light_selection, LightSelection::Uniform);
  o = {};
  o.uniform_measure = "solid_angle";
  apply_overrides(o, s);
  EXPECT_EQ(s.uniform_measure, UniformMeasure::SolidAngle);
}

// A scene file's `time` and the command line's --spp: --spp alone renders that many samples (as `compare --spp` does,
// so that compare's "reproduce with lumis render" line is the same image); --spp and --time both keep both, and the
// render stops at whichever comes first; --time alone replaces the scene's budget.
TEST(RenderOptions, SppAloneOverridesTheScenesTimeBudget) {
  const auto budget = [](std::optional<uint32_t> spp, std::optional<double> time) {
    RenderSettings s = scene_settings();
    s.time_budget = 5;
    RenderOverrides o;
    o.spp = spp;
    o.time = time;
    apply_overrides(o, s);
    return s.time_budget;
  };
  EXPECT_EQ(budget(std::nullopt, std::nullopt), 5.0);
  EXPECT_EQ(budget(16, std::nullopt), 0.0);
  EXPECT_EQ(budget(16, 2.0), 2.0);
  EXPECT_EQ(budget(std::nullopt, 2.0), 2.0);
  EXPECT_EQ(budget(std::nullopt, 0.0), 0.0);
}

TEST(RenderOptions, WidthOrHeightAloneKeepsTheAspectRatio) {
  const auto size = [](std::optional<int> w, std::optional<int> h) {
    RenderSettings s = scene_settings();  // 400 x 100
    RenderOverrides o;
    o.width = w;
    o.height = h;
    apply_overrides(o, s);
    return std::pair{s.width, s.height};
  };
  EXPECT_EQ(size(200, std::nullopt), (std::pair{200, 50}));
  EXPECT_EQ(size(std::nullopt, 50), (std::pair{200, 50}));
  EXPECT_EQ(size(30, std::nullopt), (std::pair{30, 8}));   // 7.5 rounds to 8
  EXPECT_EQ(size(2, std::nullopt), (std::pair{2, 1}));     // 0.5 rounds to one pixel
  EXPECT_EQ(size(64, 64), (std::pair{64, 64}));            // both given: as given
  EXPECT_EQ(size(std::nullopt, 4096), (std::pair{16384, 4096}));  // the largest side, exactly
  // A side the aspect ratio would put beyond 1...16384 pixels: a usage error, not a squashed picture (it was clamped
  // silently, 16384 x 20 for a 16000 x 10 scene's --height 20).
  const auto error = [&](std::optional<int> w, std::optional<int> h) {
    try {
      size(w, h);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error(std::nullopt, 4097), "--height 4097 alone keeps the scene's 400 x 100 aspect ratio, which needs a "
                                       "width of 16388 pixels, outside 1 to 16384: give --width as well");
  // The size named is the one tested, rounded alike: 10923 x 1.5 = 16384.5 rounds up to 16385 (printf's "%.0f"
  // rounds half to even and said 16384, "outside 1 to 16384").
  RenderSettings wide;
  wide.width = 1536;
  wide.height = 1024;
  RenderOverrides tall;
  tall.height = 10923;
  try {
    apply_overrides(tall, wide);
    ADD_FAILURE() << "--height 10923 of a 3:2 scene accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("needs a width of 16385 pixels"), std::string::npos) << e.what();
  }
  EXPECT_EQ(error(1, std::nullopt), "--width 1 alone keeps the scene's 400 x 100 aspect ratio, which needs a height "
                                    "of 0.25 pixels, outside 1 to 16384: give --height as well");
}

TEST(RenderOptions, UnknownNamesAreErrorsListingTheValidOnes) {
  // The message apply_overrides throws when only `field` is given, set to `value`.
  const auto message = [](std::optional<std::string> RenderOverrides::*field, const char* value) {
    RenderOverrides o;
    o.*field = value;
    RenderSettings s;
    try {
      apply_overrides(o, s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(message(&RenderOverrides::integrator, "photon"),
            "--integrator: unknown integrator 'photon' (valid: uniform, bsdf, light, mis, nee_mis)");
  EXPECT_EQ(message(&RenderOverrides::sampler, "halton"),
            "--sampler: unknown sampler 'halton' (valid: independent, stratified, sobol)");
  EXPECT_EQ(message(&RenderOverrides::light_selection, "random"),
            "--light-selection: unknown strategy 'random' (valid: uniform, power, importance)");
  EXPECT_EQ(message(&RenderOverrides::mis_heuristic, "max"),
            "--mis-heuristic: unknown heuristic 'max' (valid: balance, power)");
  EXPECT_EQ(message(&RenderOverrides::uniform_measure, "area"),
            "--uniform-measure: unknown measure 'area' (valid: theta-phi, solid-angle)");
}

TEST(RenderOptions, OptionsNoChosenIntegratorReadsAreNamed) {
  RenderOverrides o;
  o.mis_light_probability = 0.3f;
  o.uniform_measure = "solid-angle";
  o.mis_heuristic = "power";
  o.light_selection = "power";
  EXPECT_EQ(unused_overrides(o, {"bsdf"}),
            (std::vector<std::string>{
                "--mis-light-probability only affects the mis integrator; ignored for bsdf",
                "--uniform-measure only affects the uniform integrator; ignored for bsdf",
                "--mis-heuristic only affects the nee_mis integrator; ignored for bsdf",
                "--light-selection only affects light, mis and nee_mis; ignored for bsdf"}));
  EXPECT_EQ(unused_overrides(o, {"nee_mis"}),
            (std::vector<std::string>{
                "--mis-light-probability only affects the mis integrator; ignored for nee_mis",
                "--uniform-measure only affects the uniform integrator; ignored for nee_mis"}));
  // mis weighs its one sample by the mixture density, the balance heuristic: --mis-heuristic does not reach it.
  EXPECT_EQ(unused_overrides(o, {"uniform", "mis"}),
            std::vector<std::string>{"--mis-heuristic only affects the nee_mis integrator; ignored for uniform, mis"});
  EXPECT_EQ(unused_overrides(o, {"light", "uniform"}),
            (std::vector<std::string>{
                "--mis-light-probability only affects the mis integrator; ignored for light, uniform",
                "--mis-heuristic only affects the nee_mis integrator; ignored for light, uniform"}));
  EXPECT_TRUE(unused_overrides({}, {"bsdf"}).empty());
  // compare's rendered reference is nee_mis: it uses --mis-heuristic and --light-selection, and is named apart.
  EXPECT_EQ(unused_overrides(o, {"light", "bsdf"}, true),
            (std::vector<std::string>{
                "--mis-light-probability only affects the mis integrator; ignored for light, bsdf and the reference "
                "(nee_mis)",
                "--uniform-measure only affects the uniform integrator; ignored for light, bsdf and the reference "
                "(nee_mis)"}));
}

// A scene file without a camera is framed for its film's aspect ratio; --width and --height of another ratio frame
// it again, so that a tall image still shows the whole scene (its bounding sphere inside the narrower field of
// view, and not lost in the distance). A scene with a camera keeps it.
TEST(RenderOptions, ANewAspectRatioFramesAGeneratedCameraAgain) {
  const std::string shapes = R"("materials": {"m": {"type": "diffuse"}},
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}])";
  for (const auto& [w, h] : {std::pair{100, 400}, std::pair{400, 100}}) {
    const auto scene = load_scene_text(R"({"film": {"width": 400, "height": 400}, )" + shapes + "}", "framed.json");
    ASSERT_TRUE(scene->framed.has_value());
    RenderOverrides o;
    o.width = w;
    o.height = h;
    apply_overrides(o, *scene);
    const Camera& c = scene->camera;
    const float half_y = 0.5f * c.fov_y_degrees * kPi / 180;
    const float half_x = std::atan(std::tan(half_y) * float(w) / float(h));
    // The unit sphere's bounding box [-1, 1]^3 has a bounding sphere of radius sqrt(3) about the origin.
    const float seen = std::asin(std::sqrt(3.0f) / length(c.from - c.to));
    EXPECT_LT(seen, std::min(half_x, half_y)) << w << " x " << h;
    EXPECT_GT(seen, 0.9f * std::min(half_x, half_y)) << w << " x " << h;
  }
  const auto placed = load_scene_text(R"({"camera": {"from": [0, 0, 9], "to": [0, 0, 0]}, )" + shapes + "}",
                                      "placed.json");
  EXPECT_FALSE(placed->framed.has_value());
  RenderOverrides o;
  o.width = 100;
  o.height = 400;
  apply_overrides(o, *placed);
  EXPECT_EQ(placed->camera.from, Vec3(0, 0, 9));
}

// An extreme aspect ratio puts a framing camera thousands of extents away: beyond the 1e12 scene units that rays can
// start from, it is an error naming the image size (from the command line or from the file's film), not a ray that
// Embree aborts on.
TEST(RenderOptions, AFramingCameraOutOfRangeIsAnError) {
  const std::string big = R"("materials": {"m": {"type": "diffuse"}},
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1e11, "material": "m"}])";
  const auto scene = load_scene_text(R"({"film": {"width": 400, "height": 400}, )" + big + "}", "big.json");
  RenderOverrides o;
  o.width = 1;
  o.height = 16384;
  try {
    apply_overrides(o, *scene);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("1 x 16384 image"), std::string::npos) << e.what();
  }
  try {
    load_scene_text(R"({"film": {"width": 1, "height": 16384}, )" + big + "}", "big.json");
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("the framing camera (for a 1 x 16384 image)"), std::string::npos) << e.what();
  }
}
