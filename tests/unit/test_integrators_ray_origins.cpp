// Where light sampling's rays start and end (integrators/path_vertex.h light_context, core/ray.h spawn_ray_to).
// Deterministic: fixed receivers and fixed sample numbers, exact counts.
//  - Shadow rays toward a sampled light point reach it far from the origin. At 1e4 units a float's spacing is
//    1e-3, so a sampled point is rounded into its own light by up to about that much; the shadow segment used to
//    stop only 1e-4 of its length (3e-4 here) short of it, and the light shadowed itself: of 4000 shadow rays at
//    1e4, 919 (sphere), 355 (tilted quad) and 1096 (tilted mesh square) were blocked, about half at 1e5, and
//    `light` / `nee_mis` rendered a sphere light over a floor 13 % too dark. Now the segment stops the light
//    point's error bound short of the light: none is blocked, for every light and sampling method.
//  - It stops only that short: the 1e-4 margin no longer hides an occluder just in front of the light (a ceiling
//    1e-4 below a light).
//  - It stops short along itself, keeping its direction (shadow_ray's contract, on random segments).
//  - A light-sampled direction meets the light from the point the ray along it starts from. `mis` traces its
//    light-sampled directions; they were drawn from the hit point, while the ray leaves from the offset origin
//    (4e-3 above a 2000-unit ground): under a 0.03-radius sphere light 1.5 units up, 228 of 4000 missed it, and
//    the mixture density along them was 0, and `mis` rendered 4 % too dark. Now none misses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/ray.h"
#include "core/rng.h"
#include "core/warp.h"
#include "integrators/path.h"

namespace lumis {
namespace {

enum class Kind { Sphere, Quad, Mesh, QuadByArea, MeshByArea };

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
    // onto which sampled points round exactly): the quad light or the same square as a mesh light, sampled by
    // solid angle or by area.
    const Vec3 eu{0.6f, 0.15f, 0}, ev{0, 0, 0.6f}, corner = c - (eu + ev) * 0.5f;
    TriangleMesh panel;
    panel.positions = {corner, corner + eu, corner + eu + ev, corner + ev};  // normal cross(eu, ev), downward
    panel.indices = {0, 1, 2, 0, 2, 3};
    panel.light = 0;
    const bool by_area = kind == Kind::QuadByArea || kind == Kind::MeshByArea;
    if (kind == Kind::Quad || kind == Kind::QuadByArea)
      scene.lights.push_back(make_quad_light(corner, eu, ev, Color(10),
                                             by_area ? QuadSampling::Area : QuadSampling::SphericalRectangle));
    else
      scene.lights.push_back(make_mesh_light(panel, Color(10), std::nullopt, false,
                                             by_area ? TriangleSampling::Area : TriangleSampling::SphericalTriangle));
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
    for (const Kind kind : {Kind::Sphere, Kind::Quad, Kind::Mesh, Kind::QuadByArea, Kind::MeshByArea}) {
      const char* names[] = {"sphere", "quad", "mesh", "quad (by area)", "mesh (by area)"};
      const std::string what = std::string(names[int(kind)]) + " light at " + std::to_string(offset);
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

// shadow_ray's contract, checked on 80,000 segments at scales 1e-3 to 1e5 from the origin, one in five nearly
// parallel to the target's surface: (a) the segment ends off that surface, on the origin's side, by at least the
// target's projected error bound (off = |n|_1 x error); (b) it keeps more than half its length; (c) unless its end
// would move back along it by half of it or more, it ends on the line from the origin to the target: it stands for
// part of the true segment, and cannot meet a surface that segment misses. Until stop 60 the end was moved along the
// target's normal instead, which turned the segment (at 1e5, by up to 0.048 across a gap of 0.07 between a light and a
// plate under it, darkening `light` by 4 %). Rounding slack: 4 ulps of the coordinates.
TEST(RayOrigins, ShadowSegmentsEndShortOfTheirTargetAlongThemselves) {
  Pcg32 rng(21, 4);
  const auto unit3 = [&rng] { return sample_uniform_sphere({rng.next_float(), rng.next_float()}); };
  int short_of = 0, too_short = 0, turned = 0, checked = 0;
  for (const double at : {1e-3, 1.0, 1e3, 1e5}) {
    for (int i = 0; i < 20000; ++i) {
      const Vec3 o = Vec3(float(at)) + unit3() * float(at * rng.next_float());
      const Vec3 target = o + unit3() * float(std::max(at, 1.0) * (0.01 + rng.next_float()));
      const Vec3 to_o = normalize(o - target);
      // One in five nearly parallel: a normal at 1e-7 to 1e-1 radians from perpendicular to the segment.
      Vec3 n = unit3();
      if (i % 5 == 0) n = normalize(normalize(cross(to_o, n)) + to_o * std::pow(10.0f, -7 + 6 * rng.next_float()));
      const float err = kErrorScale * (max_component(abs(target)) + length(o - target)) *
                        (rng.next_float() < 0.5f ? 1 : 100 * rng.next_float());
      double len2 = 0;
      for (int k = 0; k < 3; ++k) len2 += std::pow(double(o[k]) - target[k], 2);
      const double off = double(dot(abs(n), Vec3(err))), len = std::sqrt(len2);
      if (!(off < 0.1 * len)) continue;
      ++checked;
      const Ray r = shadow_ray(o, target, n, err);
      const double slack = 4 * 0x1p-24 * (max_component(abs(o)) + max_component(abs(target)) + len);
      // The origin's side of the surface: +n when the origin lies in it, as offset_ray_origin picks.
      double e[3], ns = dot(o - target, n) < 0 ? -1 : 1, clearance = 0, kept = 0;
      for (int k = 0; k < 3; ++k) {
        e[k] = double(r.o[k]) + double(r.d[k]) * double(r.tmax);
        clearance += (e[k] - target[k]) * ns * n[k];
        kept += (e[k] - o[k]) * (e[k] - o[k]);
      }
      short_of += !(clearance >= off - slack);
      too_short += !(std::sqrt(kept) > 0.5 * len);
      if (2 * off < std::abs(dot(target - o, n))) {  // (c): the distance from the end to the line o -> target
        double u[3], along = 0, across2 = 0;
        for (int k = 0; k < 3; ++k) u[k] = (double(target[k]) - o[k]) / len;
        for (int k = 0; k < 3; ++k) along += (e[k] - o[k]) * u[k];
        for (int k = 0; k < 3; ++k) across2 += std::pow(e[k] - o[k] - along * u[k], 2);
        turned += !(std::sqrt(across2) <= slack);
      }
    }
  }
  EXPECT_GT(checked, 60000);
  EXPECT_EQ(short_of, 0) << "of " << checked << " segments end less than the target's error bound off its surface";
  EXPECT_EQ(too_short, 0) << "of " << checked << " segments keep half their length or less";
  EXPECT_EQ(turned, 0) << "of " << checked << " segments leave the line from their origin to their target";
}

}  // namespace
}  // namespace lumis
