// Environment lights at infinity: constant radiance (uniform sphere sampling) and an equirectangular map.
// The map is importance-sampled per texel (Distribution2D over luminance x texel solid angle) and uniformly in solid
// angle inside a texel, so the density is piecewise constant on the same cells as the nearest-texel radiance.
// Map convention: pixel column u in [0,1) is the azimuth phi = 2 pi u, row v in [0,1) (top row first) the polar
// angle theta = pi v from +Y, and d = (-sin theta sin phi, cos theta, sin theta cos phi): the image centre looks
// down -Z, its right half lies toward +X. rotation_degrees turns the map about +Y (counter-clockwise seen from +Y).
#include <cmath>
#include <stdexcept>

#include "core/distribution.h"
#include "core/image.h"
#include "core/warp.h"
#include "lights/light.h"

namespace lumis {
namespace {

class EnvironmentBase : public Light {
 public:
  /// The environment is not geometry: radiance arriving from -w, as for an escaped ray.
  Color le(const Hit& /*on_light*/, Vec3 w) const override { return le_escaped(-w); }
  void preprocess(const Bounds3& scene_bounds) override {
    if (!scene_bounds.empty()) scene_radius_ = std::max(0.5f * length(scene_bounds.diagonal()), 1e-3f);
  }
  bool is_environment() const override { return true; }
  /// Solid angle above the horizon (2 pi, or 4 pi with no normal) x mean luminance: never 0 for a lit sky.
  float importance(const LightSampleContext& ctx) const override {
    return (length_squared(ctx.n) > 0 ? 2 * kPi : 4 * kPi) * mean_luminance();
  }
  /// pi R^2 (scene disc) x integral of luminance over the sphere, as for a distant emitter lighting the scene.
  float power() const override { return kPi * scene_radius_ * scene_radius_ * 4 * kPi * mean_luminance(); }

 protected:
  virtual float mean_luminance() const = 0;
  std::optional<LightSample> make_sample(const LightSampleContext& ctx, Vec3 wi, float pdf) const {
    return make_sample(ctx, wi, pdf, le_escaped(wi));
  }
  std::optional<LightSample> make_sample(const LightSampleContext& ctx, Vec3 wi, float pdf, Color le) const {
    return std::make_optional<LightSample>(le, wi, INFINITY, pdf, ctx.p + wi * (2 * scene_radius_), -wi, 0.0f);
  }
  float scene_radius_ = 1;
};

class ConstantEnvironment final : public EnvironmentBase {
 public:
  explicit ConstantEnvironment(Color radiance) : radiance_(radiance) {}
  /// Uniform on the sphere, solid-angle density 1/(4 pi), whatever the receiver.
  std::optional<LightSample> sample(const LightSampleContext& ctx, Vec2 u) const override {
    return make_sample(ctx, sample_uniform_sphere(u), kInv4Pi);
  }
  /// Solid angle: 1/(4 pi) for every direction.
  float pdf(const LightSampleContext&, Vec3, const Hit&) const override { return kInv4Pi; }
  Color le_escaped(Vec3 /*d*/) const override { return radiance_; }
  std::string name() const override { return "constant_environment"; }

 private:
  float mean_luminance() const override { return std::max(luminance(radiance_), 0.0f); }
  Color radiance_;
};

class ImageEnvironment final : public EnvironmentBase {
 public:
  ImageEnvironment(std::shared_ptr<const Image> image, float scale, float rotation_degrees)
      : image_(std::move(image)), scale_(scale) {
    const float rot = rotation_degrees * kPi / 180;
    cos_rot_ = std::cos(rot);
    sin_rot_ = std::sin(rot);
    if (!image_ || image_->width <= 0 || image_->height <= 0 || image_->channels <= 0)
      throw std::invalid_argument("environment map: empty image");
    const int w = image_->width, h = image_->height;
    row_cos_.resize(static_cast<size_t>(h) + 1);
    for (int y = 0; y <= h; ++y) row_cos_[y] = std::cos(kPi * y / h);
    row_cos_[h] = -1;
    std::vector<float> f(static_cast<size_t>(w) * h);
    double lum_integral = 0;
    for (int y = 0; y < h; ++y) {
      const float dcos = row_cos_[y] - row_cos_[y + 1];  // texel solid angle = 2 pi / w * dcos
      for (int x = 0; x < w; ++x) {
        const float lum = std::max(luminance(image_->rgb(x, y)), 0.0f);
        f[static_cast<size_t>(y) * w + x] = lum * dcos;
        lum_integral += static_cast<double>(lum) * dcos * 2 * kPi / w;
      }
    }
    dist_ = Distribution2D(f, w, h);
    mean_lum_ = static_cast<float>(lum_integral / (4 * kPi)) * std::max(scale_, 0.0f);
  }

  /// Solid angle: P(texel) / (texel solid angle), uniform in solid angle inside each texel. The radiance is the
  /// sampled texel's: a direction on a texel's edge may look up its neighbour (rounding of the mapping), and the
  /// neighbour's radiance over this texel's density would be a firefly next to a bright texel.
  std::optional<LightSample> sample(const LightSampleContext& ctx, Vec2 u) const override {
    float pdf_uv = 0;
    const Vec2 uv = dist_.sample_continuous(u, &pdf_uv);
    if (!(pdf_uv > 0)) return std::nullopt;
    const int w = image_->width, h = image_->height;
    // The texel as Distribution2D::pdf() finds it (sample_continuous keeps uv inside the texel it chose).
    const int row = std::clamp(static_cast<int>(uv.y * h), 0, h - 1);
    const int col = std::clamp(static_cast<int>(uv.x * w), 0, w - 1);
    // The position inside the row is uniform; spend it uniformly in cos(theta), not in theta, so that the density
    // is constant over the texel's solid angle, like the nearest-texel radiance.
    const float frac = clamp(uv.y * h - row, 0.0f, 1.0f);
    const float cos_theta = clamp(row_cos_[row] + frac * (row_cos_[row + 1] - row_cos_[row]), -1.0f, 1.0f);
    const float sin_theta = safe_sqrt(1 - cos_theta * cos_theta);
    const float phi = 2 * kPi * uv.x;
    const Vec3 d_map{-sin_theta * std::sin(phi), cos_theta, sin_theta * std::cos(phi)};
    return make_sample(ctx, to_world(d_map), solid_angle_pdf(pdf_uv, row), image_->rgb(col, row) * scale_);
  }

  /// Solid angle, the density of sample() at wi (on_light unused).
  float pdf(const LightSampleContext&, Vec3 wi, const Hit&) const override {
    const Vec2 uv = direction_to_uv(to_map(normalize(wi)));
    const int h = image_->height;
    const int row = std::clamp(static_cast<int>(uv.y * h), 0, h - 1);
    return solid_angle_pdf(dist_.pdf({uv.x, (row + 0.5f) / h}), row);
  }

  /// Nearest texel, so that radiance is piecewise constant on exactly the cells the sampler uses: a texel with
  /// zero density never has non-zero radiance.
  Color le_escaped(Vec3 d) const override {
    const Vec2 uv = direction_to_uv(to_map(normalize(d)));
    const int x = std::clamp(static_cast<int>(uv.x * image_->width), 0, image_->width - 1);
    const int y = std::clamp(static_cast<int>(uv.y * image_->height), 0, image_->height - 1);
    return image_->rgb(x, y) * scale_;
  }
  std::string name() const override { return "image_environment"; }

 private:
  float mean_luminance() const override { return mean_lum_; }
  Vec3 to_world(Vec3 d) const { return {cos_rot_ * d.x + sin_rot_ * d.z, d.y, -sin_rot_ * d.x + cos_rot_ * d.z}; }
  Vec3 to_map(Vec3 d) const { return {cos_rot_ * d.x - sin_rot_ * d.z, d.y, sin_rot_ * d.x + cos_rot_ * d.z}; }
  // Density on [0,1)^2 -> per unit solid angle: a texel covers 1/(w h) of the square and (2 pi / w) dcos sr.
  float solid_angle_pdf(float pdf_uv, int row) const {
    const float dcos = row_cos_[row] - row_cos_[row + 1];
    return dcos > 0 ? pdf_uv / (static_cast<float>(image_->height) * 2 * kPi * dcos) : 0.0f;
  }
  static Vec2 direction_to_uv(Vec3 d) {
    float phi = std::atan2(-d.x, d.z);
    if (phi < 0) phi += 2 * kPi;
    const float u = std::min(phi * kInv2Pi, kOneMinusEpsilon);
    const float v = std::min(safe_acos(d.y) * kInvPi, kOneMinusEpsilon);
    return {u, v};
  }

  std::shared_ptr<const Image> image_;
  float scale_;
  float cos_rot_ = 1, sin_rot_ = 0;
  std::vector<float> row_cos_;  ///< cos(theta) at the h + 1 row boundaries, from +1 down to -1
  Distribution2D dist_;
  float mean_lum_ = 0;
};

}  // namespace

std::unique_ptr<Light> make_constant_environment(Color radiance) {
  return std::make_unique<ConstantEnvironment>(radiance);
}

std::unique_ptr<Light> make_image_environment(std::shared_ptr<const Image> image, float scale,
                                              float rotation_degrees) {
  return std::make_unique<ImageEnvironment>(std::move(image), scale, rotation_degrees);
}

}  // namespace lumis
