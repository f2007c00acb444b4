// glTF mesh primitives to world-space TriangleMeshes: attribute decoding, strip/fan conversion, index checks, and
// the per-instance transform (winding flipped under mirroring, normals by the inverse transpose).
#include <cmath>
#include <numeric>

#include "app/gltf_internal.h"
#include "core/tangents.h"

namespace lumis::gltf {

namespace {

std::vector<Vec2> to_vec2(const FloatData& d) {
  std::vector<Vec2> out(d.count());
  for (size_t i = 0; i < out.size(); ++i) out[i] = {d.values[2 * i], d.values[2 * i + 1]};
  return out;
}

std::vector<Vec3> to_vec3(const FloatData& d) {
  std::vector<Vec3> out(d.count());
  for (size_t i = 0; i < out.size(); ++i) out[i] = {d.values[3 * i], d.values[3 * i + 1], d.values[3 * i + 2]};
  return out;
}

/// VEC3 or VEC4 data as Vec4, the missing fourth component set to `w`.
std::vector<Vec4> to_vec4(const FloatData& d, float w) {
  std::vector<Vec4> out(d.count());
  const int c = d.components;
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = {d.values[c * i], d.values[c * i + 1], d.values[c * i + 2], c == 4 ? d.values[c * i + 3] : w};
  return out;
}

/// Triangle list from the index sequence of a TRIANGLES (4), TRIANGLE_STRIP (5) or TRIANGLE_FAN (6) primitive.
/// Strips alternate winding so that every triangle keeps the first one's orientation.
std::vector<uint32_t> assemble(const std::vector<uint32_t>& v, int mode) {
  std::vector<uint32_t> out;
  if (mode == TINYGLTF_MODE_TRIANGLES) return v;
  if (v.size() < 3) return out;
  out.reserve(3 * (v.size() - 2));
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      if (i % 2 == 0) out.insert(out.end(), {v[i], v[i + 1], v[i + 2]});
      else out.insert(out.end(), {v[i + 1], v[i], v[i + 2]});
    } else {
      out.insert(out.end(), {v[0], v[i + 1], v[i + 2]});
    }
  }
  return out;
}

}  // namespace

const PrimitiveBuilder::Decoded& PrimitiveBuilder::decode(int mesh, int prim) {
  if (auto it = cache_.find({mesh, prim}); it != cache_.end()) return it->second;
  Decoded& d = cache_[{mesh, prim}];
  const tinygltf::Primitive& p = ctx_.model.meshes[mesh].primitives[prim];
  const std::string at = indexed("meshes", mesh) + indexed(".primitives", prim);

  if (p.mode < TINYGLTF_MODE_POINTS || p.mode > TINYGLTF_MODE_TRIANGLE_FAN)
    ctx_.fail(at + ".mode", "mode " + std::to_string(p.mode) + ", expected 0 to 6");
  if (p.mode < TINYGLTF_MODE_TRIANGLES) {
    ++skipped_non_triangles_;
    d.skip = true;
    return d;
  }
  const auto pos_it = p.attributes.find("POSITION");
  if (pos_it == p.attributes.end()) {
    ctx_.warn_once("noposition", at + ": primitives without POSITION skipped");
    d.skip = true;
    return d;
  }
  if (!p.targets.empty()) ctx_.warn_once("morph", "morph targets ignored (meshes drawn with their base shape)");

  d.positions = to_vec3(acc_.floats(pos_it->second, at + ".attributes.POSITION", {TINYGLTF_TYPE_VEC3}, kFloat));
  const size_t n = d.positions.size();
  auto attribute = [&](const char* name, std::vector<int> types, const ComponentTypes& components) -> const FloatData* {
    const auto it = p.attributes.find(name);
    if (it == p.attributes.end()) return nullptr;
    const std::string aat = at + ".attributes." + name;
    const FloatData& f = acc_.floats(it->second, aat, std::move(types), components);
    if (f.count() != n)
      ctx_.fail(aat, "has " + std::to_string(f.count()) + " elements, expected " + std::to_string(n) +
                         " like POSITION");
    return &f;
  };
  if (auto* f = attribute("NORMAL", {TINYGLTF_TYPE_VEC3}, kFloat)) d.normals = to_vec3(*f);
  if (auto* f = attribute("TANGENT", {TINYGLTF_TYPE_VEC4}, kFloat)) d.tangents = to_vec4(*f, 1);
  if (auto* f = attribute("TEXCOORD_0", {TINYGLTF_TYPE_VEC2}, kFloatOrUnorm)) d.uv0 = to_vec2(*f);
  if (auto* f = attribute("TEXCOORD_1", {TINYGLTF_TYPE_VEC2}, kFloatOrUnorm)) d.uv1 = to_vec2(*f);
  if (auto* f = attribute("COLOR_0", {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, kColor))
    d.colors = to_vec4(*f, 1);

  std::vector<uint32_t> seq;
  if (p.indices >= 0) {
    seq = acc_.uints(p.indices, at + ".indices");
    for (size_t i = 0; i < seq.size(); ++i)
      if (seq[i] >= n)
        ctx_.fail(at + ".indices", "index value " + std::to_string(seq[i]) + " (element " + std::to_string(i) +
                                       ") is not below the vertex count " + std::to_string(n));
  } else {
    seq.resize(n);
    std::iota(seq.begin(), seq.end(), 0u);
  }
  if (p.mode == TINYGLTF_MODE_TRIANGLES && seq.size() % 3 != 0)
    ctx_.fail(p.indices >= 0 ? at + ".indices" : at + ".attributes.POSITION",
              std::to_string(seq.size()) + " vertices do not make whole triangles (expected a multiple of 3)");
  d.indices = assemble(seq, p.mode);

  d.material = p.material;
  if (d.material >= 0 && static_cast<size_t>(d.material) >= ctx_.model.materials.size())
    ctx_.fail(at + ".material", "material index " + std::to_string(d.material) + " out of range (the file has " +
                                    std::to_string(ctx_.model.materials.size()) + " materials)");
  if (d.material < 0) {
    if (default_material_ < 0) {
      default_material_ = static_cast<int>(scene_.materials.size());
      scene_.materials.push_back(GltfMaterial{"default", PbrParams{}});
    }
    d.material = default_material_;
  }
  // A texture read through a TEXCOORD set the primitive lacks gets uv (0, 0) everywhere: one texel. glTF does not
  // allow it (Khronos's validator calls it an error); viewers draw such files, so it is a warning.
  const PbrParams& m = scene_.materials[static_cast<size_t>(d.material)].params;
  for (const auto& [texture, name] : {std::pair{&m.base_color_texture, "baseColorTexture"},
                                      {&m.metallic_roughness_texture, "metallicRoughnessTexture"},
                                      {&m.normal_texture, "normalTexture"}, {&m.emissive_texture, "emissiveTexture"}})
    if (*texture && ((*texture)->tex_coord == 1 ? d.uv1 : d.uv0).empty())
      ctx_.warn_once("nouv", at + ": its material's " + name + " reads TEXCOORD_" +
                                 std::to_string((*texture)->tex_coord) + ", which the primitive does not have; every "
                                 "point reads the texture at uv (0, 0)");
  return d;
}

void PrimitiveBuilder::add_mesh(int mesh, const Mat4& world, const std::string& node_at) {
  if (mesh < 0 || static_cast<size_t>(mesh) >= ctx_.model.meshes.size())
    ctx_.fail(node_at + ".mesh", "mesh index " + std::to_string(mesh) + " out of range (the file has " +
                                     std::to_string(ctx_.model.meshes.size()) + " meshes)");
  const tinygltf::Mesh& gm = ctx_.model.meshes[mesh];
  const bool mirrored = world.determinant3() < 0;
  for (size_t pi = 0; pi < gm.primitives.size(); ++pi) {
    const Decoded& d = decode(mesh, static_cast<int>(pi));
    if (d.skip) continue;
    TriangleMesh tm;
    tm.name = gm.name.empty() ? indexed("meshes", mesh) : gm.name;
    if (gm.primitives.size() > 1) tm.name += indexed(".primitives", pi);

    tm.positions.resize(d.positions.size());
    for (size_t i = 0; i < d.positions.size(); ++i) {
      tm.positions[i] = world.apply_point(d.positions[i]);
      if (!is_finite(tm.positions[i])) ctx_.fail(node_at, "transformed vertex positions are not finite");
    }
    // apply_normal is the inverse transpose up to a positive factor, so normals keep their side under mirroring,
    // where the winding swap below keeps the geometric normal on that same side.
    tm.normals.resize(d.normals.size());
    for (size_t i = 0; i < d.normals.size(); ++i) {
      // Scaled by det(world): robust_length, since |nw|^2 leaves the float range for a node scale past ~1e9 or
      // below ~1e-10, which once dropped the normals of a model scaled 1e10.
      const Vec3 nw = world.apply_normal(d.normals[i]);
      const float len = robust_length(nw);
      if (!(len > 0)) {
        ctx_.warn_once("badnormal", node_at + ": zero-length vertex normals; flat shading used for that mesh");
        tm.normals.clear();
        break;
      }
      tm.normals[i] = robust_normalize(nw);
    }
    // Tangents are surface directions (plain linear map); the bitangent sign flips with the handedness.
    tm.tangents.resize(d.tangents.size());
    for (size_t i = 0; i < d.tangents.size(); ++i) {
      const Vec3 tw = world.apply_vector(d.tangents[i].xyz());
      const float len = length(tw);
      if (!(len > 0) || !std::isfinite(len)) {
        ctx_.warn_once("badtangent", node_at + ": zero-length vertex tangents dropped");
        tm.tangents.clear();
        break;
      }
      const Vec3 t = tw / len;
      const float w = d.tangents[i].w < 0 ? -1.0f : 1.0f;
      tm.tangents[i] = {t.x, t.y, t.z, mirrored ? -w : w};
    }
    tm.uv0 = d.uv0;
    tm.uv1 = d.uv1;
    tm.colors = d.colors;

    tm.indices.reserve(d.indices.size());
    for (size_t t = 0; t + 2 < d.indices.size(); t += 3) {
      uint32_t a = d.indices[t], b = d.indices[t + 1], c = d.indices[t + 2];
      if (mirrored) std::swap(b, c);
      const Vec3 e = cross(tm.positions[b] - tm.positions[a], tm.positions[c] - tm.positions[a]);
      if (e.x == 0 && e.y == 0 && e.z == 0) {  // repeated index or collinear: no surface to hit
        ++degenerate_;
        continue;
      }
      tm.indices.insert(tm.indices.end(), {a, b, c});
    }
    if (tm.indices.empty()) continue;

    tm.material = d.material;
    const GltfMaterial& mat = scene_.materials[d.material];
    // Normal maps need tangents; glTF asks renderers to generate them when the file has none.
    if (mat.params.normal_texture && tm.tangents.empty()) generate_tangents(tm, mat.params.normal_texture->tex_coord);
    if (mat.alpha_mode == AlphaMode::Mask)
      tm.alpha = AlphaMask{mat.alpha_cutoff, mat.params.base_alpha, mat.params.base_color_texture};
    scene_.meshes.push_back(std::move(tm));
  }
}

void PrimitiveBuilder::finish() {
  if (skipped_non_triangles_ > 0)
    ctx_.warn("points and lines skipped (" + std::to_string(skipped_non_triangles_) + " primitive" +
              (skipped_non_triangles_ > 1 ? "s" : "") + ")");
  if (degenerate_ > 0)
    ctx_.warn("degenerate triangles dropped (" + std::to_string(degenerate_) + ")");
}

}  // namespace lumis::gltf
