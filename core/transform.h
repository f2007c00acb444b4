// 4x4 affine transforms (row-major, column vectors: p' = M p).
#pragma once

#include "core/math.h"

namespace lumis {

struct Mat4 {
  float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

  static Mat4 identity() { return {}; }
  static Mat4 translate(Vec3 t);
  static Mat4 scale(Vec3 s);
  /// Rotation by quaternion (x, y, z, w), as glTF stores it; normalised first (in double); length 0: the identity.
  static Mat4 rotate_quaternion(Vec4 q);
  /// Rotation about an axis by an angle in degrees.
  static Mat4 rotate_axis(Vec3 axis, float degrees);
  /// From 16 numbers in column-major order (glTF "matrix").
  static Mat4 from_column_major(const double* v);

  Vec3 apply_point(Vec3 p) const;
  Vec3 apply_vector(Vec3 v) const;
  /// Transform a normal by the inverse transpose (not normalised).
  Vec3 apply_normal(Vec3 n) const;
  double determinant3() const;  ///< determinant of the upper-left 3x3, in double (negative: handedness flips)
  Mat4 inverse() const;
  bool is_finite() const;
};

Mat4 operator*(const Mat4& a, const Mat4& b);

}  // namespace lumis
