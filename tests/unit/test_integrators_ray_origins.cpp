// Where light sampling's rays start and end (integrators/path_vertex.h light_context, core/ray.h spawn_ray_to).
// Deterministic: fixed receivers and fixed sample numbers, exact counts.
//  - Shadow rays toward a sampled light point reach it far from the origin. At 1e4 units a float's spacing is
//    1e-3, so a sampled point is rounded into its own light by up to about that much; the shadow segment used to
//    stop only 1e-4 of its length (3e-4 here) short of it, and the light shadowed itself: of 4000 shadow rays at
//    1e4, 919 (sphere), 355 (tilted quad) and 1096 (tilted mesh square) were blocked, about half at 1e5, and
//    `light` / `nee_mis` rendered a sphere light over a floor 13 % too dark. Now the target is offset off the
//    light by its error bound: none is blocked.
//  - The shadow segment ends at that offset target: the 1e-4 margin no longer hides an occluder just in front of
//    the light (a ceiling 1e-4 below a light).
//  - A light-sampled direction meets the light from the point the ray along it starts from. `mis` traces its
//    light-sampled directions; they were drawn from the hit point, while the ray leaves from the offset origin
//    (4e-3 above a 2000-unit ground): under a 0.03-radius sphere light 1.5 units up, 228 of 4000 missed it, and
//    the mixture density along them was 0, and `mis` rendered 4 % too dark. Now none misses.
#include <gtest/gtest.h>

#include <string>

#include "core/rng.h"
#include "integrators/path.h"

namespace lumis {
namespace {

enum class Kind { Sphere, Quad, Mesh };

// A diffuse floor quad (half-size `half` around `at`, facing +y) and one light of the given kind 2.5 units above
// it, offset to one side; returns the light's centre.
Vec3 add_floor_and_light(Scene& scene, Vec3 at, float half, Kind kind) {
  scene.materials.push_back(make_diffuse_material(Color(0.5f)));
  TriangleMesh floor;
  floor.positions = {at + Vec3{-half, 0, -half}, at + Vec3{-half, 0, half}, at + Vec3{half, 0, half},
                     at + Vec3{half, 0, -half}};  // counter-clockwise seen from +y
  floor.indices = {0, 1, 2, 0, 2, 3};
  floor.material = 0;
  scene.geometry.add_mesh(std::move(floor));
  const Vec3 c = at + Vec3{1, 2.5f, 1};
  if (kind == Kind::Sphere) {
    scene.lights.push_back(make_sphere_light(c, 0.3f, Color(10)));
    scene.geometry.add_sphere(Sphere{c, 0.3f, -1, 0});
  } else {
    // A square of side about 0.6 facing down, tilted (a horizontal one lies on a float-representable height,
    // onto which sampled points round exactly): the quad light (spherical rectangles) or the same square as a
    // mesh light.
    const Vec3 eu{0.6f, 0.15f, 0}, ev{0, 0, 0.6f}, corner = c - (eu + ev) * 0.5f;
    TriangleMesh panel;
    panel.positions = {corner, corner + eu, corner + eu + ev, corner + ev};  // normal cross(eu, ev), downward
    panel.indices = {0, 1, 2, 0, 2, 3};
    panel.light = 0;
    scene.lights.push_back(kind == Kind::Quad ? make_quad_light(corner, eu, ev, Color(10))
                                              : make_mesh_light(panel, Color(10), std::nullopt, false));
    scene.geometry.add_mesh(std::move(panel));
  }
  scene.finalize();
  return c;
}

// The floor's hit under (x, z) relative to `at`, seen from 1 unit above (below the lights), and its vertex.
std::optional<Vertex> floor_vertex(const Scene& scene, Vec3 at, float x, float z, Hit& hit) {
  const Ray down{at + Vec3{x, 1, z}, {0, -1, 0}, 0, INFINITY};
  if (!scene.geometry.intersect(down, hit) || hit.material != 0) return std::nullopt;
  return make_vertex(scene, hit, down.d);
}

// The shadow ray of the scene's only light sampled at v with numbers u, as `light` and `nee_mis` make it
// (sample_direct); nullopt when the light or the sample gives none.
std::optional<Ray> shadow_ray_of(const Scene& scene, const Vertex& v, Vec2 u) {
  LightDraw draw;
  draw.choice = {0, 1.0f};
  const std::optional<LightSample> ls = scene.lights[0]->sample(v.ctx, u);
  if (!ls) return std::nullopt;
  draw.sample = *ls;
  draw.ok = true;
  PathCounters counters;
  const std::optional<ShadowQuery> q = sample_direct(v, draw, false, MisHeuristic::Balance, counters);
  return q ? std::optional<Ray>(q->ray) : std::nullopt;
}

TEST(RayOrigins, ShadowRaysReachSampledLightPointsFarFromTheOrigin) {
  for (const float offset : {0.0f, 1e3f, 1e4f, 1e5f}) {
    for (const Kind kind : {Kind::Sphere, Kind::Quad, Kind::Mesh}) {
      const std::string what = std::string(kind == Kind::Sphere ? "sphere" : kind == Kind::Quad ? "quad" : "mesh") +
                               " light at " + std::to_string(offset);
      Scene scene;
      const Vec3 at{offset, offset, -offset};
      add_floor_and_light(scene, at, 4, kind);
      Pcg32 rng(7, 3);
      int traced = 0, blocked = 0;
      for (int i = 0; i < 4000; ++i) {
        Hit hit;
        const float x = 6 * rng.next_float() - 3, z = 6 * rng.next_float() - 3;
        const std::optional<Vertex> v = floor_vertex(scene, at, x, z, hit);
        ASSERT_TRUE(v.has_value()) << what;
        const std::optional<Ray> ray = shadow_ray_of(scene, *v, {rng.next_float(), rng.next_float()});
        if (!ray) continue;
        ++traced;
        blocked += scene.geometry.occluded(*ray);
      }
      EXPECT_GT(traced, 3000) << what;
      EXPECT_EQ(blocked, 0) << what << ": of " << traced << " shadow rays, " << blocked
                            << " were blocked by the light itself";
    }
  }
}

// A quad light 1e-4 above a ceiling 2 units over the floor (a light hidden above it): every shadow ray from the floor
// must meet the ceiling. With the shadow segment stopping 1e-4 of its length (2e-4 here) short of the light, the
// ceiling was ignored and `light` / `nee_mis` lit the room through it (0.10 against 0.008 from BSDF sampling). Near
// the origin: 100 units out, the light point's own error bound (8e-4) is more than the gap, and no renderer in float
// can tell the two surfaces apart.
TEST(RayOrigins, ShadowRaysSeeAnOccluderJustInFrontOfTheLight) {
  for (const float offset : {0.0f, 1.0f}) {
    Scene scene;
    const Vec3 at{offset, 0, offset};
    scene.materials.push_back(make_diffuse_material(Color(0.5f)));
    const auto square = [&](float y, int light) {
      TriangleMesh m;
      m.positions = {at + Vec3{-1, y, -1}, at + Vec3{1, y, -1}, at + Vec3{1, y, 1}, at + Vec3{-1, y, 1}};
      m.indices = {0, 1, 2, 0, 2, 3};
      m.material = light < 0 ? 0 : -1;
      m.light = light;
      return m;
    };
    TriangleMesh floor = square(0, -1);
    floor.indices = {0, 2, 1, 0, 3, 2};  // facing up
    scene.geometry.add_mesh(std::move(floor));
    scene.geometry.add_mesh(square(2, -1));  // the ceiling
    TriangleMesh panel = square(2 + 1e-4f, 0);
    scene.lights.push_back(make_quad_light(panel.positions[0], {2, 0, 0}, {0, 0, 2}, Color(10)));
    scene.geometry.add_mesh(std::move(panel));
    scene.finalize();
    Pcg32 rng(3, 9);
    int traced = 0, unblocked = 0;
    for (int i = 0; i < 2000; ++i) {
      Hit hit;
      const float x = 1.6f * rng.next_float() - 0.8f, z = 1.6f * rng.next_float() - 0.8f;
      const std::optional<Vertex> v = floor_vertex(scene, at, x, z, hit);
      ASSERT_TRUE(v.has_value());
      const std::optional<Ray> ray = shadow_ray_of(scene, *v, {rng.next_float(), rng.next_float()});
      if (!ray) continue;
      ++traced;
      unblocked += !scene.geometry.occluded(*ray);
    }
    EXPECT_GT(traced, 1900) << offset;
    EXPECT_EQ(unblocked, 0) << "of " << traced << " shadow rays at " << offset << ", through the ceiling";
  }
}

TEST(RayOrigins, LightSampledDirectionsMeetTheLightFromTheRayOrigin) {
  Scene scene;
  scene.materials.push_back(make_diffuse_material(Color(0.5f)));
  TriangleMesh ground;
  const float e = 1000;  // the hit points' error bound, and so the rays' offset, is 4e-3
  ground.positions = {{-e, 0, -e}, {-e, 0, e}, {e, 0, e}, {e, 0, -e}};
  ground.indices = {0, 1, 2, 0, 2, 3};
  ground.material = 0;
  scene.geometry.add_mesh(std::move(ground));
  const Vec3 c{1, 1.5f, 1};
  scene.lights.push_back(make_sphere_light(c, 0.03f, Color(1000)));
  scene.geometry.add_sphere(Sphere{c, 0.03f, -1, 0});
  scene.finalize();
  Pcg32 rng(11, 5);
  int missed = 0, density_zero = 0;
  constexpr int kSamples = 4000;
  for (int i = 0; i < kSamples; ++i) {
    Hit hit;
    const float x = 4 * rng.next_float() - 2, z = 4 * rng.next_float() - 2;
    const std::optional<Vertex> v = floor_vertex(scene, {0, 0, 0}, x, z, hit);
    ASSERT_TRUE(v.has_value());
    const std::optional<LightSample> ls = scene.lights[0]->sample(v->ctx, {rng.next_float(), rng.next_float()});
    ASSERT_TRUE(ls.has_value());
    // The ray `mis` continues along, and the query its mixture density makes.
    Hit on_light;
    missed += !scene.geometry.intersect(spawn_ray(hit, ls->wi), on_light) || on_light.light != 0;
    PathCounters counters;
    density_zero += !(light_strategy_pdf(scene, hit, v->ctx, ls->wi, counters) > 0);
  }
  EXPECT_EQ(missed, 0) << "of " << kSamples << " light-sampled directions";
  EXPECT_EQ(density_zero, 0) << "of " << kSamples << " light-sampled directions";
}

}  // namespace
}  // namespace lumis
