// Materials: per-hit evaluation of textures into a BSDF and a shading frame.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "core/frame.h"
#include "core/geometry.h"
#include "core/texture.h"
#include "materials/bsdf.h"

namespace lumis {

/// The glTF 2.0 metallic-roughness material's inputs (factors multiply textures, as glTF says).
struct PbrParams {
  Color base_color{1, 1, 1};
  float base_alpha = 1;
  std::optional<Texture> base_color_texture;        ///< linear RGB (decoded from sRGB) + alpha
  float metallic = 1, roughness = 1;
  std::optional<Texture> metallic_roughness_texture;  ///< G = roughness, B = metallic (linear)
  std::optional<Texture> normal_texture;            ///< tangent-space normal map (linear)
  float normal_scale = 1;
  Color emissive{0, 0, 0};                          ///< emissiveFactor x KHR_materials_emissive_strength
  std::optional<Texture> emissive_texture;          ///< linear RGB (decoded from sRGB)
  bool double_sided = false;
};

/// What shading needs at a hit: the BSDF and its local frame (frame.n is the shading normal, on the same side of
/// the surface as the geometric normal's front face).
struct ShadingPoint {
  Frame frame;
  Bsdf bsdf;
};

class Material {
 public:
  virtual ~Material() = default;
  /// Evaluate textures at the hit: BSDF plus shading frame (normal-mapped when the material has a normal map).
  virtual ShadingPoint shade(const Hit& hit) const = 0;
  /// Albedo for the AOV channel (base colour after textures).
  virtual Color albedo(const Hit& hit) const = 0;
};

/// Factories (one file per material in materials/).
std::unique_ptr<Material> make_diffuse_material(Color albedo, std::optional<Texture> texture = std::nullopt);
std::unique_ptr<Material> make_pbr_material(PbrParams params);
/// Pure GGX conductor-like specular lobe with Schlick Fresnel of reflectance f0 at normal incidence.
std::unique_ptr<Material> make_ggx_material(Color f0, float roughness);

}  // namespace lumis
