// Every integrator variant (and `nee_mis` with the power heuristic) against scenes with closed-form answers:
//  - white furnace: diffuse sphere (albedo 0.8) in a uniform environment (radiance 1): 0.8 on the sphere, 1 off it;
//  - glossy furnace: the same with the two-lobe glTF BSDF, whose value (its directional albedo) has no closed form:
//    every variant against the `bsdf` variant's image;
//  - closed sphere of albedo 0.5 emitting 0.5 inside: radiance 1 everywhere (pbrt-v4's analytic test);
//  - sphere light (radius r, radiance L, height h) over a diffuse plane (albedo rho), direct lighting only: the
//    point straight below has radiance rho L (r/h)^2 (at the height rays leave from: h minus their offset); also
//    for `light` and `nee_mis` with radii down to 1e-15 of the distance, the light off to the side;
//  - a large emitting square (radiance L) over a diffuse plane, half of it cut out (alphaMode MASK) along a diagonal
//    through the zenith, direct lighting only: by symmetry half of pi L reaches the point below, radiance rho L / 2.
// Also the depth AOV against the distance to a plane.
// Each check is a z-test of a region mean against the exact value, using the film's own variance estimate.
// Level: alpha = 0.01 for the whole file, Sidak-split over all 124 z-tests (41 regions x 3 channels, and the
// silhouette's coverage), so the file fails by chance with probability below 1% for a correct renderer at any
// seed; seeds are fixed, so a pass is reproducible. Bias of the truncated series (max depth) is below 1e-6 and
// included in the expectation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "integrators/integrator.h"
#include "integrators/render.h"
#include "tests/support/render_film.h"
#include "tests/support/render_stats.h"

namespace lumis {
namespace {

constexpr double kAlpha = 0.01;

Camera make_camera(Vec3 from, Vec3 to, float fov) {
  Camera c;
  c.from = from;
  c.to = to;
  c.fov_y_degrees = fov;
  return c;
}
constexpr int kRegionTests = 124;  // 41 regions x 3 channels + 1 (Bonferroni-safe under dependence)

struct Case {
  std::string integrator;
  SamplerType sampler;
  MisHeuristic heuristic = MisHeuristic::Balance;
  /// The variant's name, and the heuristic when it is not the lecture's balance heuristic.
  std::string label() const { return heuristic == MisHeuristic::Power ? integrator + " (power)" : integrator; }
};

// Every variant, and `nee_mis` once more with the power heuristic (--mis-heuristic power).
std::vector<Case> all_variants() {
  return {{"uniform", SamplerType::Independent},
          {"bsdf", SamplerType::Stratified},
          {"light", SamplerType::Sobol},
          {"mis", SamplerType::Independent},
          {"nee_mis", SamplerType::Stratified},
          {"nee_mis", SamplerType::Independent, MisHeuristic::Power}};
}

Film render_scene(Scene& scene, const Case& c, uint32_t spp) {
  scene.settings.integrator = c.integrator;
  scene.settings.sampler = c.sampler;
  scene.settings.mis_heuristic = c.heuristic;
  return test::render_film(scene, spp).film;
}

void expect_region(const test::RegionMean& r, double expected, const std::string& what) {
  ASSERT_GT(r.pixels, 0) << what;
  const double z_max = test::sidak_z(kAlpha, kRegionTests);
  for (int c = 0; c < 3; ++c) {
    // Zero-variance estimators (cosine sampling in the furnace) are exact up to float rounding of the inputs
    // (0.8f != 0.8): allow 1e-6 relative on top of the statistical bound.
    const double sd = std::sqrt(r.var[c]);
    const double err = std::abs(r.mean[c] - expected);
    EXPECT_LT(err, z_max * sd + 1e-6 * expected)
        << what << ": mean " << r.mean[c] << " expected " << expected << " sd " << sd << " z " << err / sd;
  }
}

// --- White furnace ---------------------------------------------------------------------------------------------

std::unique_ptr<Scene> furnace_scene(std::unique_ptr<Material> material = make_diffuse_material(Color(0.8f))) {
  auto s = std::make_unique<Scene>();
  s->materials.push_back(std::move(material));
  s->geometry.add_sphere(Sphere{{0, 0, 0}, 1, 0, -1});
  s->lights.push_back(make_constant_environment(Color(1)));
  s->environment = 0;
  s->camera = make_camera({0, 0, 4}, {0, 0, 0}, 40);
  s->settings.width = s->settings.height = 24;
  s->settings.max_depth = 8;
  s->settings.rr_depth = 0;
  s->finalize();
  return s;
}

// Whether a ray (from outside) meets the unit sphere at the origin.
bool sees_unit_sphere(const Ray& r) {
  const float b = dot(r.o, r.d), c = dot(r.o, r.o) - 1;
  return b * b - c > 0;
}

// Classify pixels whose whole footprint is on (1) or off (0) the unit sphere; -1 for silhouette pixels.
int footprint(const Scene& scene, int x, int y) {
  Camera cam = scene.camera;
  cam.prepare(scene.settings.width, scene.settings.height);
  int on = 0;
  for (int k = 0; k < 4; ++k) {
    on += sees_unit_sphere(cam.generate_ray({static_cast<float>(x + (k & 1)), static_cast<float>(y + (k >> 1))}));
  }
  return on == 4 ? 1 : (on == 0 ? 0 : -1);
}

TEST(IntegratorAnalytic, WhiteFurnace) {
  auto scene = furnace_scene();
  for (const Case& c : all_variants()) {
    const Film film = render_scene(*scene, c, 64);
    expect_region(test::region_mean(film, [&](int x, int y) { return footprint(*scene, x, y) == 1; }), 0.8,
                  c.label() + " furnace sphere");
    expect_region(test::region_mean(film, [&](int x, int y) { return footprint(*scene, x, y) == 0; }), 1.0,
                  c.label() + " furnace background");
  }
}

TEST(IntegratorAnalytic, FurnaceSilhouetteFollowsPixelCoverage) {
  // Box filter: a pixel's value is the mean over its whole square. In the furnace `bsdf` is exact per sample
  // (0.8 on the sphere, 1 off it), so a silhouette pixel's mean is 1 - 0.2 c, with c the fraction of its square
  // that sees the sphere (here by a 64 x 64 grid of rays per pixel: against a 512 x 512 grid the region mean's
  // expectation moved by 1.2e-5, well under the 1e-3 allowed); its samples are Bernoulli, so the film's variance
  // estimate applies. Samples all through the pixel centre would give 0.8 or 1.
  auto scene = furnace_scene();
  const Film film = render_scene(*scene, {"bsdf", SamplerType::Stratified}, 256);
  Camera cam = scene->camera;
  cam.prepare(scene->settings.width, scene->settings.height);
  double mean = 0, expected = 0, var = 0;
  int n = 0;
  for (int y = 0; y < scene->settings.height; ++y)
    for (int x = 0; x < scene->settings.width; ++x) {
      if (footprint(*scene, x, y) != -1) continue;
      int hits = 0;
      for (int k = 0; k < 64 * 64; ++k)
        hits += sees_unit_sphere(cam.generate_ray({x + ((k % 64) + 0.5f) / 64, y + ((k / 64) + 0.5f) / 64}));
      expected += 1 - 0.2 * hits / (64.0 * 64);
      mean += film.mean(x, y).x;
      var += film.variance_of_mean(x, y).x;
      ++n;
    }
  ASSERT_GT(n, 20);
  const double sd = std::sqrt(var) / n;
  mean /= n;
  expected /= n;
  EXPECT_LT(std::abs(mean - expected), test::sidak_z(kAlpha, kRegionTests) * sd + 1e-3)
      << "silhouette mean " << mean << " expected " << expected << " sd " << sd;
}

// --- Glossy furnace ---------------------------------------------------------------------------------------------

TEST(IntegratorAnalytic, GlossyFurnaceAgreement) {
  // A white dielectric (base 0.8, roughness 0.5): a Lambert lobe under a GGX lobe, each sampled with probability
  // 1/2. Light sampling and the one-sample combination must get that mixture density right to agree with pure
  // BSDF sampling. Two-sample z-test of the sphere's region mean against a 256-spp `bsdf` reference.
  PbrParams p;
  p.base_color = Color(0.8f);
  p.metallic = 0;
  p.roughness = 0.5f;
  auto scene = furnace_scene(make_pbr_material(p));
  const auto on_sphere = [&](int x, int y) { return footprint(*scene, x, y) == 1; };
  const test::RegionMean ref =
      test::region_mean(render_scene(*scene, {"bsdf", SamplerType::Stratified}, 256), on_sphere);
  const double z_max = test::sidak_z(kAlpha, kRegionTests);
  for (const Case& c : all_variants()) {
    if (c.integrator == "bsdf") continue;
    const test::RegionMean r = test::region_mean(render_scene(*scene, c, 64), on_sphere);
    for (int k = 0; k < 3; ++k) {
      const double sd = std::sqrt(r.var[k] + ref.var[k]), err = std::abs(r.mean[k] - ref.mean[k]);
      EXPECT_LT(err, z_max * sd) << c.label() << " glossy furnace: mean " << r.mean[k] << " reference "
                                 << ref.mean[k] << " sd " << sd << " z " << err / sd;
    }
  }
}

// --- Closed emitting sphere -------------------------------------------------------------------------------------

TriangleMesh sphere_mesh(float radius, int n_theta, int n_phi) {
  TriangleMesh m;
  for (int i = 0; i <= n_theta; ++i)
    for (int j = 0; j <= n_phi; ++j) {
      const float th = kPi * i / n_theta, ph = 2 * kPi * j / n_phi;
      m.positions.push_back(Vec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)) * radius);
    }
  for (int i = 0; i < n_theta; ++i)
    for (int j = 0; j < n_phi; ++j) {
      const uint32_t a = i * (n_phi + 1) + j, b = a + 1, c = a + n_phi + 1, d = c + 1;
      if (i > 0) m.indices.insert(m.indices.end(), {a, b, c});
      if (i < n_theta - 1) m.indices.insert(m.indices.end(), {b, d, c});
    }
  return m;
}

TEST(IntegratorAnalytic, ClosedEmittingSphere) {
  Scene scene;
  scene.materials.push_back(make_diffuse_material(Color(0.5f)));
  TriangleMesh m = sphere_mesh(1, 12, 24);
  m.material = 0;
  m.light = 0;
  scene.lights.push_back(make_mesh_light(m, Color(0.5f), std::nullopt, /*two_sided=*/true));
  scene.geometry.add_mesh(std::move(m));
  scene.camera = make_camera({0, 0, 0.3f}, {0, 0, -1}, 60);
  scene.settings.width = scene.settings.height = 16;
  scene.settings.max_depth = 24;  // truncation bias 0.5^25 < 1e-7
  scene.settings.rr_depth = 3;
  scene.finalize();
  for (const Case& c : all_variants()) {
    const Film film = render_scene(scene, c, 32);
    expect_region(test::region_mean(film, [](int, int) { return true; }), 1.0, c.label() + " closed sphere");
  }
}

// --- Sphere light over a plane, direct lighting ----------------------------------------------------------------

// A sphere light (centre c, radius r, radiance L) over a diffuse plane of albedo rho, seen through a narrow field of
// view at the origin.
constexpr float kPlaneHalfSide = 500, kRho = 0.6f;
void build_sphere_light_over_plane(Scene& scene, Vec3 c, float r, Color radiance) {
  scene.materials.push_back(make_diffuse_material(Color(kRho)));
  TriangleMesh plane;
  const float e = kPlaneHalfSide;
  plane.positions = {{-e, 0, -e}, {-e, 0, e}, {e, 0, e}, {e, 0, -e}};  // counter-clockwise seen from +y
  plane.indices = {0, 1, 2, 0, 2, 3};
  plane.material = 0;
  scene.geometry.add_mesh(std::move(plane));
  scene.lights.push_back(make_sphere_light(c, r, radiance));
  scene.geometry.add_sphere(Sphere{c, r, -1, 0});
  // Look at the origin from the side, through a very narrow field of view: the footprint is about 1e-4 wide.
  scene.camera = make_camera({2, 1, 0.5f}, {0, 0, 0}, 0.005f);
  scene.settings.width = scene.settings.height = 4;
  scene.settings.max_depth = 1;
  scene.finalize();
}
// Every ray from the plane, and every light sample (light_context, integrators/path_vertex.h), starts at the hit
// point offset by its error bound, d = e kErrorScale = 2.4e-4 above the plane: the radiance there is
// rho / pi x pi L (r / D)^2 cos = rho L r^2 (c.y - d) / D^3, D the distance from there to c; below a light at height
// 1 that is 0.048 % above the value on the plane, which `light` and `nee_mis` resolve (z = 13 and 6 against it).
double radiance_at_origin(Vec3 c, double r, double radiance) {
  const double d = double(kPlaneHalfSide) * kErrorScale, h = c.y - d;
  const double dist = std::sqrt(double(c.x) * c.x + h * h + double(c.z) * c.z);
  return kRho * radiance * r * r * h / (dist * dist * dist);
}

TEST(IntegratorAnalytic, SphereLightOverPlane) {
  const float r = 0.25f;
  const Color radiance(8.0f);
  Scene scene;
  build_sphere_light_over_plane(scene, {0, 1, 0}, r, radiance);
  const double expected = radiance_at_origin({0, 1, 0}, r, radiance.x);
  for (const Case& c : all_variants()) {
    const uint32_t spp = c.integrator == "uniform" ? 20000 : 4000;
    const Film film = render_scene(scene, c, spp);
    expect_region(test::region_mean(film, [](int, int) { return true; }), expected,
                  c.label() + " plane below light");
  }
}

// The same with spheres 1e4 to 1e15 times smaller than their distance, off to the side, radiance scaled by 1 / r^2:
// `light` and `nee_mis` sample the cap and get it, whether or not floats resolve the sphere. The samples' normals used
// to be (point - centre) / r, of any length and direction there, and the shadow rays' ends, offset along them, went
// astray (8 times too dark at 1e-10). The variants that must hit a light to see it (uniform, bsdf, mis) cannot below
// ~1e-6 of the distance, where Embree's sphere test rounds; docs/lights.md says so.
TEST(IntegratorAnalytic, TinySphereLightsOverPlane) {
  const Vec3 c{0.3f, 1, -0.2f};
  for (float r : {1e-4f, 1e-8f, 1e-15f}) {
    const Color radiance(8.0f * (0.25f / r) * (0.25f / r));
    Scene scene;
    build_sphere_light_over_plane(scene, c, r, radiance);
    const double expected = radiance_at_origin(c, r, radiance.x);
    char what[64];
    std::snprintf(what, sizeof what, " plane near a light of radius %g", r);
    for (const Case& c : {Case{"light", SamplerType::Sobol}, Case{"nee_mis", SamplerType::Stratified}}) {
      const Film film = render_scene(scene, c, 64);
      expect_region(test::region_mean(film, [](int, int) { return true; }), expected, c.label() + what);
    }
  }
}

// --- Depth AOV -------------------------------------------------------------------------------------------------

// The Z channel is the first hit's distance from the camera's position, also when camera rays start at a near clip
// distance (glTF's znear): a plane 2 units in front of a camera with near clip 0.5 reads 2, not 1.5. Deterministic
// (a 0.01-degree field of view: every ray within 1e-8 of the axis).
TEST(IntegratorAnalytic, DepthIsTheDistanceFromTheCamera) {
  Scene scene;
  scene.materials.push_back(make_diffuse_material(Color(0.5f)));
  TriangleMesh plane;
  plane.positions = {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};  // counter-clockwise seen from +z
  plane.indices = {0, 1, 2, 0, 2, 3};
  plane.material = 0;
  scene.geometry.add_mesh(std::move(plane));
  scene.lights.push_back(make_constant_environment(Color(1)));
  scene.environment = 0;
  scene.camera = make_camera({0, 0, 2}, {0, 0, 0}, 0.01f);
  scene.camera.near_clip = 0.5f;
  scene.settings.width = scene.settings.height = 2;
  scene.settings.integrator = "nee_mis";
  scene.finalize();
  FilmOptions aovs;
  aovs.depth = true;
  const Image img = test::render_film(scene, 4, {}, aovs).film.to_image();
  int z = -1;
  for (int c = 0; c < img.channels; ++c)
    if (img.channel_names[c] == "Z") z = c;
  ASSERT_GE(z, 0);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) EXPECT_NEAR(img.at(x, y, z), 2.0f, 1e-5f) << x << ", " << y;
}

// --- Half-cut-out square light over a plane, direct lighting -----------------------------------------------------

// A cut-out emits nothing: rays pass through it, and light samples that land there must be empty. The square
// (half-side 500 at height 1, facing down) is split along the diagonal x = z, whose plane holds the normal at the
// origin, so each half sends exactly half of the square's irradiance there; the square's own is pi L (1 - 2e-6).
TEST(IntegratorAnalytic, CutOutHalfOfASquareLight) {
  const float e = 500, rho = 0.6f;
  Scene scene;
  scene.materials.push_back(make_diffuse_material(Color(rho)));
  TriangleMesh plane;
  plane.positions = {{-e, 0, -e}, {-e, 0, e}, {e, 0, e}, {e, 0, -e}};  // counter-clockwise seen from +y
  plane.indices = {0, 1, 2, 0, 2, 3};
  plane.material = 0;
  scene.geometry.add_mesh(std::move(plane));
  TriangleMesh square;
  // Two triangles with their own vertices, clockwise seen from +y (facing down); the second is cut out by its
  // vertex alpha (0, below the default cutoff 0.5).
  square.positions = {{-e, 1, -e}, {e, 1, e}, {e, 1, -e}, {-e, 1, -e}, {-e, 1, e}, {e, 1, e}};
  square.indices = {0, 2, 1, 3, 5, 4};
  square.colors = {{1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 0}, {1, 1, 1, 0}, {1, 1, 1, 0}};
  square.alpha = AlphaMask{};
  square.material = 0;
  square.light = 0;
  scene.lights.push_back(make_mesh_light(square, Color(1.0f), std::nullopt, /*two_sided=*/false));
  scene.geometry.add_mesh(std::move(square));
  scene.camera = make_camera({2, 0.5f, 0.5f}, {0, 0, 0}, 0.005f);
  scene.settings.width = scene.settings.height = 4;
  scene.settings.max_depth = 1;
  scene.finalize();
  const double expected = rho * 0.5 * (1 - 2e-6);
  for (const Case& c : all_variants()) {
    const Film film = render_scene(scene, c, 2000);
    expect_region(test::region_mean(film, [](int, int) { return true; }), expected, c.label() + " half-cut light");
  }
}

}  // namespace
}  // namespace lumis
