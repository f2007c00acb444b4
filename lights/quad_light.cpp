// Emitting parallelogram origin + s edge_u + t edge_v (s, t in [0,1]), one-sided toward cross(edge_u, edge_v).
// Sampling: uniform in the solid angle of the rectangle (Urena et al. 2013) when the edges are orthogonal and the
// solid angle is large enough to sample stably; otherwise uniform by area, converted to solid angle.
#include <cmath>

#include "core/warp.h"
#include "lights/light.h"

namespace lumis {
namespace {

class QuadLight final : public Light {
 public:
  QuadLight(Vec3 origin, Vec3 eu, Vec3 ev, Color radiance, QuadSampling method)
      : o_(origin), eu_(eu), ev_(ev), radiance_(radiance), method_(method) {
    const Vec3 c = cross(eu, ev);
    area_ = robust_length(c);  // not length(c): |c|^2 overflows for edges beyond ~1e9 units
    n_ = robust_normalize(c);
    // Relative tolerance: edges typed into a scene file as (1,0,0) and (0,0,1) rotated are orthogonal only to
    // rounding; anything further off is a parallelogram and is sampled by area.
    const float lu = length(eu), lv = length(ev);
    is_rectangle_ = lu > 0 && lv > 0 && std::abs(dot(eu, ev)) <= 1e-5f * lu * lv;
    edges_ = max_component(abs(eu)) + max_component(abs(ev));
    extent_ = max_component(abs(origin)) + edges_;
  }

  /// Solid angle at ctx.p; nullopt when the receiver is behind or in the plane (nothing is emitted toward it).
  std::optional<LightSample> sample(const LightSampleContext& ctx, Vec2 u) const override {
    if (!faces(ctx.p)) return std::nullopt;
    Vec3 wi, p_light;
    float dist, pdf, err;
    // sample_spherical_rectangle fails for reasons of geometry only (never of u): then every u falls back to area.
    const auto ss = method_ == QuadSampling::SphericalRectangle && is_rectangle_
                        ? sample_spherical_rectangle(ctx.p, o_, eu_, ev_, u)
                        : std::nullopt;
    if (ss) {
      const float denom = dot(ss->w, n_);
      if (!(denom < 0)) return std::nullopt;
      wi = ss->w;
      dist = dot(o_ - ctx.p, n_) / denom;
      p_light = ctx.p + wi * dist;
      pdf = ss->pdf;
      // From the receiver, the distance and the edges: dist comes from o - p, and the corner o is within dist + edges.
      err = sampled_point_error(ctx.p, dist, edges_);
    } else {
      p_light = o_ + eu_ * u.x + ev_ * u.y;
      const Vec3 to_p = p_light - ctx.p;
      const float dist2 = length_squared(to_p);
      dist = std::sqrt(dist2);
      if (!(dist > 0)) return std::nullopt;
      wi = to_p / dist;
      const float cos_l = -dot(n_, wi);
      if (!(cos_l > 0)) return std::nullopt;
      pdf = dist2 / (cos_l * area_);
      err = sampled_point_error({}, dist, extent_);  // from the corner and the edges
    }
    return std::make_optional<LightSample>(radiance_, wi, dist, pdf, p_light, n_, err);
  }

  /// Solid angle at ctx.p, as sample() would produce wi; only on_light.p is used (never prim_id).
  float pdf(const LightSampleContext& ctx, Vec3 wi, const Hit& on_light) const override {
    if (!faces(ctx.p)) return 0;
    if (const auto pdf = spherical_pdf(ctx.p)) return *pdf;
    const float cos_l = -dot(n_, wi);
    if (!(cos_l > 0)) return 0;
    return length_squared(on_light.p - ctx.p) / (cos_l * area_);
  }

  /// Radiance leaving the front side (the side of cross(edge_u, edge_v)) toward w.
  Color le(const Hit& /*on_light*/, Vec3 w) const override { return dot(n_, w) > 0 ? radiance_ : Color{}; }

  /// Solid angle (parallelogram_solid_angle, from the exact edges) x luminance; 0 when the receiver is behind the
  /// quad or every corner is on or below its horizon.
  float importance(const LightSampleContext& ctx) const override {
    if (!faces(ctx.p)) return 0;
    const Vec3 a = o_, b = o_ + eu_, c = o_ + eu_ + ev_, d = o_ + ev_;
    if (length_squared(ctx.n) > 0 && dot(ctx.n, a - ctx.p) <= 0 && dot(ctx.n, b - ctx.p) <= 0 &&
        dot(ctx.n, c - ctx.p) <= 0 && dot(ctx.n, d - ctx.p) <= 0)
      return 0;
    return parallelogram_solid_angle(ctx.p, o_, eu_, ev_) * luminance(radiance_);
  }

  /// pi x area x luminance (Lambertian, one side).
  float power() const override { return kPi * area_ * luminance(radiance_); }
  std::string name() const override { return "quad"; }

 private:
  bool faces(Vec3 p) const { return area_ > 0 && dot(p - o_, n_) > 0; }
  // The spherical-rectangle density from p: present exactly when sample() takes that branch, and the very value
  // (1 / solid angle) sample() reports.
  std::optional<float> spherical_pdf(Vec3 p) const {
    if (method_ != QuadSampling::SphericalRectangle || !is_rectangle_) return std::nullopt;
    return spherical_rectangle_pdf(p, o_, eu_, ev_);
  }

  Vec3 o_, eu_, ev_, n_;
  float area_ = 0;
  float edges_ = 0;   ///< |edge_u| + |edge_v| (max norms): how far a point of the quad lies from its corner
  float extent_ = 0;  ///< |origin| + edges_: the scale of an area-sampled point's rounding
  bool is_rectangle_ = false;
  Color radiance_;
  QuadSampling method_;
};

}  // namespace

std::unique_ptr<Light> make_quad_light(Vec3 origin, Vec3 edge_u, Vec3 edge_v, Color radiance, QuadSampling method) {
  return std::make_unique<QuadLight>(origin, edge_u, edge_v, radiance, method);
}

}  // namespace lumis
