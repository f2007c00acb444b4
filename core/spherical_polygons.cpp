// Solid angles of triangles and rectangles seen from a point, and uniform sampling of them by solid angle:
// Arvo 1995 ("Stratified sampling of spherical triangles") and Urena, Fajardo & King 2013 ("An area-preserving
// parametrization for spherical rectangles"). All arithmetic is in double: both algorithms take differences of
// angles whose sum is close to pi (small triangles), which float cannot resolve below ~1e-3 sr.
//
// Failure (nullopt) depends only on the geometry (p and the polygon), never on u, so a caller can ask "would
// sampling succeed from here?" with any u and reproduce the choice in its pdf. Arvo's steps themselves are in
// core/spherical_triangle.h, shared with the batch kernel that mesh lights use.
#include <algorithm>
#include <cmath>

#include "core/spherical_triangle.h"
#include "core/warp.h"

namespace lumis {
namespace {

using namespace sph_tri;  // D3 and its operations, the solid-angle limits, the shared triangle steps

// Urena et al. 2013, section 3: the rectangle in a frame with x, y along its edges and the receiver at the origin
// on the negative-z side (z0 < 0).
struct SphericalRect {
  D3 o, x, y, z;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0, z0 = 0;
  double b0 = 0, b1 = 0, k = 0, s = 0;
  bool resolved = false;  ///< s can reach kMinSolidAngle by the bound below (smaller s is rounding noise)
};

SphericalRect make_spherical_rect(Vec3 p, Vec3 origin, Vec3 ex, Vec3 ey) {
  SphericalRect r;
  r.o = to_d(p);
  const D3 dex = to_d(ex), dey = to_d(ey);
  const double exl = dlen(dex), eyl = dlen(dey);
  if (!(exl > 0 && eyl > 0)) return r;
  r.x = dex * (1 / exl);
  r.y = dey * (1 / eyl);
  r.z = dcross(r.x, r.y);
  const D3 d = to_d(origin) - r.o;
  r.z0 = ddot(d, r.z);
  if (r.z0 > 0) {
    r.z = r.z * -1.0;
    r.z0 = -r.z0;
  }
  r.x0 = ddot(d, r.x);
  r.y0 = ddot(d, r.y);
  r.x1 = r.x0 + exl;
  r.y1 = r.y0 + eyl;
  if (!(r.z0 < 0)) return r;  // receiver in the plane: solid angle 0 or 2 pi, both degenerate
  // Every point of the rectangle is at least dmin away, so its solid angle is at most area |z0| / dmin^3. Below
  // kMinSolidAngle by that bound, the four angles below differ from pi / 2 by less than their rounding (the cross
  // products of nearly parallel corners): a rectangle of 1e-13 at 2.5 units came out at 1e-6 to 3e-6 sr from one
  // receiver in twenty, not 1e-27, and rendered 1e20 times too bright. Sampling then fails (area sampling instead),
  // whatever s says.
  const double dx = std::max({0.0, r.x0, -r.x1}), dy = std::max({0.0, r.y0, -r.y1});
  const double dmin2 = r.z0 * r.z0 + dx * dx + dy * dy;
  r.resolved = exl * eyl * -r.z0 >= kMinSolidAngle * dmin2 * std::sqrt(dmin2);
  const D3 v00{r.x0, r.y0, r.z0}, v01{r.x0, r.y1, r.z0}, v10{r.x1, r.y0, r.z0}, v11{r.x1, r.y1, r.z0};
  // Normals of the planes through the origin and each edge, all pointing into the pyramid.
  const D3 n0 = dnormalize(dcross(v00, v10)), n1 = dnormalize(dcross(v10, v11));
  const D3 n2 = dnormalize(dcross(v11, v01)), n3 = dnormalize(dcross(v01, v00));
  const double g0 = std::acos(dclamp(-ddot(n0, n1), -1, 1)), g1 = std::acos(dclamp(-ddot(n1, n2), -1, 1));
  const double g2 = std::acos(dclamp(-ddot(n2, n3), -1, 1)), g3 = std::acos(dclamp(-ddot(n3, n0), -1, 1));
  r.b0 = n0.z;
  r.b1 = n2.z;
  r.k = 2 * kDPi - g2 - g3;
  r.s = std::max(g0 + g1 - r.k, 0.0);  // four-angle formula: sum of interior angles - 2 pi
  return r;
}

// General-length form of Van Oosterom & Strackee on the corners relative to the receiver, so no normalisation of
// near-zero vectors is needed.
double triangle_solid_angle_d(D3 da, D3 db, D3 dc) {
  const double la = dlen(da), lb = dlen(db), lc = dlen(dc);
  const double num = std::abs(ddot(da, dcross(db, dc)));
  const double den = la * lb * lc + ddot(da, db) * lc + ddot(da, dc) * lb + ddot(db, dc) * la;
  return 2 * std::atan2(num, den);
}

}  // namespace

float triangle_solid_angle(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const D3 dp = to_d(p);
  return static_cast<float>(triangle_solid_angle_d(to_d(a) - dp, to_d(b) - dp, to_d(c) - dp));
}

float parallelogram_solid_angle(Vec3 p, Vec3 origin, Vec3 ex, Vec3 ey) {
  // The corners in double relative to p: corners summed in float coincide once the edges are below an ulp of the
  // origin (a quad of 1e-13 at 0.3 had solid angle 0, so importance-based selection never chose it).
  const D3 a = to_d(origin) - to_d(p), dx = to_d(ex), dy = to_d(ey);
  const D3 n = dcross(dx, dy), m = a + (dx + dy) * 0.5;
  const double m2 = ddot(m, m);
  // Edges below 1e-3 of the distance to the centre: area |cos| / d^2 there, within ~1e-5; the triple products below
  // would be rounding noise for the tiniest.
  if (std::max(ddot(dx, dx), ddot(dy, dy)) < 1e-6 * m2)
    return static_cast<float>(std::abs(ddot(n, m)) / (m2 * std::sqrt(m2)));
  const D3 b = a + dx, c = b + dy, d = a + dy;
  return static_cast<float>(triangle_solid_angle_d(a, b, c) + triangle_solid_angle_d(a, c, d));
}

std::optional<SphericalSample> sample_spherical_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c, Vec2 u) {
  const sph_tri::Sample r = sph_tri::sample(p, a, b, c, u);  // core/spherical_triangle.h, shared with the batch
  if (!r.ok) return std::nullopt;
  return SphericalSample{r.w, r.pdf};
}

std::optional<float> spherical_triangle_pdf(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const UnitTriangle t = unit_triangle(p, a, b, c);
  if (!t.ok) return std::nullopt;
  return static_cast<float>(1 / t.area);
}

Vec2 invert_spherical_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c, Vec3 w) {
  const UnitTriangle t = unit_triangle(p, a, b, c);
  if (!(t.area > 0)) return {0, 0};
  const D3 A = t.a, B = t.b, C = t.c, W = dnormalize(to_d(w));
  // C' is where the great circle through B and w meets arc AC; pick the antipode lying between A and C.
  D3 c_sub = dnormalize(dcross(dcross(B, W), dcross(C, A)));
  if (ddot(c_sub, A + C) < 0) c_sub = c_sub * -1.0;
  const double u0 = unit_triangle_solid_angle(A, B, c_sub) / t.area;
  const double den = 1 - ddot(c_sub, B);
  const double u1 = den > 0 ? (1 - ddot(W, B)) / den : 0;
  return {static_cast<float>(dclamp(u0, 0, 1)), static_cast<float>(dclamp(u1, 0, 1))};
}

float rectangle_solid_angle(Vec3 p, Vec3 origin, Vec3 ex, Vec3 ey) {
  return static_cast<float>(make_spherical_rect(p, origin, ex, ey).s);
}

std::optional<float> spherical_rectangle_pdf(Vec3 p, Vec3 origin, Vec3 ex, Vec3 ey) {
  const SphericalRect r = make_spherical_rect(p, origin, ex, ey);
  if (!(r.resolved && r.s >= kMinSolidAngle && r.s <= kMaxSolidAngle)) return std::nullopt;
  return static_cast<float>(1 / r.s);
}

std::optional<SphericalSample> sample_spherical_rectangle(Vec3 p, Vec3 origin, Vec3 ex, Vec3 ey, Vec2 u) {
  const SphericalRect r = make_spherical_rect(p, origin, ex, ey);
  if (!(r.resolved && r.s >= kMinSolidAngle && r.s <= kMaxSolidAngle)) return std::nullopt;
  // u.x picks the x of the point through the area of the sub-rectangle left of it (the angle au)...
  const double au = u.x * r.s + r.k;
  const double fu = (std::cos(au) * r.b0 - r.b1) / std::sin(au);
  double cu = (fu > 0 ? 1.0 : -1.0) / std::sqrt(fu * fu + r.b0 * r.b0);
  cu = dclamp(cu, -1, 1);
  double xu = -(cu * r.z0) / std::sqrt(std::max(1e-300, 1 - cu * cu));
  xu = std::isfinite(xu) ? dclamp(xu, r.x0, r.x1) : 0.5 * (r.x0 + r.x1);
  // ...and u.y is uniform in the sine of the elevation along that vertical line, which is uniform in solid angle.
  const double dd = std::sqrt(xu * xu + r.z0 * r.z0);
  const double h0 = r.y0 / std::sqrt(dd * dd + r.y0 * r.y0), h1 = r.y1 / std::sqrt(dd * dd + r.y1 * r.y1);
  const double hv = h0 + u.y * (h1 - h0), hv2 = hv * hv;
  const double yv = hv2 < 1 - 1e-12 ? (hv * dd) / std::sqrt(1 - hv2) : r.y1;
  const D3 local = r.x * xu + r.y * dclamp(yv, r.y0, r.y1) + r.z * r.z0;
  return SphericalSample{to_f(dnormalize(local)), static_cast<float>(1 / r.s)};
}

}  // namespace lumis
