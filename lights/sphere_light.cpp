// Spherical emitter, one-sided (emits outward only). From outside, directions are uniform in the cone the sphere
// subtends (lecture: z_min = sqrt(1 - r^2/|c|^2), p = 1/(2 pi (1 - z_min))); from inside or on the surface the
// sphere's outside is not visible, so nothing arrives, but sampling stays defined: uniform by area, converted to
// solid angle.
#include <algorithm>

#include "core/simd.h"
#include "core/warp.h"
#include "lights/sphere_cap.h"

namespace lumis {
namespace {

class SphereLight final : public Light {
 public:
  SphereLight(Vec3 center, float radius, Color radiance) : c_(center), r_(radius), radiance_(radiance) {}

  /// Solid angle at ctx.p: uniform in the subtended cap (outside), area sampling converted (inside).
  std::optional<LightSample> sample(const LightSampleContext& ctx, Vec2 u) const override {
    const Vec3 to_c = c_ - ctx.p;
    const float d2 = length_squared(to_c);
    if (!(r_ > 0)) return std::nullopt;
    if (d2 <= r_ * r_) return sample_area(ctx, u);
    const sphere_cap::Setup s = sphere_cap::setup(r_ * r_, d2, u);
    const sphere_cap::Point q = sphere_cap::finish(ctx.p, to_c, r_, s);
    // Every direction in the cap meets the sphere first on its near side, which faces the receiver: it emits.
    return std::make_optional<LightSample>(radiance_, q.wi, q.t, 1 / (2 * kPi * s.one_minus_cos_max), q.p, q.n,
                                           cap_point_error(ctx.p, q.t));
  }

  /// sample() for n receivers: the cap samples side by side (lights/sphere_light_batch.cpp), the same numbers.
  void sample_many(const LightSampleContext* ctx, const Vec2* u, int n, LightSample* out, bool* ok) const override {
    if (!(r_ > 0)) {
      std::fill(ok, ok + n, false);
      return;
    }
    const int level = simd_level();
    sphere_cap::Batch b;
    b.c = c_, b.r = r_;
    for (int begin = 0; begin < n; begin += sphere_cap::Batch::kChunk) {
      const int m = std::min(sphere_cap::Batch::kChunk, n - begin);
      for (int k = 0; k < m; ++k) {
        const Vec3 p = ctx[begin + k].p;
        b.px[k] = p.x, b.py[k] = p.y, b.pz[k] = p.z, b.ux[k] = u[begin + k].x, b.uy[k] = u[begin + k].y;
      }
      sphere_cap::run(b, m, level);
      for (int k = 0; k < m; ++k) {
        const int i = begin + k;
        if (length_squared(c_ - ctx[i].p) <= r_ * r_) {  // inside: by area, one at a time
          const std::optional<LightSample> ls = sample_area(ctx[i], u[i]);
          ok[i] = ls.has_value();
          if (ok[i]) out[i] = *ls;
          continue;
        }
        ok[i] = true;
        out[i] = LightSample(radiance_, {b.wx[k], b.wy[k], b.wz[k]}, b.t[k],
                             1 / (2 * kPi * b.one_minus_cos_max[k]), {b.lx[k], b.ly[k], b.lz[k]},
                             {b.nx[k], b.ny[k], b.nz[k]}, cap_point_error(ctx[i].p, b.t[k]));
      }
    }
  }

  /// Solid angle at ctx.p, the same density as sample() from this receiver; on_light is a hit on the sphere.
  /// The density is per direction: from outside, a ray crossing the sphere twice must be counted once (either hit).
  float pdf(const LightSampleContext& ctx, Vec3 wi, const Hit& on_light) const override {
    const float d2 = length_squared(c_ - ctx.p);
    if (!(r_ > 0)) return 0;
    if (d2 <= r_ * r_) {
      const Vec3 n = normalize(on_light.p - c_);
      const float cos_l = std::abs(dot(n, wi));
      const float dist2 = length_squared(on_light.p - ctx.p);
      return cos_l > 0 ? dist2 / (cos_l * area()) : 0.0f;
    }
    return 1 / (2 * kPi * cap_one_minus_cos(d2));
  }

  /// Radiance leaving on_light toward world direction w: outward side only.
  Color le(const Hit& on_light, Vec3 w) const override {
    return dot(on_light.p - c_, w) > 0 ? radiance_ : Color{};
  }

  /// Cap solid angle x luminance; 0 below the horizon (n.(c - p) < -r) and from inside (nothing emitted inward).
  float importance(const LightSampleContext& ctx) const override { return sphere_importance(params(), ctx); }
  std::optional<SphereEmitter> sphere() const override { return params(); }

  /// pi x area x luminance (Lambertian emitter).
  float power() const override { return kPi * area() * luminance(radiance_); }
  std::string name() const override { return "sphere"; }

 private:
  float area() const { return 4 * kPi * r_ * r_; }
  /// Rounding-error bound (world units, per axis) of a cap sample, p + t wi from receiver p: from the receiver's
  /// coordinates and the distance. With the light's added (until stop 59), shadow rays toward a light 0.1 under a
  /// ceiling 1e5 from the origin ended beyond the ceiling (Robustness.VariantsAgreeFarFromTheOrigin).
  float cap_point_error(Vec3 p, float t) const { return sampled_point_error(p, t, 0); }
  /// Rounding-error bound (world units, per axis) of an area sample, c + r n, at distance dist from the receiver.
  float area_point_error(float dist) const { return sampled_point_error({}, dist, max_component(abs(c_)) + r_); }
  SphereEmitter params() const { return {c_, r_, luminance(radiance_)}; }
  /// 1 - cos of the half-angle of the cap the sphere subtends from squared distance d2 > r^2.
  float cap_one_minus_cos(float d2) const { return sphere_cap_one_minus_cos(r_ * r_, d2); }

  // Uniform point on the sphere; solid-angle density dist^2 / (|cos| area) at the receiver.
  std::optional<LightSample> sample_area(const LightSampleContext& ctx, Vec2 u) const {
    const Vec3 n = sample_uniform_sphere(u);
    const Vec3 p = c_ + n * r_;
    const Vec3 to_p = p - ctx.p;
    const float dist2 = length_squared(to_p);
    if (!(dist2 > 0)) return std::nullopt;
    const float dist = std::sqrt(dist2);
    const Vec3 wi = to_p / dist;
    const float cos_l = std::abs(dot(n, wi));
    if (!(cos_l > 0)) return std::nullopt;
    return std::make_optional<LightSample>(dot(n, -wi) > 0 ? radiance_ : Color{}, wi, dist, dist2 / (cos_l * area()),
                                           p, n, area_point_error(dist));
  }

  Vec3 c_;
  float r_;
  Color radiance_;
};

}  // namespace

std::unique_ptr<Light> make_sphere_light(Vec3 center, float radius, Color radiance) {
  return std::make_unique<SphereLight>(center, radius, radiance);
}

}  // namespace lumis
