// Light interface. All densities are per unit solid angle at the receiving point; choosing WHICH light is a
// separate probability (lights/light_selection.h). pdf() works independently of sample(), as MIS needs.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/math.h"
#include "core/texture.h"
#include "core/warp.h"

namespace lumis {

/// The receiving point: position and the surface normal there (zero normal: a point in free space, no horizon).
struct LightSampleContext {
  Vec3 p;
  Vec3 n;
};

/// A sphere light's parameters, for selection loops that evaluate many spheres without a virtual call each.
struct SphereEmitter {
  Vec3 center;
  float radius = 0;
  float luminance = 0;  ///< luminance of its radiance
};

/// 1 - cos of the half-angle of the cap a sphere of squared radius r2 subtends from squared distance d2 > r2.
inline float sphere_cap_one_minus_cos(float r2, float d2) { return one_minus_cos_from_sin2(std::min(r2 / d2, 1.0f)); }

/// Selection importance of a one-sided sphere emitter at ctx (lecture): cap solid angle x luminance; 0 from inside
/// (nothing is emitted inward) and when the sphere lies entirely below the horizon (n.(c - p) < -r). Written without
/// branches, so that the selector's loop over many spheres vectorises (lights/light_selection.cpp).
inline float sphere_importance(const SphereEmitter& s, const LightSampleContext& ctx) {
  const Vec3 to_c = s.center - ctx.p;
  const float d2 = length_squared(to_c);
  const float r2 = s.radius * s.radius;
  const bool hidden = (d2 <= r2) | (dot(ctx.n, to_c) < -s.radius);  // no short circuit: no branch
  const float importance = 2 * kPi * sphere_cap_one_minus_cos(r2, d2) * s.luminance;
  return hidden ? 0.0f : importance;
}

/// Rounding-error bound (world units, per axis) of a sampled light point (LightSample::p_error): p is the receiver
/// when the point is computed from it (p + t wi; {} otherwise), extent the largest magnitudes of what else goes in
/// (the light's edges, or its coordinates for an area sample). dist always counts: shadow_ray (core/ray.h) relies
/// on every bound being at least kErrorScale x dist.
inline float sampled_point_error(Vec3 p, float dist, float extent) {
  return (max_component(abs(p)) + dist + extent) * kErrorScale;
}

// The sample structs below have constructors so that std::make_optional<T>(members...) builds them in place: a
// T built in a temporary and then copied into the optional is read back 16 bytes at a time from 4-byte stores, and
// every such read waits on a failed store forward (docs/performance.md, "Store forwarding").
struct LightSample {
  LightSample() = default;
  /// le, wi, dist, pdf, p_light, n_light, p_error (the members themselves are ordered by slot).
  LightSample(Color le_, Vec3 wi_, float dist_, float pdf_, Vec3 p_light_, Vec3 n_light_, float p_error_)
      : wi(wi_), dist(dist_), p_light(p_light_), pdf(pdf_), n_light(n_light_), p_error(p_error_), le(le_) {}
  // In 16-byte slots (a Vec3 and a float each), like Ray in core/ray.h.
  Vec3 wi;           ///< unit world direction from the receiver toward the light
  float dist = 0;    ///< distance to the sampled light point (INFINITY for the environment)
  Vec3 p_light;      ///< sampled point on the light (unused for the environment)
  float pdf = 0;     ///< solid-angle density of wi at the receiver
  Vec3 n_light;      ///< light surface normal at p_light
  float p_error = 0; ///< rounding-error bound of p_light, per axis (world units; 0 for the environment)
  alignas(16) Color le;  ///< radiance arriving at the receiver along -wi (before visibility)
};

class Light {
 public:
  virtual ~Light() = default;
  /// Sample a direction toward the light from ctx.p; density per unit solid angle at ctx.p.
  virtual std::optional<LightSample> sample(const LightSampleContext& ctx, Vec2 u) const = 0;
  /// sample() for n receivers (solid angle at each ctx[i]): out[i] where ok[i], ok[i] false where sample() gives
  /// nullopt. The same numbers as sample(); lights with a batch kernel override it (sphere).
  virtual void sample_many(const LightSampleContext* ctx, const Vec2* u, int n, LightSample* out, bool* ok) const {
    for (int i = 0; i < n; ++i) {
      const std::optional<LightSample> ls = sample(ctx[i], u[i]);
      ok[i] = ls.has_value();
      if (ok[i]) out[i] = *ls;
    }
  }
  /// Solid-angle density at ctx.p with which sample() would produce direction wi, arriving at `on_light`
  /// (the hit a BSDF ray made on this light). Environment: on_light is ignored.
  virtual float pdf(const LightSampleContext& ctx, Vec3 wi, const Hit& on_light) const = 0;
  /// Radiance leaving the light at on_light in world direction w (pointing away from the light).
  virtual Color le(const Hit& on_light, Vec3 w) const = 0;
  /// Radiance arriving along a ray that escaped the scene in direction d (environment lights only).
  virtual Color le_escaped(Vec3 /*d*/) const { return {}; }
  /// Selection importance at the receiver (lecture): solid angle x luminance(Le), 0 when the light is entirely
  /// below the receiver's horizon.
  virtual float importance(const LightSampleContext& ctx) const = 0;
  /// Total emitted power (luminance units, W-like), for power-proportional selection.
  virtual float power() const = 0;
  /// Called once with the scene bounds before rendering (environment: scene radius).
  virtual void preprocess(const Bounds3& /*scene_bounds*/) {}
  virtual bool is_environment() const { return false; }
  /// Sphere lights: their parameters (importance() is then sphere_importance of them); others: nullopt.
  virtual std::optional<SphereEmitter> sphere() const { return std::nullopt; }
  virtual std::string name() const = 0;
};

/// Triangle-mesh light sampling method.
enum class TriangleSampling { Area, SphericalTriangle };
/// Quad light sampling method.
enum class QuadSampling { Area, SphericalRectangle };

/// Emitting sphere (one-sided: emits outward). Lecture's spherical-cap sampling; area sampling from inside.
std::unique_ptr<Light> make_sphere_light(Vec3 center, float radius, Color radiance);
/// Emitting parallelogram origin + s edge_u + t edge_v; emits on the side of cross(edge_u, edge_v).
std::unique_ptr<Light> make_quad_light(Vec3 origin, Vec3 edge_u, Vec3 edge_v, Color radiance,
                                       QuadSampling method = QuadSampling::SphericalRectangle);
/// Emissive triangle mesh (world space; emits on the front face, both faces when two_sided). Radiance =
/// factor x texture (when given, looked up with the mesh's uv set); a cut-out (mesh.alpha) emits nothing, and
/// samples landing in it are empty. Triangles chosen by emitted power.
std::unique_ptr<Light> make_mesh_light(const TriangleMesh& mesh, Color factor, std::optional<Texture> texture,
                                       bool two_sided, TriangleSampling method = TriangleSampling::SphericalTriangle);
/// Constant-radiance environment.
std::unique_ptr<Light> make_constant_environment(Color radiance);
/// Equirectangular environment map (lat-long, +Y up), importance-sampled by luminance x sin(theta).
/// rotation_degrees rotates about +Y.
std::unique_ptr<Light> make_image_environment(std::shared_ptr<const Image> image, float scale, float rotation_degrees);

}  // namespace lumis
