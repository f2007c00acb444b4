// run_warptest: verdicts and pictures for a few warps, and the list of names for an unknown one.
// Each run draws 200k samples with the tool's fixed seed at alpha = 0.01 (an exact warp fails 1% of seeds).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>

#include "app/warptest.h"
#include "core/chi2.h"
#include "core/frame.h"
#include "core/image_io.h"
#include "core/warp.h"

namespace lumis {
namespace {

std::filesystem::path temp_dir() {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("lumis_warptest_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::create_directories(dir);
  return dir;
}

void expect_passes_with_picture(const std::string& name, float param) {
  const auto dir = temp_dir();
  const std::string png = (dir / (name + ".png")).string();
  std::ostringstream out;
  EXPECT_EQ(run_warptest(name, param, 200'000, png, out, out), 0) << out.str();
  EXPECT_NE(out.str().find("p-value"), std::string::npos) << out.str();
  ASSERT_TRUE(std::filesystem::exists(png)) << out.str();
  const Image img = read_image(png);
  EXPECT_EQ(img.width, 2 * 80 * 8 + 16);
  EXPECT_EQ(img.height, 40 * 8);
  std::filesystem::remove_all(dir);
}

TEST(Warptest, CosineHemispherePasses) { expect_passes_with_picture("cosine_hemisphere", NAN); }
TEST(Warptest, SphericalCapDefaultAndExplicitParam) {
  expect_passes_with_picture("spherical_cap", NAN);
  expect_passes_with_picture("spherical_cap", 0.2f);
}
TEST(Warptest, GgxHeitzPasses) { expect_passes_with_picture("ggx_heitz", 0.3f); }

TEST(Warptest, UnknownNameListsValidNames) {
  std::ostringstream out, err;
  EXPECT_EQ(run_warptest("no_such_warp", NAN, 1000, "", out, err), 2);
  EXPECT_EQ(out.str(), "");
  for (const std::string& n : warptest_names()) EXPECT_NE(err.str().find(n), std::string::npos) << n;
}

// A parameter outside the warp's domain is a usage error (2), not a failed test (1), and so is one given to a warp
// that takes none; the domain's edges are outside it except alpha = 1.
TEST(Warptest, ParamOutsideTheDomainIsAUsageError) {
  const std::pair<const char*, float> bad[] = {{"spherical_cap", 1.0f},  {"spherical_cap", -1.0f},
                                               {"spherical_cap", 2.0f},  {"ggx_cap", 0.0f},
                                               {"ggx_heitz", -0.3f},     {"ggx_cap", 1.5f},
                                               {"cosine_hemisphere", 0.5f}};
  for (const auto& [name, param] : bad) {
    std::ostringstream out, err;
    EXPECT_EQ(run_warptest(name, param, 1000, "", out, err), 2) << name << " " << param;
    EXPECT_EQ(err.str().rfind("lumis: warptest: ", 0), 0u) << err.str();  // as every other command's messages
  }
  std::ostringstream out, err;
  EXPECT_EQ(run_warptest("ggx_cap", 1.0f, 100'000, "", out, err), 0) << out.str() << err.str();
  // Checked as given, with enough digits to tell the value from the bound, and as the float the warp uses.
  const std::tuple<const char*, double, const char*> near[] = {
      {"ggx_heitz", 1.0000001, "must lie in (0, 1], found 1.0000001\n"},
      {"spherical_cap", 0.99999999, "found 0.99999999, which is 1 as the 32-bit float it is used as"},
      {"ggx_cap", 1e-50, "found 1e-50, which is 0 as the 32-bit float it is used as"}};
  for (const auto& [name, param, says] : near) {
    std::ostringstream o, e;
    EXPECT_EQ(run_warptest(name, param, 100'000, "", o, e), 2) << name << " " << param;
    EXPECT_NE(e.str().find(says), std::string::npos) << e.str();
  }
}

// Alpha may be anywhere in (0, 1]. Lobes much narrower than the cells (alpha 1e-4: all samples in the top row, the
// pdf a near-delta between the quadrature points) used to make exact samplers FAIL; they are binned in stretched
// directions now.
TEST(Warptest, TinyGgxAlphasPass) {
  for (const char* name : {"ggx_heitz", "ggx_cap"})
    for (const float alpha : {1e-3f, 1e-4f, 1e-6f}) {
      std::ostringstream out;
      EXPECT_EQ(run_warptest(name, alpha, 200'000, "", out, out), 0) << name << " " << alpha << "\n" << out.str();
      EXPECT_NE(out.str().find("stretched"), std::string::npos) << out.str();
    }
}

// Stretching keeps the test's power: GGX samples at alpha 1e-4 pass against their own density and fail against the
// density of a lobe 10% wider (one tenth of the lobe's width, all of it within 0.001 rad of the pole).
TEST(Warptest, StretchedCellsStillRejectAWrongLobe) {
  const Vec3 wo{0.70710678f, 0.0f, 0.70710678f};
  const auto ggx = [&](float sample_alpha, float pdf_alpha) {
    return Warp{[=](Vec2 u) -> std::optional<Vec3> {
                  return sample_ggx_vndf(wo, sample_alpha, sample_alpha, u, VndfMethod::SphericalCap2023);
                },
                [=](Vec3 wm) { return double(ggx_vndf_pdf(wo, wm, pdf_alpha, pdf_alpha)); }};
  };
  const auto test = [](const Warp& w) {
    DirectionalTest cfg;
    cfg.samples = 200'000;
    return chi_square_directions(
        [&](Pcg32& rng) {
          const float u0 = rng.next_float(), u1 = rng.next_float();
          return w.sample(Vec2(u0, u1));
        },
        w.pdf, cfg);
  };
  const ChiSquareResult right = test(stretched(ggx(1e-4f, 1e-4f), 3000));
  EXPECT_TRUE(right.passed) << right.message;
  const ChiSquareResult wrong = test(stretched(ggx(1e-4f, 1.1e-4f), 3000));
  EXPECT_FALSE(wrong.passed) << wrong.message;
  // A cap of cos_max 0.999 against the density of one 10% larger in solid angle: in unstretched cells both lie in
  // the top row, which only sees the azimuth.
  const auto cap = [](float sample_cos, float pdf_cos) {
    return Warp{[=](Vec2 u) -> std::optional<Vec3> { return sample_spherical_cap(u, sample_cos); },
                [=](Vec3 w) { return double(spherical_cap_pdf(w, pdf_cos)); }};
  };
  EXPECT_TRUE(test(stretched(cap(0.999f, 0.999f), 20)).passed);
  EXPECT_FALSE(test(stretched(cap(0.999f, 0.9989f), 20)).passed);
}

// Narrow caps are stretched too; a cap so small that float directions cannot place its rim, or a GGX alpha whose peak
// density overflows float, is reported as undecidable (2), not as a failed sampler.
TEST(Warptest, NarrowCapsPassAndUndecidableParamsSaySo) {
  for (const float cos_max : {0.99f, 0.9999f}) {
    std::ostringstream out;
    EXPECT_EQ(run_warptest("spherical_cap", cos_max, 200'000, "", out, out), 0) << cos_max << "\n" << out.str();
    EXPECT_NE(out.str().find("stretched"), std::string::npos) << out.str();
  }
  const std::pair<const char*, float> undecidable[] = {{"spherical_cap", 0.99999f}, {"ggx_heitz", 1e-20f}};
  for (const auto& [name, param] : undecidable) {
    std::ostringstream out, err;
    EXPECT_EQ(run_warptest(name, param, 200'000, "", out, err), 2) << name << " " << param << out.str();
    EXPECT_NE(err.str().find("cannot decide"), std::string::npos) << err.str();
    EXPECT_EQ(out.str(), "");
  }
}

// Too few samples for any verdict is not a failed sampler (1) but a usage error (2) that says how many are needed.
TEST(Warptest, TooFewSamplesToDecideIsAUsageError) {
  std::ostringstream out, err;
  EXPECT_EQ(run_warptest("uniform_sphere", NAN, 1000, "", out, err), 2) << out.str() << err.str();
  EXPECT_NE(err.str().find("cannot decide"), std::string::npos) << err.str();
  const size_t at = err.str().find("use --samples ");
  ASSERT_NE(at, std::string::npos) << err.str();
  EXPECT_NEAR(std::stod(err.str().substr(at + 14)), 16000, 2) << err.str();  // 5 per cell, 3200 equal cells
}

// The picture's path is checked before any sampling: nothing is printed, no statistic computed.
TEST(Warptest, UnwritablePictureIsRefusedBeforeSampling) {
  const auto dir = temp_dir();
  for (const std::string& png : {(dir / "missing" / "w.png").string(), (dir / "w.tif").string(), dir.string()}) {
    std::ostringstream out, err;
    EXPECT_EQ(run_warptest("cosine_hemisphere", NAN, 100'000, png, out, err), 2) << png << ": " << err.str();
    EXPECT_EQ(out.str(), "") << png;
    EXPECT_NE(err.str().find(png), std::string::npos) << err.str();
  }
  std::filesystem::remove_all(dir);
}

// A cosine lobe about an axis off every symmetry of the cells (no two cells expect the same count), with its density.
Warp tilted_cosine() {
  const Frame f = Frame::from_normal(normalize(Vec3(0.3f, 0.5f, 0.8f)));
  return {[=](Vec2 u) -> std::optional<Vec3> { return f.to_world(sample_cosine_hemisphere(u)); },
          [=](Vec3 w) { return std::max(0.0, double(dot(w, f.n))) / kPi; }};
}

// A sampler that does not match its density FAILS with exit code 1, which CI and scripts act on.
TEST(Warptest, AWrongWarpFails) {
  const Warp right = tilted_cosine();
  std::ostringstream out, err;
  EXPECT_EQ(check_warp(right, "tilted", "", 200'000, "", out, err), 0) << out.str() << err.str();
  EXPECT_NE(out.str().find("warptest tilted: 200000 samples in 40 x 80 (cos theta, phi) cells, seed 1"),
            std::string::npos) << out.str();
  const Warp wrong{right.sample, [](Vec3 w) { return double(uniform_hemisphere_pdf(w)); }};
  out.str("");
  EXPECT_EQ(check_warp(wrong, "tilted", "", 200'000, "", out, err), 1) << out.str() << err.str();
  EXPECT_NE(out.str().find("FAILED"), std::string::npos) << out.str();
}

// 70% of the samples in a cap of radius 0.01 rad in the middle of one cell (cos theta in [0, 0.05), phi in
// [0, 2 pi / 80)), the rest uniform over the sphere.
Warp mostly_in_one_cell() {
  const Vec3 centre = normalize(Vec3(std::cos(0.0393f), std::sin(0.0393f), 0.025f));
  const Frame f = Frame::from_normal(centre);
  const float cos_max = std::cos(0.01f);
  return {[=](Vec2 u) -> std::optional<Vec3> {
            if (u.x < 0.7f) return f.to_world(sample_spherical_cap(Vec2(u.x / 0.7f, u.y), cos_max));
            return sample_uniform_sphere(Vec2((u.x - 0.7f) / 0.3f, u.y));
          },
          [=](Vec3 w) { return 0.7 * spherical_cap_pdf(f.to_local(w), cos_max) + 0.3 * uniform_sphere_pdf(); }};
}

// "use --samples N" names the fewest samples that decide: N decides, a tenth fewer does not. The test decides with
// the fullest cell and all the others (pooled) each expecting 5, so a lobe mostly in one cell needs only 5 / 0.3
// samples, and one spread over many cells 5 over its fullest cell's probability.
TEST(Warptest, TheSuggestedSampleCountIsTheFewestThatDecides) {
  for (const auto& [name, w, most] : {std::tuple{"tilted", tilted_cosine(), uint64_t{100'000}},
                                      std::tuple{"one cell", mostly_in_one_cell(), uint64_t{40}}}) {
    std::ostringstream out, err;
    ASSERT_EQ(check_warp(w, name, "", 4, "", out, err), 2) << out.str() << err.str();
    const size_t at = err.str().find("use --samples ");
    ASSERT_NE(at, std::string::npos) << err.str();
    const uint64_t need = std::stoull(err.str().substr(at + 14));
    EXPECT_LE(need, most) << name;
    err.str("");
    EXPECT_NE(check_warp(w, name, "", need, "", out, err), 2) << name << ", " << need << ": " << err.str();
    EXPECT_EQ(check_warp(w, name, "", need * 9 / 10, "", out, err), 2) << name << ", " << need;
  }
}

// The picture: observed counts on the left, expected on the right, cos theta = 1 (the pole) at the top. Samples all
// within a cap about the pole against a uniform density: the left panel is lit in its top rows only, the right one
// evenly.
TEST(Warptest, PictureShowsObservedLeftExpectedRightPoleOnTop) {
  const auto dir = temp_dir();
  const std::string png = (dir / "cap.png").string();
  const Warp w{[](Vec2 u) -> std::optional<Vec3> { return sample_spherical_cap(u, 0.9f); },
               [](Vec3 d) { return double(uniform_hemisphere_pdf(d)); }};
  std::ostringstream out;
  EXPECT_EQ(check_warp(w, "cap", "", 200'000, png, out, out), 1) << out.str();
  const Image img = read_image(png);
  ASSERT_EQ(img.width, 2 * 80 * 8 + 16);
  // Pixel rows 0-7 show cos theta in [0.95, 1], rows 152-159 cos theta in [0, 0.05) (the last above the horizon).
  const int right = 80 * 8 + 16, top = 4, low = 19 * 8 + 4, last = img.height - 4;
  const auto lum = [&](int x, int y) { return img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2); };
  EXPECT_GT(lum(4, top), 0.1f);                    // observed: the cap is in the top row
  EXPECT_EQ(lum(4, low), 0.0f);                    // observed: nothing below the cap
  EXPECT_GT(lum(right + 4, top), 0.0f);            // expected: uniform over the upper hemisphere
  EXPECT_NEAR(lum(right + 4, low), lum(right + 4, top), 0.03f);  // one 8-bit code apart at most
  EXPECT_EQ(lum(right + 4, last), 0.0f);           // expected: nothing below the horizon
  std::filesystem::remove_all(dir);
}

TEST(Warptest, NoPictureWhenPathEmpty) {
  std::ostringstream out;
  EXPECT_EQ(run_warptest("uniform_sphere", NAN, 100'000, "", out, out), 0) << out.str();
  EXPECT_EQ(out.str().find("wrote"), std::string::npos);
}

}  // namespace
}  // namespace lumis
