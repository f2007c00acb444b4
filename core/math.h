// Small vector types for lumis: Vec2, Vec3 (also used as linear RGB Color), Vec4, and helpers.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lumis {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
inline constexpr float kPiOver2 = 1.57079632679489661923f;
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;  ///< largest float below 1

struct Vec2 {
  float x = 0, y = 0;
  constexpr Vec2() = default;
  constexpr Vec2(float x_, float y_) : x(x_), y(y_) {}
  constexpr float operator[](int i) const { return i == 0 ? x : y; }
  constexpr float& operator[](int i) { return i == 0 ? x : y; }
};
constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator*(Vec2 a, float s) { return {a.x * s, a.y * s}; }
constexpr Vec2 operator*(float s, Vec2 a) { return {a.x * s, a.y * s}; }

struct Vec3 {
  float x = 0, y = 0, z = 0;
  constexpr Vec3() = default;
  constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3& operator+=(Vec3 b) { x += b.x; y += b.y; z += b.z; return *this; }
  constexpr Vec3& operator-=(Vec3 b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
  constexpr Vec3& operator*=(Vec3 b) { x *= b.x; y *= b.y; z *= b.z; return *this; }
  constexpr Vec3& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
  constexpr Vec3& operator/=(float s) { return *this *= 1.0f / s; }
  constexpr bool operator==(const Vec3&) const = default;
};
/// Linear RGB radiance or reflectance (Rec.709 primaries).
using Color = Vec3;

constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
constexpr Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator*(float s, Vec3 a) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator/(Vec3 a, float s) { return a * (1.0f / s); }
constexpr Vec3 operator/(Vec3 a, Vec3 b) { return {a.x / b.x, a.y / b.y, a.z / b.z}; }

constexpr float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length_squared(Vec3 a) { return dot(a, a); }
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { return a / length(a); }
/// a itself when it is unit to float precision (|a|^2 within 4e-7 of 1: a few ulps, as a normalised vector or a
/// direction turned by an orthonormal frame comes out), else normalize(a): no square root or division on the
/// common path.
inline Vec3 normalize_unless_unit(Vec3 a) {
  const float l2 = dot(a, a);
  return std::abs(l2 - 1) <= 4e-7f ? a : a / std::sqrt(l2);
}
inline Vec3 abs(Vec3 a) { return {std::abs(a.x), std::abs(a.y), std::abs(a.z)}; }
inline Vec3 min(Vec3 a, Vec3 b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
inline Vec3 max(Vec3 a, Vec3 b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
inline float max_component(Vec3 a) { return std::max(a.x, std::max(a.y, a.z)); }
inline float min_component(Vec3 a) { return std::min(a.x, std::min(a.y, a.z)); }
inline Vec3 lerp(float t, Vec3 a, Vec3 b) { return a * (1 - t) + b * t; }
inline bool is_finite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
/// |a| for any finite a. |a|^2 overflows float for |a| beyond ~1e19 (the cross product of two ~4e9-unit edges) and
/// underflows below ~1e-19, so outside 1e-15 <= |a| <= 1e15 a is scaled by its largest component first; inside,
/// exactly length(a). 0 for a zero or non-finite a.
inline float robust_length(Vec3 a) {
  const float l2 = length_squared(a);
  if (l2 >= 1e-30f && l2 <= 1e30f) return std::sqrt(l2);
  const float m = max_component(abs(a));
  if (!(m > 0) || !is_finite(a)) return 0;
  return m * length({a.x / m, a.y / m, a.z / m});
}
/// a / |a| for any finite non-zero a, without overflow or underflow of |a|^2 (as robust_length; elsewhere exactly
/// normalize(a)); the zero vector for a zero or non-finite a.
inline Vec3 robust_normalize(Vec3 a) {
  const float l2 = length_squared(a);
  if (l2 >= 1e-30f && l2 <= 1e30f) return a / std::sqrt(l2);
  const float m = max_component(abs(a));
  if (!(m > 0) || !is_finite(a)) return {};
  return normalize({a.x / m, a.y / m, a.z / m});
}
inline bool is_black(Color c) { return c.x == 0 && c.y == 0 && c.z == 0; }
/// Rec.709 luminance of linear RGB.
inline float luminance(Color c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
/// Reflect w about n (both unit, same hemisphere convention as pbrt: result points away).
inline Vec3 reflect(Vec3 w, Vec3 n) { return 2.0f * dot(w, n) * n - w; }

struct Vec4 {
  float x = 0, y = 0, z = 0, w = 0;
  constexpr Vec4() = default;
  constexpr Vec4(float x_, float y_, float z_, float w_) : x(x_), y(y_), z(z_), w(w_) {}
  constexpr Vec3 xyz() const { return {x, y, z}; }
  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w)); }
};

inline float clamp(float v, float lo, float hi) { return std::min(std::max(v, lo), hi); }
inline float safe_sqrt(float v) { return std::sqrt(std::max(v, 0.0f)); }
inline float safe_acos(float v) { return std::acos(clamp(v, -1.0f, 1.0f)); }
inline float safe_asin(float v) { return std::asin(clamp(v, -1.0f, 1.0f)); }
inline float sqr(float v) { return v * v; }

/// sin and cos of the angle 2 pi t (t in turns, |t| <= 1e6), within one float ulp: an exact reduction to a quarter
/// turn and the Taylor series of sin and cos there in double (truncation error below 1e-11). No branch and no
/// library call, so a loop over many angles vectorises (lights/sphere_light_batch.cpp); a file that needs the
/// same numbers in a vectorised and a one-at-a-time copy compiles both without contraction (-ffp-contract=off).
inline void sincos_turns(float t, float& sin_out, float& cos_out) {
  constexpr float kRound = 12582912.0f;  // 1.5 * 2^23: (v + kRound) - kRound rounds v to an integer
  const float q = (4 * t + kRound) - kRound;
  const int quadrant = static_cast<int>(q) & 3;
  const double x = static_cast<double>(4 * t - q) * 1.5707963267948966;  // |x| <= pi/4; 4 t - q is exact
  const double x2 = x * x;
  const double s = x * (1 + x2 * (-1 / 6.0 + x2 * (1 / 120.0 + x2 * (-1 / 5040.0 + x2 * (1 / 362880.0 +
                                                                                    x2 * (-1 / 39916800.0))))));
  const double c = 1 + x2 * (-1 / 2.0 + x2 * (1 / 24.0 + x2 * (-1 / 720.0 + x2 * (1 / 40320.0 + x2 * (
                                                                  -1 / 3628800.0 + x2 * (1 / 479001600.0))))));
  const float sf = static_cast<float>(s), cf = static_cast<float>(c);
  const bool odd = quadrant & 1;
  sin_out = (quadrant & 2 ? -1.0f : 1.0f) * (odd ? cf : sf);
  cos_out = ((quadrant + 1) & 2 ? -1.0f : 1.0f) * (odd ? sf : cf);
}

/// (cos, sin) of the angle 2 pi t, t in turns: the azimuth the direction samplers take precomputed, so that a path
/// batch computes its lanes' azimuths side by side (sincos_turns_many in core/sincos_batch.h, the same values).
inline Vec2 turn_azimuth(float t) {
  float s, c;
  sincos_turns(t, s, c);
  return {c, s};
}

/// Storage for N objects of a trivially destructible T, left uninitialised: scratch arrays in hot loops that are
/// written before they are read (a T[N] of the vector types above is zeroed by their member initialisers).
template <class T, int N>
union Uninitialised {
  Uninitialised() {}
  T v[N];
  T& operator[](int i) { return v[i]; }
  const T& operator[](int i) const { return v[i]; }
  T* data() { return v; }
};

/// Axis-aligned bounding box.
struct Bounds3 {
  Vec3 lo{INFINITY, INFINITY, INFINITY};
  Vec3 hi{-INFINITY, -INFINITY, -INFINITY};
  void expand(Vec3 p) { lo = min(lo, p); hi = max(hi, p); }
  void expand(const Bounds3& b) { lo = min(lo, b.lo); hi = max(hi, b.hi); }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  Vec3 center() const { return (lo + hi) * 0.5f; }
  Vec3 diagonal() const { return hi - lo; }
};

}  // namespace lumis
