// Emissive triangle mesh (world space). A triangle is chosen with probability proportional to an estimate of its
// emitted power, then a direction toward it by solid angle (Arvo's spherical triangle) or by area, converted to
// solid angle. The estimate only has to be positive wherever emission can be non-zero: the pdf uses the very same
// probabilities, so any such choice is unbiased. A cut-out (alphaMode MASK) emits nothing: rays pass through it, so
// a sample that lands in it is empty (its density still counts it, as a black texel's does).
#include <cmath>
#include <memory>

#include "core/distribution.h"
#include "core/simd.h"
#include "core/spherical_triangle_batch.h"
#include "core/warp.h"
#include "lights/light.h"

namespace lumis {
namespace {

class MeshLight final : public Light {
 public:
  MeshLight(const TriangleMesh& mesh, Color factor, std::optional<Texture> texture, bool two_sided,
            TriangleSampling method)
      : positions_(mesh.positions), indices_(mesh.indices), factor_(factor), texture_(std::move(texture)),
        two_sided_(two_sided), method_(method) {
    if (texture_) uvs_ = texture_->tex_coord == 1 ? mesh.uv1 : mesh.uv0;
    if (mesh.alpha) {  // what alpha_at() reads: indices, vertex colours, uv sets and the mask
      mask_ = std::make_unique<TriangleMesh>();
      mask_->indices = mesh.indices, mask_->colors = mesh.colors, mask_->uv0 = mesh.uv0, mask_->uv1 = mesh.uv1;
      mask_->alpha = mesh.alpha;
    }
    const size_t n = indices_.size() / 3;
    normals_.resize(n);
    area_.resize(n);
    std::vector<float> weight(n);
    Bounds3 box;
    for (size_t t = 0; t < n; ++t) {
      const Vec3 a = vertex(t, 0), b = vertex(t, 1), c = vertex(t, 2);
      box.expand(a);
      box.expand(b);
      box.expand(c);
      const Vec3 cr = cross(b - a, c - a);
      area_[t] = 0.5f * robust_length(cr);  // not length(cr): |cr|^2 overflows for edges beyond ~1e9 units
      normals_[t] = area_[t] > 0 ? robust_normalize(cr) : Vec3{};
      // Luminance at the centroid, plus 1% of the factor's so that a triangle whose centroid texel is black but
      // whose corners glow keeps a positive probability.
      const float lum = luminance(radiance_at(t, {1.0f / 3, 1.0f / 3, 1.0f / 3}));
      weight[t] = area_[t] * (std::max(lum, 0.0f) + 0.01f * std::max(luminance(factor_), 0.0f));
      // Power and importance use the same weights, so neither is ever 0 where the mesh can emit.
      power_ += kPi * weight[t] * (two_sided_ ? 2 : 1);
      total_area_ += area_[t];
    }
    triangles_ = Distribution1D(weight);
    if (!box.empty()) {
      center_ = box.center();
      for (uint32_t i : indices_) radius_ = std::max(radius_, length(positions_[i] - center_));
    }
  }

  /// Solid angle at ctx.p: pmf(triangle) x the triangle's solid-angle density.
  std::optional<LightSample> sample(const LightSampleContext& ctx, Vec2 u) const override {
    if (triangles_.size() == 0) return std::nullopt;
    const Choice ch = choose(ctx, u);
    if (!ch.emits) return std::nullopt;
    const std::optional<SphericalSample> ss =
        method_ == TriangleSampling::SphericalTriangle
            ? sample_spherical_triangle(ctx.p, vertex(ch.t, 0), vertex(ch.t, 1), vertex(ch.t, 2), ch.v)
            : std::nullopt;
    return finish(ctx, ch, ss);
  }

  /// sample() for n receivers (solid angle at each): the spherical triangles side by side
  /// (core/spherical_triangle_batch.cpp), the same numbers.
  void sample_many(const LightSampleContext* ctx, const Vec2* u, int n, LightSample* out, bool* ok) const override {
    if (method_ != TriangleSampling::SphericalTriangle || triangles_.size() == 0) {
      Light::sample_many(ctx, u, n, out, ok);
      return;
    }
    const int level = simd_level();
    sph_tri::Batch b;
    Choice ch[sph_tri::Batch::kChunk];
    for (int begin = 0; begin < n; begin += sph_tri::Batch::kChunk) {
      const int m = std::min(sph_tri::Batch::kChunk, n - begin);
      for (int k = 0; k < m; ++k) {
        const Vec3 p = ctx[begin + k].p;
        ch[k] = choose(ctx[begin + k], u[begin + k]);
        const Vec3 a = vertex(ch[k].t, 0), bb = vertex(ch[k].t, 1), c = vertex(ch[k].t, 2);
        b.px[k] = p.x, b.py[k] = p.y, b.pz[k] = p.z;
        b.ax[k] = a.x, b.ay[k] = a.y, b.az[k] = a.z;
        b.bx[k] = bb.x, b.by[k] = bb.y, b.bz[k] = bb.z;
        b.cx[k] = c.x, b.cy[k] = c.y, b.cz[k] = c.z;
        b.ux[k] = ch[k].v.x, b.uy[k] = ch[k].v.y;
      }
      sph_tri::run(b, m, level);
      for (int k = 0; k < m; ++k) {
        std::optional<SphericalSample> ss;
        if (b.ok[k]) ss = SphericalSample{{b.wx[k], b.wy[k], b.wz[k]}, b.pdf[k]};
        const std::optional<LightSample> ls = ch[k].emits ? finish(ctx[begin + k], ch[k], ss) : std::nullopt;
        ok[begin + k] = ls.has_value();
        if (ls) out[begin + k] = *ls;
      }
    }
  }

  /// Solid angle at ctx.p for the triangle on_light.prim_id (a direction crossing several triangles has one such
  /// density per crossing; the caller sums them when it needs the density of the direction).
  float pdf(const LightSampleContext& ctx, Vec3 wi, const Hit& on_light) const override {
    const size_t t = on_light.prim_id;
    if (t >= area_.size() || !emits_toward(t, ctx.p)) return 0;
    const float pmf = triangles_.pmf(t);
    if (method_ == TriangleSampling::SphericalTriangle) {
      if (const auto pdf = spherical_triangle_pdf(ctx.p, vertex(t, 0), vertex(t, 1), vertex(t, 2))) return *pdf * pmf;
    }
    const float cos_l = std::abs(dot(normals_[t], wi));
    if (!(cos_l > 0)) return 0;
    return length_squared(on_light.p - ctx.p) / (cos_l * area_[t]) * pmf;
  }

  /// Radiance leaving triangle on_light.prim_id toward w: factor x texture(uv); front face only unless two-sided.
  Color le(const Hit& on_light, Vec3 w) const override {
    const size_t t = on_light.prim_id;
    if (t >= area_.size()) return {};
    if (!two_sided_ && !(dot(normals_[t], w) > 0)) return {};
    if (!texture_) return factor_;
    return factor_ * texture_->sample(on_light.uv[texture_->tex_coord == 1 ? 1 : 0]).xyz();
  }

  /// Bounding-sphere cap solid angle x mean luminance: a conservative stand-in that is 0 only when the whole
  /// bounding sphere lies below the receiver's horizon.
  float importance(const LightSampleContext& ctx) const override {
    if (!(total_area_ > 0)) return 0;
    const Vec3 to_c = center_ - ctx.p;
    if (dot(ctx.n, to_c) < -radius_) return 0;
    const float d2 = length_squared(to_c);
    const float solid_angle =
        d2 <= radius_ * radius_ ? 4 * kPi : 2 * kPi * one_minus_cos_from_sin2(radius_ * radius_ / d2);
    const float mean_lum = power_ / (kPi * total_area_ * (two_sided_ ? 2 : 1));
    return solid_angle * mean_lum;
  }

  /// Sum over triangles of pi x area x (estimated) luminance, twice when two-sided.
  float power() const override { return power_; }
  std::string name() const override { return "mesh"; }

 private:
  /// The triangle a sample draws (by power, u.x reused within its bin), its 2D number, and whether it emits
  /// toward the receiver at all.
  struct Choice {
    size_t t;
    Vec2 v;
    bool emits;
  };
  Choice choose(const LightSampleContext& ctx, Vec2 u) const {
    float u_tri = 0;
    const size_t t = triangles_.sample_discrete(u.x, nullptr, &u_tri);
    return {t, {std::min(u_tri, kOneMinusEpsilon), u.y}, emits_toward(t, ctx.p)};
  }
  /// The sample toward triangle ch.t from the spherical sample ss (solid angle) or, where that failed (nullopt),
  /// by area converted to solid angle.
  std::optional<LightSample> finish(const LightSampleContext& ctx, const Choice& ch,
                                    const std::optional<SphericalSample>& ss) const {
    const size_t t = ch.t;
    const Vec3 a = vertex(t, 0), b = vertex(t, 1), c = vertex(t, 2), n = normals_[t];
    Vec3 wi, p_light, bary;
    float dist, pdf, err;
    // Spherical sampling fails for reasons of geometry only, never of u, so the fallback is a function of
    // (receiver, triangle) that pdf() reproduces.
    if (ss) {
      const float denom = dot(ss->w, n);
      if (denom == 0) return std::nullopt;
      wi = ss->w;
      dist = dot(a - ctx.p, n) / denom;
      if (!(dist > 0)) return std::nullopt;
      p_light = ctx.p + wi * dist;
      pdf = ss->pdf;
      // From the receiver, the distance and the edges: dist comes from a - p, and the corner a is within dist + edges.
      err = sampled_point_error(ctx.p, dist, max_component(abs(b - a)) + max_component(abs(c - a)));
      if (texture_ || mask_) bary = barycentrics(t, p_light);  // only a texture's or a mask's lookup needs them
    } else {
      const Vec2 b01 = sample_uniform_triangle(ch.v);
      bary = {b01.x, b01.y, 1 - b01.x - b01.y};
      p_light = a * bary.x + b * bary.y + c * bary.z;
      const Vec3 to_p = p_light - ctx.p;
      const float dist2 = length_squared(to_p);
      dist = std::sqrt(dist2);
      if (!(dist > 0)) return std::nullopt;
      wi = to_p / dist;
      const float cos_l = std::abs(dot(n, wi));
      if (!(cos_l > 0)) return std::nullopt;
      pdf = dist2 / (cos_l * area_[t]);
      // From the corners: a x b0 + b x b1 + c x b2 rounds by under 2 units in the last place of the largest.
      err = sampled_point_error({}, dist, max_component(max(abs(a), max(abs(b), abs(c)))));
    }
    if (mask_ && alpha_at(*mask_, static_cast<unsigned>(t), bary.y, bary.z) < mask_->alpha->cutoff)
      return std::nullopt;
    pdf *= triangles_.pmf(t);
    return std::make_optional<LightSample>(radiance_at(t, bary), wi, dist, pdf, p_light, n, err);
  }
  Vec3 vertex(size_t t, int k) const { return positions_[indices_[3 * t + k]]; }
  bool emits_toward(size_t t, Vec3 p) const {
    if (!(area_[t] > 0)) return false;
    return two_sided_ || dot(p - vertex(t, 0), normals_[t]) > 0;
  }
  // Barycentrics (weights of vertices 0, 1, 2) of a point in the plane of triangle t.
  Vec3 barycentrics(size_t t, Vec3 p) const {
    const Vec2 b = triangle_barycentrics(p, vertex(t, 0), vertex(t, 1), vertex(t, 2));
    return {1 - b.x - b.y, b.x, b.y};
  }
  Color radiance_at(size_t t, Vec3 bary) const {
    if (!texture_) return factor_;
    Vec2 uv{0, 0};
    if (!uvs_.empty()) {
      for (int k = 0; k < 3; ++k) {
        const Vec2 vk = uvs_[indices_[3 * t + k]];
        uv = uv + vk * bary[k];
      }
    }
    return factor_ * texture_->sample(uv).xyz();
  }

  std::vector<Vec3> positions_;
  std::vector<uint32_t> indices_;
  std::vector<Vec2> uvs_;
  std::vector<Vec3> normals_;
  std::vector<float> area_;
  Color factor_;
  std::optional<Texture> texture_;
  std::unique_ptr<TriangleMesh> mask_;  // the cut-out, when the mesh has one
  bool two_sided_;
  TriangleSampling method_;
  Distribution1D triangles_;
  float power_ = 0, total_area_ = 0;
  Vec3 center_;
  float radius_ = 0;
};

}  // namespace

std::unique_ptr<Light> make_mesh_light(const TriangleMesh& mesh, Color factor, std::optional<Texture> texture,
                                       bool two_sided, TriangleSampling method) {
  return std::make_unique<MeshLight>(mesh, factor, std::move(texture), two_sided, method);
}

}  // namespace lumis
