// The generated large benchmark scene, written as a binary glTF so that its load time is measured through the
// real loader. A closed room keeps incoherent rays hitting geometry at every bounce, as in an interior.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench.h"
#include "core/atomic_write.h"
#include "core/math.h"

namespace lumis {

namespace {

using Json = nlohmann::json;

struct Part {
  std::vector<Vec3> positions, normals;  // normals empty: flat
  std::vector<uint32_t> indices;
  int material = 0;
};

// An nu x nv grid over the parallelogram origin + [0,1] edge_u + [0,1] edge_v; front face along cross(edge_u, edge_v).
Part grid(Vec3 origin, Vec3 edge_u, Vec3 edge_v, uint32_t nu, uint32_t nv, int material) {
  Part p;
  p.material = material;
  p.positions.reserve(size_t(nu + 1) * (nv + 1));
  for (uint32_t j = 0; j <= nv; ++j)
    for (uint32_t i = 0; i <= nu; ++i)
      p.positions.push_back(origin + edge_u * (float(i) / nu) + edge_v * (float(j) / nv));
  p.indices.reserve(size_t(nu) * nv * 6);
  const uint32_t row = nu + 1;
  for (uint32_t j = 0; j < nv; ++j)
    for (uint32_t i = 0; i < nu; ++i) {
      const uint32_t a = j * row + i, b = a + 1, c = a + row + 1, d = a + row;
      p.indices.insert(p.indices.end(), {a, b, c, a, c, d});
    }
  return p;
}

// A UV sphere with `rings` latitude bands and 2 x rings segments, smooth normals, counter-clockwise seen from
// outside; 4 rings (rings - 1) triangles (the pole bands have one triangle per segment).
Part uv_sphere(Vec3 center, float radius, uint32_t rings, int material) {
  Part p;
  p.material = material;
  const uint32_t segments = 2 * rings, row = segments + 1;
  for (uint32_t r = 0; r <= rings; ++r) {
    const float theta = kPi * float(r) / rings;
    for (uint32_t s = 0; s <= segments; ++s) {
      const float phi = 2 * kPi * float(s) / segments;
      const Vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      p.normals.push_back(n);
      p.positions.push_back(center + n * radius);
    }
  }
  for (uint32_t r = 0; r < rings; ++r)
    for (uint32_t s = 0; s < segments; ++s) {
      const uint32_t a = r * row + s, b = a + 1, c = a + row + 1, d = a + row;
      if (r != 0) p.indices.insert(p.indices.end(), {a, b, c});          // degenerate at the north pole
      if (r != rings - 1) p.indices.insert(p.indices.end(), {a, c, d});  // degenerate at the south pole
    }
  return p;
}

// Appends raw bytes to the binary buffer at a 4-byte boundary; returns the new buffer view's index.
size_t add_view(std::vector<uint8_t>& bin, Json& views, const void* data, size_t bytes, int target) {
  while (bin.size() % 4) bin.push_back(0);
  const size_t offset = bin.size();
  bin.resize(offset + bytes);
  std::memcpy(bin.data() + offset, data, bytes);
  views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
  return views.size() - 1;
}

Json material(const char* name, Color base, float metallic, float roughness) {
  return {{"name", name},
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {base.x, base.y, base.z, 1.0}}, {"metallicFactor", metallic},
            {"roughnessFactor", roughness}}}};
}

}  // namespace

LargeSceneInfo write_large_scene(const std::string& path, size_t min_triangles) {
  // Room [-2,2] x [0,3] x [-2,2]; about 45% of the triangles in the walls, the rest in eight spheres.
  const float wall_share = 0.45f;
  // With nu = 4n/3 cells along the 4 m edges and n along the 3 m ones, the six walls have 160/9 n^2 triangles.
  const uint32_t n =
      std::max<uint32_t>(3, uint32_t(std::ceil(std::sqrt(wall_share * double(min_triangles) * 9.0 / 160.0))));
  const uint32_t nu = n + n / 3, nv = n;
  std::vector<Part> parts;
  // Front faces point into the room.
  parts.push_back(grid({-2, 0, -2}, {0, 0, 4}, {4, 0, 0}, nu, nu, 0));  // floor (+y)
  parts.push_back(grid({-2, 3, -2}, {4, 0, 0}, {0, 0, 4}, nu, nu, 0));  // ceiling (-y)
  parts.push_back(grid({-2, 0, -2}, {4, 0, 0}, {0, 3, 0}, nu, nv, 0));  // back (+z)
  parts.push_back(grid({-2, 0, 2}, {0, 3, 0}, {4, 0, 0}, nv, nu, 0));   // front (-z), behind the camera
  parts.push_back(grid({-2, 0, -2}, {0, 3, 0}, {0, 0, 4}, nv, nu, 1));  // left (+x), red
  parts.push_back(grid({2, 0, -2}, {0, 0, 4}, {0, 3, 0}, nu, nv, 2));   // right (-x), green
  size_t walls = 0;
  for (const Part& p : parts) walls += p.indices.size() / 3;
  const size_t per_sphere = min_triangles > walls + 2 ? (min_triangles - walls - 2 + 7) / 8 : 8;
  const uint32_t rings =
      std::max<uint32_t>(3, uint32_t(std::ceil((1 + std::sqrt(1.0 + double(per_sphere))) / 2)));
  for (int i = 0; i < 8; ++i) {
    const float x = -1.35f + 0.9f * float(i % 4), z = i < 4 ? -1.1f : 0.1f;
    parts.push_back(uv_sphere({x, 0.4f, z}, 0.4f, rings, 3 + i % 2));
  }
  parts.push_back(grid({-0.5f, 2.95f, -0.5f}, {1, 0, 0}, {0, 0, 1}, 1, 1, 5));  // the light, facing down

  Json doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", "lumis bench --write-large-scene"}};
  doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  Json mats = Json::array();
  mats.push_back(material("white", {0.73f, 0.73f, 0.73f}, 0, 1));
  mats.push_back(material("red", {0.65f, 0.05f, 0.05f}, 0, 1));
  mats.push_back(material("green", {0.12f, 0.45f, 0.15f}, 0, 1));
  mats.push_back(material("copper", {0.95f, 0.64f, 0.54f}, 1, 0.3f));
  mats.push_back(material("blue plastic", {0.1f, 0.2f, 0.6f}, 0, 0.4f));
  Json light = material("light", {0, 0, 0}, 0, 1);
  light["emissiveFactor"] = {1.0, 1.0, 1.0};
  light["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 20.0}}}};
  mats.push_back(light);
  doc["materials"] = mats;

  std::vector<uint8_t> bin;
  Json views = Json::array(), accessors = Json::array(), meshes = Json::array(), nodes = Json::array();
  size_t triangles = 0;
  for (const Part& p : parts) {
    Vec3 lo(INFINITY), hi(-INFINITY);
    for (const Vec3& v : p.positions) {
      lo = min(lo, v);
      hi = max(hi, v);
    }
    Json attributes;
    size_t view = add_view(bin, views, p.positions.data(), p.positions.size() * sizeof(Vec3), 34962);
    accessors.push_back({{"bufferView", view}, {"componentType", 5126}, {"count", p.positions.size()},
                         {"type", "VEC3"}, {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}});
    attributes["POSITION"] = accessors.size() - 1;
    if (!p.normals.empty()) {
      view = add_view(bin, views, p.normals.data(), p.normals.size() * sizeof(Vec3), 34962);
      accessors.push_back(
          {{"bufferView", view}, {"componentType", 5126}, {"count", p.normals.size()}, {"type", "VEC3"}});
      attributes["NORMAL"] = accessors.size() - 1;
    }
    view = add_view(bin, views, p.indices.data(), p.indices.size() * sizeof(uint32_t), 34963);
    accessors.push_back(
        {{"bufferView", view}, {"componentType", 5125}, {"count", p.indices.size()}, {"type", "SCALAR"}});
    meshes.push_back({{"primitives", {{{"attributes", attributes}, {"indices", accessors.size() - 1},
                                       {"material", p.material}}}}});
    nodes.push_back({{"mesh", meshes.size() - 1}});
    triangles += p.indices.size() / 3;
  }
  static_assert(sizeof(Vec3) == 12, "glTF VEC3 float accessors are tightly packed");
  // glTF cameras look down their local -z: from near the front wall toward the back wall.
  doc["cameras"] = {{{"type", "perspective"},
                     {"perspective", {{"yfov", 0.95}, {"aspectRatio", 1.0}, {"znear", 0.01}}}}};
  nodes.push_back({{"name", "camera"}, {"camera", 0}, {"translation", {0.0, 1.5, 1.9}}});
  Json scene_nodes = Json::array();
  for (size_t i = 0; i < nodes.size(); ++i) scene_nodes.push_back(i);
  doc["nodes"] = nodes;
  doc["meshes"] = meshes;
  doc["accessors"] = accessors;
  doc["bufferViews"] = views;
  while (bin.size() % 4) bin.push_back(0);
  doc["buffers"] = {{{"byteLength", bin.size()}}};
  doc["scenes"] = {{{"nodes", scene_nodes}}};
  doc["scene"] = 0;

  std::string text = doc.dump();
  while (text.size() % 4) text.push_back(' ');
  const uint32_t total = uint32_t(12 + 8 + text.size() + 8 + bin.size());
  std::string file;
  file.reserve(total);
  auto u32 = [&file](uint32_t v) { file.append(reinterpret_cast<const char*>(&v), 4); };  // little-endian hosts
  u32(0x46546C67);  // "glTF"
  u32(2);
  u32(total);
  u32(uint32_t(text.size()));
  u32(0x4E4F534A);  // "JSON"
  file += text;
  u32(uint32_t(bin.size()));
  u32(0x004E4942);  // "BIN\0"
  file.append(reinterpret_cast<const char*>(bin.data()), bin.size());
  if (const std::string why = write_file_atomically(path, file); !why.empty())
    throw std::runtime_error(path + ": " + why);
  return {triangles, total};
}

}  // namespace lumis
