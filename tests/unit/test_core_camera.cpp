// The pinhole camera of core/camera.cpp: where the image's edges point (vertical field of view, aspect ratio,
// orientation), square pixels, the near clip, unit directions, and a usable basis when `up` is parallel to the view
// direction.
// Deterministic geometry: no statistics, tolerances are float rounding.
#include <gtest/gtest.h>

#include <cmath>

#include "core/camera.h"

namespace lumis {
namespace {

constexpr double kPiD = 3.14159265358979323846;

double angle_between(Vec3 a, Vec3 b) {
  return std::atan2(static_cast<double>(length(cross(a, b))), static_cast<double>(dot(a, b)));
}

// Looking down -z from (0, 0, 5) with +y up: image right is +x, image top is +y.
Camera looking_down_z(float fov_y_degrees) {
  Camera c;
  c.from = {0, 0, 5};
  c.to = {0, 0, 0};
  c.up = {0, 1, 0};
  c.fov_y_degrees = fov_y_degrees;
  return c;
}

TEST(Camera, EdgesFollowFieldOfViewAndAspect) {
  // A wide image (2:1) and a tall one (1:3): the vertical field of view is fov_y whatever the shape, and the
  // horizontal half-angle has tangent tan(fov_y / 2) x width / height.
  struct Case {
    int w, h;
    float fov;
  };
  for (const Case c : {Case{200, 100, 40.0f}, Case{90, 270, 65.0f}, Case{64, 64, 90.0f}}) {
    SCOPED_TRACE(testing::Message() << c.w << "x" << c.h << " fov " << c.fov);
    Camera cam = looking_down_z(c.fov);
    cam.prepare(c.w, c.h);
    const float cx = 0.5f * c.w, cy = 0.5f * c.h;
    const Vec3 forward{0, 0, -1};
    const double half_v = 0.5 * c.fov * kPiD / 180;
    const double half_h = std::atan(std::tan(half_v) * c.w / c.h);
    const Vec3 centre = cam.generate_ray({cx, cy}).d, top = cam.generate_ray({cx, 0}).d;
    const Vec3 bottom = cam.generate_ray({cx, static_cast<float>(c.h)}).d;
    const Vec3 left = cam.generate_ray({0, cy}).d, right = cam.generate_ray({static_cast<float>(c.w), cy}).d;
    EXPECT_LT(angle_between(centre, forward), 1e-6);
    EXPECT_NEAR(angle_between(top, forward), half_v, 1e-5);
    EXPECT_NEAR(angle_between(bottom, forward), half_v, 1e-5);
    EXPECT_NEAR(angle_between(left, forward), half_h, 1e-5);
    EXPECT_NEAR(angle_between(right, forward), half_h, 1e-5);
    // Orientation: pixel rows go down the image, columns go right.
    EXPECT_GT(top.y, 0.0f);
    EXPECT_LT(bottom.y, 0.0f);
    EXPECT_GT(right.x, 0.0f);
    EXPECT_LT(left.x, 0.0f);
    EXPECT_EQ(cam.generate_ray({cx, cy}).o, Vec3(0, 0, 5));
  }
}

TEST(Camera, PixelsAreSquare) {
  // At the image centre a step of one pixel turns the ray by the same angle across and down, for any aspect ratio.
  for (const auto& [w, h] : {std::pair{320, 120}, std::pair{100, 300}}) {
    Camera cam = looking_down_z(50);
    cam.prepare(w, h);
    const float cx = 0.5f * w, cy = 0.5f * h;
    const Vec3 c = cam.generate_ray({cx, cy}).d;
    const double across = angle_between(c, cam.generate_ray({cx + 1, cy}).d);
    const double down = angle_between(c, cam.generate_ray({cx, cy + 1}).d);
    EXPECT_NEAR(across / down, 1.0, 1e-3) << w << "x" << h;
  }
}

// near_clip: every ray starts that far from the eye along its own direction (the scene format's "near"), so
// whatever is closer to the eye is not seen.
TEST(Camera, RaysStartNearClipFromTheEye) {
  Camera cam = looking_down_z(60);
  cam.near_clip = 2;
  cam.prepare(40, 30);
  for (const Vec2 film : {Vec2(20, 15), Vec2(0, 0), Vec2(40, 30), Vec2(3.5f, 27)}) {
    const Ray r = cam.generate_ray(film);
    EXPECT_NEAR(length(r.o - cam.from), 2.0f, 1e-6f);
    EXPECT_LT(length(cross(r.o - cam.from, r.d)), 1e-6f);  // on the ray from the eye
    EXPECT_GT(dot(r.o - cam.from, r.d), 0.0f);            // ahead of the eye
  }
}

TEST(Camera, UnitDirectionsAndDegenerateUp) {
  // `up` parallel to the view direction still gives an orthonormal basis (the camera picks another up), and every
  // direction is unit length.
  Camera cam;
  cam.from = {1, 7, 2};
  cam.to = {1, -3, 2};
  cam.up = {0, 1, 0};
  cam.fov_y_degrees = 30;
  cam.prepare(48, 32);
  for (float y : {0.0f, 7.5f, 32.0f})
    for (float x : {0.0f, 13.25f, 48.0f}) {
      const Ray r = cam.generate_ray({x, y});
      ASSERT_TRUE(std::isfinite(r.d.x) && std::isfinite(r.d.y) && std::isfinite(r.d.z));
      EXPECT_NEAR(length(r.d), 1.0f, 1e-6f);
      EXPECT_LT(r.d.y, 0.0f);  // every ray looks down, toward `to`
    }
  EXPECT_LT(angle_between(cam.generate_ray({24, 16}).d, {0, -1, 0}), 1e-6);
}

}  // namespace
}  // namespace lumis
