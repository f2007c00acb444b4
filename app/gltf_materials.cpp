// glTF materials: pbrMetallicRoughness, emissive (with KHR_materials_emissive_strength), normal maps, alpha modes
// and double-sidedness. Their textures (images, samplers, KHR_texture_transform) are made in gltf_textures.cpp.
#include <algorithm>
#include <cmath>
#include <set>

#include "app/gltf_internal.h"

namespace lumis::gltf {

namespace {

Color color3(const Context& ctx, const std::vector<double>& v, const std::string& where) {
  if (v.size() != 3) ctx.fail(where, "expected 3 numbers, got " + std::to_string(v.size()));
  for (double x : v)
    if (!std::isfinite(static_cast<float>(x))) ctx.fail(where, "expected finite numbers (within float's range)");
  return {float(v[0]), float(v[1]), float(v[2])};
}

}  // namespace

std::vector<GltfMaterial> convert_materials(Context& ctx) {
  ImageCache images(ctx);
  // Decoding dominates load time for textured models: find every image the materials use and decode in parallel.
  std::set<std::pair<int, bool>> wanted;
  auto want = [&](int texture, bool srgb) {
    if (texture >= 0 && static_cast<size_t>(texture) < ctx.model.textures.size())
      wanted.insert({ctx.model.textures[texture].source, srgb});
  };
  for (const auto& m : ctx.model.materials) {
    want(m.pbrMetallicRoughness.baseColorTexture.index, true);
    want(m.pbrMetallicRoughness.metallicRoughnessTexture.index, false);
    want(m.normalTexture.index, false);
    want(m.emissiveTexture.index, true);
  }
  images.prefetch(wanted);
  std::vector<GltfMaterial> out;
  int blend = 0;
  for (size_t i = 0; i < ctx.model.materials.size(); ++i) {
    const tinygltf::Material& m = ctx.model.materials[i];
    const std::string at = indexed("materials", i);
    const auto& pbr = m.pbrMetallicRoughness;
    GltfMaterial g;
    g.name = m.name.empty() ? at : m.name;
    PbrParams& p = g.params;

    if (pbr.baseColorFactor.size() != 4) ctx.fail(at + ".pbrMetallicRoughness.baseColorFactor", "expected 4 numbers");
    const std::vector<double> rgb(pbr.baseColorFactor.begin(), pbr.baseColorFactor.begin() + 3);
    p.base_color = color3(ctx, rgb, at + ".pbrMetallicRoughness.baseColorFactor");
    p.base_alpha = static_cast<float>(pbr.baseColorFactor[3]);
    p.metallic = static_cast<float>(pbr.metallicFactor);
    p.roughness = static_cast<float>(pbr.roughnessFactor);
    if (!std::isfinite(p.base_alpha) || !std::isfinite(p.metallic) || !std::isfinite(p.roughness))
      ctx.fail(at + ".pbrMetallicRoughness", "factors must be finite numbers");
    // glTF bounds these factors to [0, 1]; a value outside is clamped where it is used (the BSDF), with a warning
    // for the first material that has one.
    const auto outside = [](double v) { return !(v >= 0 && v <= 1); };
    if (std::any_of(pbr.baseColorFactor.begin(), pbr.baseColorFactor.end(), outside) ||
        outside(pbr.metallicFactor) || outside(pbr.roughnessFactor))
      ctx.warn_once("factor range", at + ".pbrMetallicRoughness: a factor outside [0, 1] is clamped to it (glTF "
                                         "allows 0...1 for baseColorFactor, metallicFactor and roughnessFactor)");
    // Clamped here, before a texture multiplies it (the BSDF clamps only the product) and the alpha cutoff sees it.
    const auto unit = [](float v) { return std::clamp(v, 0.0f, 1.0f); };
    for (int c = 0; c < 3; ++c) p.base_color[c] = unit(p.base_color[c]);
    p.base_alpha = unit(p.base_alpha);
    p.metallic = unit(p.metallic);
    p.roughness = unit(p.roughness);
    if (pbr.baseColorTexture.index >= 0)
      p.base_color_texture = make_texture(ctx, images, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                          pbr.baseColorTexture.extensions, true,
                                          at + ".pbrMetallicRoughness.baseColorTexture");
    if (pbr.metallicRoughnessTexture.index >= 0)
      p.metallic_roughness_texture = make_texture(
          ctx, images, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
          pbr.metallicRoughnessTexture.extensions, false, at + ".pbrMetallicRoughness.metallicRoughnessTexture");
    if (m.normalTexture.index >= 0) {
      p.normal_texture = make_texture(ctx, images, m.normalTexture.index, m.normalTexture.texCoord,
                                      m.normalTexture.extensions, false, at + ".normalTexture");
      p.normal_scale = static_cast<float>(m.normalTexture.scale);
    }

    float strength = 1;
    if (auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end()) {
      const std::string sat = at + ".extensions.KHR_materials_emissive_strength.emissiveStrength";
      if (it->second.IsObject() && it->second.Has("emissiveStrength"))
        strength = number(ctx, it->second.Get("emissiveStrength"), sat);
      if (strength < 0) ctx.fail(sat, "must be >= 0");
    }
    const Color emissive_factor = color3(ctx, m.emissiveFactor, at + ".emissiveFactor");
    if (min_component(emissive_factor) < 0) ctx.fail(at + ".emissiveFactor", "expected numbers >= 0");
    p.emissive = emissive_factor * strength;
    if (!is_finite(p.emissive))
      ctx.fail(at + ".emissiveFactor", "times emissiveStrength overflows float's range");
    if (m.emissiveTexture.index >= 0)
      p.emissive_texture = make_texture(ctx, images, m.emissiveTexture.index, m.emissiveTexture.texCoord,
                                        m.emissiveTexture.extensions, true, at + ".emissiveTexture");
    p.double_sided = m.doubleSided;

    if (m.alphaMode == "MASK") {
      g.alpha_mode = AlphaMode::Mask;
    } else if (m.alphaMode == "BLEND") {
      g.alpha_mode = AlphaMode::Blend;
      ++blend;
    } else if (m.alphaMode != "OPAQUE") {
      ctx.fail(at + ".alphaMode", "'" + m.alphaMode + "', expected OPAQUE, MASK or BLEND");
    }
    g.alpha_cutoff = static_cast<float>(m.alphaCutoff);
    if (!std::isfinite(g.alpha_cutoff)) ctx.fail(at + ".alphaCutoff", "expected a finite number");
    out.push_back(std::move(g));
  }
  if (blend > 0)
    ctx.warn("alphaMode BLEND rendered as OPAQUE (" + std::to_string(blend) + " material" + (blend > 1 ? "s" : "") +
             ")");
  return out;
}

}  // namespace lumis::gltf
