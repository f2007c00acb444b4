#include "core/transform.h"

#include <cmath>

namespace lumis {

Mat4 Mat4::translate(Vec3 t) {
  Mat4 r;
  r.m[0][3] = t.x; r.m[1][3] = t.y; r.m[2][3] = t.z;
  return r;
}

Mat4 Mat4::scale(Vec3 s) {
  Mat4 r;
  r.m[0][0] = s.x; r.m[1][1] = s.y; r.m[2][2] = s.z;
  return r;
}

Mat4 Mat4::rotate_quaternion(Vec4 q) {
  // Normalised in double: in float the squares of 1e-30 underflow (and of 1e20 overflow), which left the identity.
  const double qx = q.x, qy = q.y, qz = q.z, qw = q.w;
  const double n = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
  if (n > 0 && std::isfinite(n))
    q = {static_cast<float>(qx / n), static_cast<float>(qy / n), static_cast<float>(qz / n),
         static_cast<float>(qw / n)};
  const float x = q.x, y = q.y, z = q.z, w = q.w;
  Mat4 r;
  r.m[0][0] = 1 - 2 * (y * y + z * z); r.m[0][1] = 2 * (x * y - z * w);     r.m[0][2] = 2 * (x * z + y * w);
  r.m[1][0] = 2 * (x * y + z * w);     r.m[1][1] = 1 - 2 * (x * x + z * z); r.m[1][2] = 2 * (y * z - x * w);
  r.m[2][0] = 2 * (x * z - y * w);     r.m[2][1] = 2 * (y * z + x * w);     r.m[2][2] = 1 - 2 * (x * x + y * y);
  return r;
}

Mat4 Mat4::rotate_axis(Vec3 axis, float degrees) {
  const Vec3 a = normalize(axis);
  const float half = degrees * kPi / 360.0f;
  const float s = std::sin(half);
  return rotate_quaternion({a.x * s, a.y * s, a.z * s, std::cos(half)});
}

Mat4 Mat4::from_column_major(const double* v) {
  Mat4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) r.m[row][c] = static_cast<float>(v[c * 4 + row]);
  return r;
}

Vec3 Mat4::apply_point(Vec3 p) const {
  return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
          m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
          m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
}

Vec3 Mat4::apply_vector(Vec3 v) const {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Vec3 Mat4::apply_normal(Vec3 n) const {
  // Cofactor matrix of the 3x3 part = det * inverse transpose; sign(det) keeps orientation for mirrored
  // transforms consistent with the flipped winding (callers flip winding when det < 0).
  const auto& a = m;
  const Vec3 c0{a[1][1] * a[2][2] - a[1][2] * a[2][1], a[1][2] * a[2][0] - a[1][0] * a[2][2],
                a[1][0] * a[2][1] - a[1][1] * a[2][0]};
  const Vec3 c1{a[0][2] * a[2][1] - a[0][1] * a[2][2], a[0][0] * a[2][2] - a[0][2] * a[2][0],
                a[0][1] * a[2][0] - a[0][0] * a[2][1]};
  const Vec3 c2{a[0][1] * a[1][2] - a[0][2] * a[1][1], a[0][2] * a[1][0] - a[0][0] * a[1][2],
                a[0][0] * a[1][1] - a[0][1] * a[1][0]};
  // c0, c1, c2 are the rows of the cofactor matrix C = det * inverse transpose.
  Vec3 r{dot(c0, n), dot(c1, n), dot(c2, n)};
  if (determinant3() < 0) r = -r;
  return r;
}

double Mat4::determinant3() const {
  // In double: in float a scale of 1e13 overflows the product to infinity, and larger entries make it NaN.
  const auto a = [this](int i, int j) { return static_cast<double>(m[i][j]); };
  return a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)) - a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0)) +
         a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
}

Mat4 Mat4::inverse() const {
  // General 4x4 inverse by Gauss-Jordan elimination with partial pivoting.
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 8; ++j) a[i][j] = j < 4 ? m[i][j] : (j - 4 == i ? 1.0 : 0.0);
  for (int c = 0; c < 4; ++c) {
    int piv = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(a[r][c]) > std::abs(a[piv][c])) piv = r;
    if (a[piv][c] == 0) return Mat4{};
    for (int j = 0; j < 8; ++j) std::swap(a[c][j], a[piv][j]);
    const double inv = 1.0 / a[c][c];
    for (int j = 0; j < 8; ++j) a[c][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = a[r][c];
      for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
    }
  }
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = static_cast<float>(a[i][j + 4]);
  return r;
}

bool Mat4::is_finite() const {
  for (const auto& row : m)
    for (float v : row)
      if (!std::isfinite(v)) return false;
  return true;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      float s = 0;
      for (int k = 0; k < 4; ++k) s += a.m[i][k] * b.m[k][j];
      r.m[i][j] = s;
    }
  return r;
}

}  // namespace lumis
