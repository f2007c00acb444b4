// run_warptest: verdicts and pictures for a few warps, and the list of names for an unknown one.
// Each run draws 200k samples with the tool's fixed seed at alpha = 0.01 (an exact warp fails 1% of seeds).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "app/warptest.h"
#include "core/image_io.h"

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
    EXPECT_NE(err.str().find("warptest:"), std::string::npos) << err.str();
  }
  std::ostringstream out, err;
  EXPECT_EQ(run_warptest("ggx_cap", 1.0f, 100'000, "", out, err), 0) << out.str() << err.str();
}

TEST(Warptest, NoPictureWhenPathEmpty) {
  std::ostringstream out;
  EXPECT_EQ(run_warptest("uniform_sphere", NAN, 100'000, "", out, out), 0) << out.str();
  EXPECT_EQ(out.str().find("wrote"), std::string::npos);
}

}  // namespace
}  // namespace lumis
