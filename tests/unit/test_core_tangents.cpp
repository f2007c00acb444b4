// Tangent generation: direction from dP/du, orthogonal to the normal, handedness by glTF's convention
// (bitangent = w cross(n, t) points toward decreasing v, "up" in the image).
#include <gtest/gtest.h>

#include "core/tangents.h"

namespace lumis {
namespace {

// Unit quad in the xy plane facing +z; image "up" (decreasing v) is +y.
TriangleMesh quad(bool mirror_u) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  const float u0 = mirror_u ? 1.0f : 0.0f, u1 = mirror_u ? 0.0f : 1.0f;
  m.uv0 = {{u0, 1}, {u1, 1}, {u1, 0}, {u0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TEST(Tangents, FollowUAndGltfHandedness) {
  TriangleMesh m = quad(false);
  generate_tangents(m, 0);
  ASSERT_EQ(m.tangents.size(), 4u);
  for (const Vec4& t : m.tangents) {
    EXPECT_NEAR(t.x, 1, 1e-6);
    EXPECT_NEAR(t.y, 0, 1e-6);
    EXPECT_NEAR(t.z, 0, 1e-6);
    EXPECT_EQ(t.w, 1.0f);  // cross(+z, +x) = +y = up in the image
  }
}

TEST(Tangents, MirroredUvFlipsHandedness) {
  TriangleMesh m = quad(true);
  generate_tangents(m, 0);
  for (const Vec4& t : m.tangents) {
    EXPECT_NEAR(t.x, -1, 1e-6);
    EXPECT_EQ(t.w, -1.0f);  // cross(+z, -x) = -y, but up is +y
  }
}

TEST(Tangents, OrthogonalToBentNormalsAndSafeWithoutUvGradient) {
  TriangleMesh m = quad(false);
  m.normals = {normalize(Vec3(0.3f, 0, 1)), {0, 0, 1}, {0, 0, 1}, normalize(Vec3(0.3f, 0.2f, 1))};
  generate_tangents(m, 0);
  for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(dot(m.tangents[i].xyz(), m.normals[i]), 0, 1e-6);
  TriangleMesh flat = quad(false);
  flat.uv0.assign(4, Vec2{0.5f, 0.5f});  // no gradient: arbitrary but valid tangents
  generate_tangents(flat, 0);
  for (const Vec4& t : flat.tangents) EXPECT_NEAR(length(t.xyz()), 1, 1e-5);
}

}  // namespace
}  // namespace lumis
