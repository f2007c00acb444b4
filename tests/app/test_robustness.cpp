// Faults never reach the image: non-finite samples are dropped and counted, the shipped scenes produce none, and
// the renderer is scale invariant (a scene scaled by 1e-11, 1e-3, 1e4 or 1e12, radiance unchanged, renders the same
// image) and translation invariant (moved 1e4 from the origin), whatever floating-point mode its caller is in, a scene
// too small for float arithmetic is a load error, and lights too small for rays to hit are named.
//
// Scale invariance: the default Cornell box at 24x24 pixels, max depth 3, 256 spp, the unscaled render at seed 1
// against each scaled render at seed 2 (independent samples). z-tests on 4x4-pixel block means per channel:
// z = (a - b) / sqrt(var_a + var_b), variances from the films' per-pixel variance of the mean (an over-estimate
// for the stratified sampler, so conservative). Level alpha = 0.01 per scale, Sidak-split over 36 blocks x 3
// channels, so a scale-invariant renderer fails with probability below 1% at any seed pair; the fixed seeds make a
// pass reproducible.
#include <gtest/gtest.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/json_reader.h"
#include "app/scene_error.h"
#include "app/scene_loader.h"
#include "integrators/render.h"
#include "tests/support/render_film.h"
#include "tests/support/render_stats.h"

namespace lumis {
namespace {

namespace fs = std::filesystem;

std::string scenes_dir() { return std::string(LUMIS_SOURCE_DIR) + "/scenes"; }

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

using test::Rendered;

Rendered render_small(Scene& scene, int size, uint32_t spp, uint32_t seed, int max_depth) {
  scene.settings.width = scene.settings.height = size;
  scene.settings.seed = seed;
  scene.settings.max_depth = max_depth;
  return test::render_film(scene, spp);
}

bool film_is_finite(const Film& film) {
  for (float v : film.to_image().data)
    if (!std::isfinite(v)) return false;
  return true;
}

TEST(Robustness, ShippedScenesDropNoSamples) {
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(scenes_dir())) {
    if (entry.path().extension() != ".json") continue;
    auto scene = load_scene(entry.path().string());
    const Rendered r = render_small(*scene, 16, 4, 1, 8);
    EXPECT_EQ(r.stats.dropped, 0u) << entry.path();
    EXPECT_EQ(r.film.dropped(), 0u) << entry.path();
    EXPECT_TRUE(film_is_finite(r.film)) << entry.path();
    ++scenes;
  }
  EXPECT_GE(scenes, 4);
}

// Radiance near the float maximum on a surface that also reflects a light of the same radiance: emitted plus
// reflected overflows to infinity in float. Those samples must be dropped, counted, and absent from the image.
// (The variance channel may still overflow: a finite sample above sqrt(FLT_MAX) has a square beyond float.)
TEST(Robustness, OverflowingSamplesAreDroppedAndCounted) {
  const std::string text = R"({
    "camera": {"from": [0, 1, 3], "to": [0, 0, 0]},
    "materials": {"white": {"type": "diffuse", "albedo": [0.9, 0.9, 0.9]}},
    "shapes": [{"type": "quad", "origin": [-2, 0, 2], "edge_u": [4, 0, 0], "edge_v": [0, 0, -4], "material": "white",
                "emission": [3e38, 3e38, 3e38]}],
    "lights": [{"type": "sphere", "center": [0, 0.3, 0], "radius": 0.2, "radiance": [3e38, 3e38, 3e38]}]
  })";
  auto scene = load_scene_text(text, scenes_dir() + "/overflow.json");
  constexpr int kSize = 8;
  constexpr uint32_t kSpp = 16;
  const Rendered r = render_small(*scene, kSize, kSpp, 1, 2);
  EXPECT_GT(r.stats.dropped, 0u);
  EXPECT_EQ(r.stats.dropped, r.film.dropped());
  uint64_t kept = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      kept += r.film.count(x, y);
      EXPECT_TRUE(is_finite(r.film.mean(x, y))) << "pixel " << x << ", " << y;
    }
  EXPECT_EQ(kept + r.stats.dropped, uint64_t(kSize) * kSize * kSpp) << "each sample is kept or counted as dropped";
}

// Multiply every length of the Cornell-box scene by `k` (camera, shape and light positions, edges, radii), then
// move every position by `shift`.
std::string moved_cornell(float k, Vec3 shift = {}) {
  Json doc = parse_json_text(read_file(scenes_dir() + "/cornell-sphere.json"), "cornell-sphere.json");
  auto scale_vec = [k](Json& v, Vec3 add) {
    for (int i = 0; i < 3; ++i) v[i] = v[i].get<double>() * k + double(add[i]);
  };
  scale_vec(doc["camera"]["from"], shift);
  scale_vec(doc["camera"]["to"], shift);
  for (const char* section : {"shapes", "lights"})
    for (auto& s : doc[section]) {
      for (const char* key : {"center", "origin"})
        if (s.contains(key)) scale_vec(s[key], shift);
      for (const char* key : {"edge_u", "edge_v"})
        if (s.contains(key)) scale_vec(s[key], {});
      if (s.contains("radius")) s["radius"] = s["radius"].get<double>() * k;
    }
  return doc.dump();
}

constexpr int kSize = 24, kBlock = 4, kDepth = 3;
constexpr uint32_t kSpp = 256;

// Two renders of kSize x kSize pixels agree: block z-tests, as the file's comment says.
void expect_same(const Rendered& a, const Rendered& b, const std::string& what) {
  EXPECT_EQ(b.stats.dropped, 0u) << what;
  const int nb = kSize / kBlock;
  const double z_max = test::sidak_z(0.01, nb * nb * 3.0);
  int rejected = 0;
  double worst = 0;
  std::string where;
  for (int by = 0; by < nb; ++by)
    for (int bx = 0; bx < nb; ++bx) {
      auto in_block = [&](int x, int y) { return x / kBlock == bx && y / kBlock == by; };
      const test::RegionMean ra = test::region_mean(a.film, in_block), rb = test::region_mean(b.film, in_block);
      for (int c = 0; c < 3; ++c) {
        const double sd = std::sqrt(ra.var[c] + rb.var[c]), diff = std::abs(ra.mean[c] - rb.mean[c]);
        const double z = sd > 0 ? diff / sd : (diff > 1e-6 ? INFINITY : 0);
        if (z > worst) {
          worst = z;
          where = "block (" + std::to_string(bx) + ", " + std::to_string(by) + ") channel " + std::to_string(c) +
                  ": first " + std::to_string(ra.mean[c]) + ", second " + std::to_string(rb.mean[c]);
        }
        if (z > z_max) ++rejected;
      }
    }
  EXPECT_EQ(rejected, 0) << what << ": " << rejected << " block-channels differ (largest z " << worst
                         << " at " << where << ", limit " << z_max << ")";
}

void expect_invariant(float k, Vec3 shift = {}) {
  auto base = load_scene(scenes_dir() + "/cornell-sphere.json");
  auto moved = load_scene_text(moved_cornell(k, shift), scenes_dir() + "/cornell-moved.json");
  const Rendered a = render_small(*base, kSize, kSpp, 1, kDepth);
  const Rendered b = render_small(*moved, kSize, kSpp, 2, kDepth);
  expect_same(a, b, "scale " + std::to_string(k) + ", shift (" + std::to_string(shift.x) + ", " +
                        std::to_string(shift.y) + ", " + std::to_string(shift.z) + ")");
}

TEST(Robustness, ScaleInvarianceSmall) { expect_invariant(1e-3f); }
TEST(Robustness, ScaleInvarianceLarge) { expect_invariant(1e4f); }
// 2e11 (the box reaches 4e11 and the camera 8e11, within the 1e12 limit): squared lengths of cross products
// (triangle normals, quad areas) overflow float; they are rescaled.
TEST(Robustness, ScaleInvarianceHuge) { expect_invariant(2e11f); }
// 1e-11: Embree's barycentrics are wrong on triangles this small (its reciprocal clamps at 1e-18); recomputed.
TEST(Robustness, ScaleInvarianceTiny) { expect_invariant(1e-11f); }

// Far from the origin: the box moved 1e4 units away, where a float's spacing is 1e-3. Rays leave surfaces from
// points moved off them by the hit's error bound, 8 units in the last place of its coordinates (5e-3 here); at 64,
// the bound until stop 59, they were moved 0.04, 2 % of the box, and the image failed this test (rejected blocks).
TEST(Robustness, TranslationInvariance) { expect_invariant(1, {1e4f, -6e3f, 8e3f}); }

// 1e5 from the origin, where a float's spacing is 8e-3, the box's sphere light hangs 0.1 below the ceiling. A shadow
// ray stops short of its light point by that point's error bound; taken from the receiver's and the light's
// coordinates together (0.095 there, up to 0.165 along a diagonal normal, until stop 59) it let rays toward the top of
// the light end beyond the ceiling, which shadowed them: `light` read 0.790 against 0.833 for `bsdf`. Cap samples
// (p + t wi) now take theirs from the receiver and the distance only. `light` and `bsdf` must agree (block z-tests).
TEST(Robustness, VariantsAgreeFarFromTheOrigin) {
  auto scene = load_scene_text(moved_cornell(1, {1e5f, -1e5f, 1e5f}), scenes_dir() + "/cornell-far.json");
  scene->settings.integrator = "light";
  const Rendered a = render_small(*scene, kSize, kSpp, 1, kDepth);
  scene->settings.integrator = "bsdf";
  const Rendered b = render_small(*scene, kSize, kSpp, 2, kDepth);
  expect_same(a, b, "light against bsdf, the box moved by (1e5, -1e5, 1e5)");
}

// The box at (1e5, -1e5, 1e5) with its sphere light replaced by `shapes` (positions relative to the box), and a black
// material; `light` against `bsdf`, as above.
void expect_far_light_agrees(Json shapes, const std::string& what) {
  const Vec3 far{1e5f, -1e5f, 1e5f};
  Json doc = parse_json_text(moved_cornell(1, far), "cornell-far.json");
  doc["lights"] = Json::array();
  doc["materials"]["black"] = {{"type", "diffuse"}, {"albedo", {0, 0, 0}}};
  const auto move = [&far](Json& v) {
    for (int i = 0; i < 3; ++i) v[i] = v[i].get<double>() + double(far[i]);
  };
  for (Json& s : shapes) {
    if (s.contains("origin")) move(s["origin"]);
    if (s.contains("positions"))
      for (Json& v : s["positions"]) move(v);
    doc["shapes"].push_back(s);
  }
  auto scene = load_scene_text(doc.dump(), scenes_dir() + "/cornell-far.json");
  scene->settings.integrator = "light";
  const Rendered a = render_small(*scene, kSize, kSpp, 1, kDepth);
  scene->settings.integrator = "bsdf";
  const Rendered b = render_small(*scene, kSize, kSpp, 2, kDepth);
  expect_same(a, b, "light against bsdf, " + what + ", the box moved by (1e5, -1e5, 1e5)");
}

// A mesh light: a sphere of 24 x 12 facets, radius 0.2, its top 0.05 below the ceiling. Until stop 60 a shadow ray
// ended at its light point moved off the light along the facet's normal, by a bound from the receiver's coordinates
// and three times the triangle's (0.19 here): toward facets near the top of the sphere's outline it ended beyond the
// ceiling, which shadowed it. A shadow ray now ends short along itself, inside the segment it stands for.
TEST(Robustness, MeshLightAgreesFarFromTheOrigin) {
  constexpr int kAround = 24, kDown = 12;
  constexpr double kPiD = 3.14159265358979323846, kR = 0.2;
  Json positions = Json::array(), indices = Json::array();
  positions.push_back({0, 1.75 + kR, 0});
  for (int i = 1; i < kDown; ++i)
    for (int j = 0; j < kAround; ++j) {
      const double theta = kPiD * i / kDown, phi = 2 * kPiD * j / kAround;
      positions.push_back({kR * std::sin(theta) * std::cos(phi), 1.75 + kR * std::cos(theta),
                           kR * std::sin(theta) * std::sin(phi)});
    }
  positions.push_back({0, 1.75 - kR, 0});
  const int bottom = 1 + (kDown - 1) * kAround;
  const auto ring = [](int i, int j) { return 1 + (i - 1) * kAround + (j % kAround); };
  for (int j = 0; j < kAround; ++j) {  // counter-clockwise seen from outside
    for (int k : {0, ring(1, j + 1), ring(1, j)}) indices.push_back(k);
    for (int i = 1; i + 1 < kDown; ++i)
      for (int k : {ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)})
        indices.push_back(k);
    for (int k : {bottom, ring(kDown - 1, j), ring(kDown - 1, j + 1)}) indices.push_back(k);
  }
  Json sphere = {{"type", "mesh"}, {"material", "white"}, {"emission", {25, 25, 25}}};
  sphere["positions"] = positions;
  sphere["indices"] = indices;
  expect_far_light_agrees(Json::array({sphere}), "a mesh sphere light");
}

// A panel light 1.8 wide, 0.1 below the ceiling, and a black plate 0.07 under half of it: a quad light, and the same
// square as a mesh light, each sampled by solid angle and by area. A sampled point's bound took the receiver's
// coordinates and the light's together until stop 60 (0.095 for the quad, 0.19 for the mesh; a mesh's area samples
// 0.143 from three times its corners): shadow rays ended short of the plate and `light` lit the room through it.
// Solid-angle samples (p + t wi) now take the receiver and the distance, area samples the light's coordinates and
// the distance, once each (0.048).
TEST(Robustness, PanelLightsAgreeFarFromTheOrigin) {
  const Json plate = {{"type", "quad"}, {"origin", {-1, 1.83, -1}}, {"edge_u", {1, 0, 0}}, {"edge_v", {0, 0, 2}},
                      {"material", "black"}};
  const Json quad = {{"type", "quad"}, {"origin", {-0.9, 1.9, -0.9}}, {"edge_u", {1.8, 0, 0}},
                     {"edge_v", {0, 0, 1.8}}, {"material", "white"}, {"emission", {5, 5, 5}}};
  const Json mesh = {{"type", "mesh"}, {"material", "white"}, {"emission", {5, 5, 5}},
                     {"positions", {{-0.9, 1.9, -0.9}, {0.9, 1.9, -0.9}, {0.9, 1.9, 0.9}, {-0.9, 1.9, 0.9}}},
                     {"indices", {0, 1, 2, 0, 2, 3}}};  // facing down
  for (const char* sampling : {"solid angle", "area"})
    for (Json light : {quad, mesh}) {
      if (sampling[0] == 'a') light["sampling"] = "area";
      expect_far_light_agrees(Json::array({light, plate}), std::string("a ") + light["type"].get<std::string>() +
                                                               " light over a plate, sampled by " + sampling);
    }
}

// render() runs every tile under the floating-point mode it sets (TracingFloatMode, core/embree_util.h), not under
// its caller's, and gives the caller's back. A TBB arena runs its tasks in the mode of the thread that initialized
// it: the flush-to-zero mode render() used to set from a thread observer reached no task of a process's first
// render and every task of its later ones (compare's second variant, bench's repetitions): with today's error
// bounds those rendered the 1e-11 box 46 % too dark. Same image, bit for bit, whichever mode the caller is in: the
// default, or flush-to-zero with rounding toward zero.
TEST(Robustness, ImageDoesNotDependOnTheCallersFloatMode) {
  auto scene = load_scene_text(moved_cornell(1e-11f), scenes_dir() + "/cornell-tiny.json");
  const unsigned saved = _mm_getcsr();
  const unsigned odd = 0x1F80u | _MM_FLUSH_ZERO_ON | _MM_DENORMALS_ZERO_ON | _MM_ROUND_TOWARD_ZERO;
  _mm_setcsr(0x1F80u);
  const Rendered a = render_small(*scene, 16, 16, 1, 3);
  EXPECT_EQ(_mm_getcsr() & ~0x3Fu, 0x1F80u);
  _mm_setcsr(odd);
  const Rendered b = render_small(*scene, 16, 16, 1, 3);
  const unsigned after = _mm_getcsr();
  _mm_setcsr(saved);
  EXPECT_EQ(after & ~0x3Fu, odd) << "the caller's mode is given back (the low 6 bits are exception flags)";
  const std::vector<float> da = a.film.to_image().data, db = b.film.to_image().data;
  ASSERT_EQ(da.size(), db.size());
  size_t differ = 0;
  for (size_t i = 0; i < da.size(); ++i) differ += std::bit_cast<uint32_t>(da[i]) != std::bit_cast<uint32_t>(db[i]);
  EXPECT_EQ(differ, 0u) << "of " << da.size() << " values";
}

// Below the smallest size lumis can render, the loader says so instead of rendering a wrong image.
TEST(Robustness, TooSmallSceneIsAClearError) {
  try {
    load_scene_text(moved_cornell(1e-14f), scenes_dir() + "/cornell-tiny.json");
    FAIL() << "a scene 2e-14 units across loaded";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("scale the scene up"), std::string::npos) << e.what();
  }
}

// Lights smaller than 1e-5 (kMinLightSize) of the scene's span around them are named in warnings at the JSON pointer
// of their size (render and compare print them for uniform, bsdf and mis: tests/cli/usage.sh). The span from the
// light at (0, 2, -1.5) is 4.61 (to the camera), so a radius of 4e-5 is named and 6e-5 is not; the quad light's
// centre sees 3.775 (a corner of the floor); a quad's distance from the origin counts too (1000: 0.005 is named
// there, a sphere of that radius is not).
TEST(Robustness, LightsTooSmallToHitAreNamed) {
  const std::string near = R"({"camera": {"from": [0, 3, 3], "to": [0, 0, 0]}, "materials": {"m": {"type": "diffuse"}},
    "shapes": [{"type": "quad", "origin": [-2, 0, 2], "edge_u": [4, 0, 0], "edge_v": [0, 0, -4], "material": "m"},
               {"type": "sphere", "center": [1, 1, 0], "radius": 1e-6, "material": "m", "emission": [1, 1, 1]},
               {"type": "quad", "origin": [0, 1, 0], "edge_u": [0.01, 0, 0], "edge_v": [0, 0, 1e-6], "material": "m",
                "emission": [1, 1, 1]}],
    "lights": [{"type": "sphere", "center": [0, 2, -1.5], "radius": 4e-5, "radiance": [1, 1, 1]},
               {"type": "sphere", "center": [0, 2, -1.5], "radius": 6e-5, "radiance": [1, 1, 1]},
               {"type": "quad", "origin": [0, 2, 0], "edge_u": [3e-5, 0, 0], "edge_v": [0, 0, 1],
                "radiance": [1, 1, 1]},
               {"type": "environment", "radiance": [1, 1, 1]}]})";
  const auto scene = load_scene_text(near, "near.json");
  const std::vector<std::string> expected = {
      "near.json:/shapes/1/radius: warning: the emitting sphere's radius, 1e-06, is less than 1e-05 times the span "
      "of the scene around it, 3.742: rays miss or hit a light this small as float rounding falls, so uniform, bsdf "
      "and mis can render it too dark or with fireflies (light and nee_mis sample it directly and are not affected)",
      "near.json:/shapes/2/edge_v: warning: the emitting quad's edge_v, 1e-06,",
      "near.json:/lights/0/radius: warning: the sphere light's radius, 4e-05, is less than 1e-05 times the span of "
      "the scene around it, 4.61:",
      "near.json:/lights/2/edge_u: warning: the quad light's edge_u, 3e-05, is less than 1e-05 times the span of "
      "the scene around it, 3.775:"};
  ASSERT_EQ(scene->small_lights.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i)
    EXPECT_EQ(scene->small_lights[i].substr(0, expected[i].size()), expected[i]) << scene->small_lights[i];

  const std::string far = R"({"camera": {"from": [1000, 3, 3], "to": [1000, 0, 0]},
    "materials": {"m": {"type": "diffuse"}},
    "shapes": [{"type": "quad", "origin": [998, 0, 2], "edge_u": [4, 0, 0], "edge_v": [0, 0, -4], "material": "m"}],
    "lights": [{"type": "sphere", "center": [1000, 2, 0], "radius": 0.005, "radiance": [1, 1, 1]},
               {"type": "quad", "origin": [1000, 2, 0], "edge_u": [0.005, 0, 0], "edge_v": [0, 0, 0.005],
                "radiance": [1, 1, 1]}]})";
  const auto far_scene = load_scene_text(far, "far.json");
  ASSERT_EQ(far_scene->small_lights.size(), 1u);
  const std::string far_expected =
      "far.json:/lights/1/edge_u: warning: the quad light's edge_u, 0.005, is less than 1e-05 times the distance "
      "from the origin to its centre, 1000:";
  EXPECT_EQ(far_scene->small_lights[0].substr(0, far_expected.size()), far_expected);
}

}  // namespace
}  // namespace lumis
