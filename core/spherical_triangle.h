// Arvo's uniform sampling of a spherical triangle (1995), in double, written once as inline branch-free steps so
// that sample_spherical_triangle (one receiver, core/spherical_polygons.cpp) and the batch kernel (many receivers
// side by side, core/spherical_triangle_batch.cpp) run the same arithmetic in the same order and give the same
// numbers bit for bit. Its two library calls, atan2 and sin/cos, are polynomials here (atan2_upper,
// sincos_radians), so a loop over lanes vectorises. Both files are compiled without floating-point contraction.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/math.h"

namespace lumis::sph_tri {

struct D3 {
  double x = 0, y = 0, z = 0;
};
inline D3 to_d(Vec3 v) { return {v.x, v.y, v.z}; }
inline Vec3 to_f(D3 v) { return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)}; }
inline D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double ddot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline D3 dcross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double dlen(D3 a) { return std::sqrt(ddot(a, a)); }
/// a / |a|, or 0 when |a| = 0 (branch-free).
inline D3 dnormalize(D3 a) {
  const double l = dlen(a);
  const double inv = l > 0 ? 1 / l : 0.0;
  return a * inv;
}
inline double dclamp(double v, double lo, double hi) { return std::min(std::max(v, lo), hi); }
/// Neither infinite nor NaN, as a compare (vectorises; std::isfinite may not).
inline bool dfinite(double v) { return std::abs(v) <= std::numeric_limits<double>::max(); }
constexpr double kDPi = 3.14159265358979323846;

/// atan2(y, x) for y >= 0 (the upper half plane), in [0, pi]; 0 at y = x = 0. Within a few double ulps (the
/// SphTriMath tests): |y / x| or its reciprocal, whichever is <= 1, is reduced below tan(pi / 8) by
/// atan(a) = pi / 4 + atan((a - 1) / (a + 1)), halved by atan(t) = 2 atan(t / (1 + sqrt(1 + t^2))), and the
/// Taylor series of the result (|s| <= tan(pi / 16)) is summed to 12 terms (truncation below 1e-18).
inline double atan2_upper(double y, double x) {
  const double ax = std::abs(x);
  const double hi = std::max(y, ax), lo = std::min(y, ax);
  const double a = hi > 0 ? lo / hi : 0.0;
  const bool big = a > 0.41421356237309503;  // tan(pi / 8)
  const double t = big ? (a - 1) / (a + 1) : a;
  const double s = t / (1 + std::sqrt(1 + t * t));
  const double z = s * s;
  double acc = 1 / 23.0;
  acc = 1 / 21.0 - z * acc;
  acc = 1 / 19.0 - z * acc;
  acc = 1 / 17.0 - z * acc;
  acc = 1 / 15.0 - z * acc;
  acc = 1 / 13.0 - z * acc;
  acc = 1 / 11.0 - z * acc;
  acc = 1 / 9.0 - z * acc;
  acc = 1 / 7.0 - z * acc;
  acc = 1 / 5.0 - z * acc;
  acc = 1 / 3.0 - z * acc;
  acc = 1 - z * acc;
  double r = (big ? kDPi / 4 : 0.0) + 2 * (s * acc);
  r = y > ax ? kDPi / 2 - r : r;
  return x < 0 ? kDPi - r : r;
}

/// sin and cos of x (radians, |x| < 2^20; Arvo needs [0, 2 pi)) within two double ulps: x reduced by the nearest
/// multiple q of pi / 2 (a 33-bit head, so q times it is exact, and a tail), then Taylor series on [-pi / 4, pi / 4]
/// (truncation below 1e-19).
inline void sincos_radians(double x, double& sin_out, double& cos_out) {
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kRound = 6755399441055744.0;  // 1.5 * 2^52: (v + kRound) - kRound rounds v to an integer
  constexpr double kPio2Hi = 1.57079632673412561417;     // pi / 2 to 33 bits: q * kPio2Hi is exact
  constexpr double kPio2Lo = 6.07710050650619224932e-11;  // pi / 2 - kPio2Hi
  const double shifted = x * kTwoOverPi + kRound;
  const double q = shifted - kRound;
  const uint64_t quadrant = std::bit_cast<uint64_t>(shifted) & 3;  // q mod 4, from the integer in the low bits
  const double r = (x - q * kPio2Hi) - q * kPio2Lo;
  const double r2 = r * r;
  // sin r = r - r^3 (1/3! - r^2/5! + ... - r^14/17!), cos r = 1 - r^2 (1/2! - r^2/4! + ... + r^16/18!), by Horner.
  double sp = 1 / 355687428096000.0;  // 1 / 17!
  sp = 1 / 1307674368000.0 - r2 * sp;
  sp = 1 / 6227020800.0 - r2 * sp;
  sp = 1 / 39916800.0 - r2 * sp;
  sp = 1 / 362880.0 - r2 * sp;
  sp = 1 / 5040.0 - r2 * sp;
  sp = 1 / 120.0 - r2 * sp;
  sp = 1 / 6.0 - r2 * sp;
  const double s = r - r * (r2 * sp);
  double cp = 1 / 6402373705728000.0;  // 1 / 18!
  cp = 1 / 20922789888000.0 - r2 * cp;
  cp = 1 / 87178291200.0 - r2 * cp;
  cp = 1 / 479001600.0 - r2 * cp;
  cp = 1 / 3628800.0 - r2 * cp;
  cp = 1 / 40320.0 - r2 * cp;
  cp = 1 / 720.0 - r2 * cp;
  cp = 1 / 24.0 - r2 * cp;
  cp = 1 / 2.0 - r2 * cp;
  const double c = 1 - r2 * cp;
  const bool odd = quadrant & 1, neg_sin = quadrant & 2, neg_cos = (quadrant + 1) & 2;
  const double sin_abs = odd ? c : s, cos_abs = odd ? s : c;
  sin_out = neg_sin ? -sin_abs : sin_abs;
  cos_out = neg_cos ? -cos_abs : cos_abs;
}

// Solid angles below this are left to area sampling. In double the angle-sum cancellation costs ~1e-16 / omega
// relative, harmless down to 1e-10 sr; the limit is the float result direction (~6e-8 rad): at 1e-6 sr the polygon
// spans ~1e-3 rad and a float direction can miss it by 1e-4 of its width. Below that, the polygon is so small that
// the area-to-solid-angle Jacobian is nearly constant over it and area sampling is practically as good.
constexpr double kMinSolidAngle = 1e-6;
// Near 2 pi the receiver lies almost in the polygon's plane above its interior: every spherical angle tends to pi
// and Arvo's q divides by sin(alpha) -> 0, so leave that case to area sampling as well.
constexpr double kMaxSolidAngle = 2 * kDPi - 1e-3;

/// Van Oosterom & Strackee on unit vectors: tan(omega / 2) = |a.(b x c)| / (1 + a.b + b.c + c.a).
inline double unit_triangle_solid_angle(D3 a, D3 b, D3 c) {
  const double num = std::abs(ddot(a, dcross(b, c)));
  const double den = 1 + ddot(a, b) + ddot(b, c) + ddot(c, a);
  return 2 * atan2_upper(num, den);
}

/// The triangle (a, b, c) projected onto the unit sphere around p, and its solid angle. ok: sampling it by solid
/// angle works (corners at nonzero finite distances, solid angle in [kMinSolidAngle, kMaxSolidAngle]); that depends
/// on the geometry only, never on u.
struct UnitTriangle {
  D3 a, b, c;
  double area = 0;
  bool ok = false;
};
inline UnitTriangle unit_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const D3 dp = to_d(p);
  const D3 da = to_d(a) - dp, db = to_d(b) - dp, dc = to_d(c) - dp;
  const double la = dlen(da), lb = dlen(db), lc = dlen(dc);
  UnitTriangle t;
  const bool lengths_ok = (la > 0) & (lb > 0) & (lc > 0) & dfinite(la + lb + lc);
  t.a = da * (1 / la);
  t.b = db * (1 / lb);
  t.c = dc * (1 / lc);
  t.area = unit_triangle_solid_angle(t.a, t.b, t.c);
  t.ok = lengths_ok & (t.area >= kMinSolidAngle) & (t.area <= kMaxSolidAngle);
  return t;
}

/// A direction uniform in solid angle inside the triangle seen from p, and its density 1 / area; ok as in
/// UnitTriangle (when false, w and pdf are meaningless).
struct Sample {
  Vec3 w;
  float pdf;
  bool ok;
};
[[gnu::always_inline]] inline Sample sample(Vec3 p, Vec3 a, Vec3 b, Vec3 c, Vec2 u) {
  const UnitTriangle t = unit_triangle(p, a, b, c);
  const D3 A = t.a, B = t.b, C = t.c;
  // alpha, the interior angle at A between the arcs toward B and toward C: the angle between the normals of the
  // two arcs' planes, in [0, pi] (so its sine is >= 0).
  const D3 nb = dcross(A, B), nc = dcross(A, C);
  const double inv = 1 / std::sqrt(ddot(nb, nb) * ddot(nc, nc));
  const bool inv_ok = dfinite(inv);
  const double alpha_cos = inv_ok ? dclamp(ddot(nb, nc) * inv, -1, 1) : 1.0;
  const double alpha_sin = inv_ok ? dclamp(dlen(dcross(nb, nc)) * inv, 0, 1) : 0.0;
  const double cos_c = ddot(A, B);  // cosine of the arc opposite C
  // Arvo: choose the sub-triangle (A, B, C') of area u.x * area; C' lies on arc AC at cos(arc AC') = q. The sine
  // and cosine of area_sub - alpha by the angle-difference identities: one sincos instead of an acos and two.
  const double area_sub = u.x * t.area;
  double sin_sub, cos_sub;
  sincos_radians(area_sub, sin_sub, cos_sub);
  const double s = sin_sub * alpha_cos - cos_sub * alpha_sin;   // sin(area_sub - alpha)
  const double cs = cos_sub * alpha_cos + sin_sub * alpha_sin;  // cos(area_sub - alpha)
  const double uu = cs - alpha_cos;
  const double vv = s + alpha_sin * cos_c;
  double q = ((vv * cs - uu * s) * alpha_cos - vv) / ((vv * s + uu * cs) * alpha_sin);
  q = dfinite(q) ? q : 1.0;  // not finite only at area_sub -> 0, where C' = A
  q = dclamp(q, -1, 1);
  const D3 c_perp = dnormalize(C - A * ddot(C, A));
  const D3 c_sub = A * q + c_perp * std::sqrt(std::max(0.0, 1 - q * q));
  // Then uniform in the sub-triangle along the arc from B toward C', by 1 - cos of the arc length.
  const double z = 1 - u.y * (1 - ddot(c_sub, B));
  const D3 b_perp = dnormalize(c_sub - B * ddot(c_sub, B));
  const D3 w = dnormalize(B * z + b_perp * std::sqrt(std::max(0.0, 1 - z * z)));
  return {to_f(w), static_cast<float>(1 / t.area), t.ok};
}

}  // namespace lumis::sph_tri
