// Mat4::determinant3: the sign callers use to flip the winding and the normals of a mirroring transform, and the
// value the scene file's singular-matrix check divides by the column lengths; rotate_quaternion's normalisation.
// Deterministic.
#include <gtest/gtest.h>

#include <cmath>

#include "core/transform.h"

namespace lumis {
namespace {

Mat4 rows(float a, float b, float c, float d, float e, float f, float g, float h, float i) {
  Mat4 r;
  const float v[9] = {a, b, c, d, e, f, g, h, i};
  for (int k = 0; k < 9; ++k) r.m[k / 3][k % 3] = v[k];
  return r;
}

TEST(Mat4, Determinant3OfOrdinaryTransforms) {
  EXPECT_DOUBLE_EQ(Mat4::identity().determinant3(), 1.0);
  EXPECT_DOUBLE_EQ(Mat4::scale({2, 3, -4}).determinant3(), -24.0);
  EXPECT_NEAR((Mat4::rotate_axis({1, 2, 3}, 40) * Mat4::scale({1, -1, 1})).determinant3(), -1.0, 1e-6);
  EXPECT_DOUBLE_EQ(Mat4::translate({5, 6, 7}).determinant3(), 1.0);  // the translation is not part of it
}

// Entries a float product cannot hold: a scale of 1e13 made the float determinant -infinity, and a mirroring shear of
// 1e20 made it NaN, which is not "< 0", so the mirror went unnoticed (inside-out normals). In double both are exact.
TEST(Mat4, Determinant3OfLargeEntriesIsFiniteAndKeepsItsSign) {
  const double s = static_cast<double>(1e13f);
  EXPECT_DOUBLE_EQ(Mat4::scale({1e13f, 1e13f, -1e13f}).determinant3(), -s * s * s);
  const float k = 1e20f;
  const double kd = static_cast<double>(k);
  const double det = rows(-k, 0, 0, 0, k, k, 0, k, 2 * k).determinant3();  // -k (2 k^2 - k^2)
  EXPECT_LT(det, 0.0);
  EXPECT_DOUBLE_EQ(det, -kd * kd * kd);
}

// A quaternion is normalised before use. In float the squares of 1e-30 underflowed to 0 (and of 1e20 overflowed),
// so both scaled copies of a quarter turn about +X became the identity.
TEST(Mat4, RotateQuaternionNormalisesTinyAndHugeQuaternions) {
  const float h = std::sqrt(0.5f);
  for (const float k : {1.0f, 1e-30f, 1e20f, 3.0f}) {
    const Mat4 r = Mat4::rotate_quaternion({h * k, 0, 0, h * k});
    const Vec3 y = r.apply_vector({0, 1, 0});
    EXPECT_NEAR(y.x, 0, 1e-6) << "scale " << k;
    EXPECT_NEAR(y.y, 0, 1e-6) << "scale " << k;
    EXPECT_NEAR(y.z, 1, 1e-6) << "scale " << k << ": +Y turns to +Z";
  }
  const Vec3 same = Mat4::rotate_quaternion({0, 0, 0, 0}).apply_vector({1, 2, 3});  // length 0: the identity
  EXPECT_EQ(same.x, 1);
  EXPECT_EQ(same.z, 3);
}

}  // namespace
}  // namespace lumis
