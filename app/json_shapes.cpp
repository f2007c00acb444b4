// The "shapes" and "lights" sections (a "gltf" shape: app/json_gltf.cpp). Emitters are geometry too: every light
// except the environment adds a sphere or mesh carrying its light index, so that a BSDF-sampled ray that hits it
// knows which light it found.
#include "app/json_scene.h"

#include <iostream>

#include "app/scene_error.h"
#include "core/file_ext.h"
#include "core/image_io.h"

namespace lumis {

namespace {

const std::vector<std::string> kQuadSampling = {"spherical_rectangle", "area"};

QuadSampling quad_sampling(const JsonNode& node) {
  if (!node.has("sampling")) return QuadSampling::SphericalRectangle;
  return node["sampling"].as_choice(kQuadSampling, "quad sampling") == 0 ? QuadSampling::SphericalRectangle
                                                                          : QuadSampling::Area;
}

struct QuadGeometry {
  Vec3 origin, edge_u, edge_v;
};

QuadGeometry parse_quad(const JsonNode& node) {
  QuadGeometry q{node["origin"].as_vec3(), node["edge_u"].as_vec3(), node["edge_v"].as_vec3()};
  if (!(robust_length(cross(q.edge_u, q.edge_v)) > 0))
    node["edge_v"].fail("edge_u and edge_v must be non-zero and not parallel (the quad has no area)");
  return q;
}

// Triangles (0,1,2), (0,2,3): both wind so that the front face looks along cross(edge_u, edge_v).
TriangleMesh quad_mesh(const QuadGeometry& q) {
  TriangleMesh m;
  m.positions = {q.origin, q.origin + q.edge_u, q.origin + q.edge_u + q.edge_v, q.origin + q.edge_v};
  m.uv0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

std::vector<Vec3> parse_points(const JsonNode& node) {
  std::vector<Vec3> out;
  for (const auto& e : node.elements()) out.push_back(e.as_vec3());
  return out;
}

}  // namespace

TriangleSampling json_mesh_sampling(const JsonNode& node) {
  static const std::vector<std::string> kMeshSampling = {"spherical_triangle", "area"};
  if (!node.has("sampling")) return TriangleSampling::SphericalTriangle;
  return node["sampling"].as_choice(kMeshSampling, "mesh sampling") == 0 ? TriangleSampling::SphericalTriangle
                                                                          : TriangleSampling::Area;
}

void JsonSceneBuilder::add_shape(const JsonNode& node) {
  static const std::vector<std::string> types = {"sphere", "quad", "mesh", "gltf"};
  if (auto n = node.find("name")) n->as_string();  // a label for the reader, but a string on every kind of shape
  switch (node["type"].as_choice(types, "shape type")) {
    case 0: add_sphere_shape(node); break;
    case 1: add_quad_shape(node); break;
    case 2: add_mesh_shape(node); break;
    default: add_gltf_shape(node); break;
  }
}

void JsonSceneBuilder::add_sphere_shape(const JsonNode& node) {
  node.expect_object({"type", "name", "center", "radius", "material", "emission"});
  Sphere s;
  s.center = node["center"].as_vec3();
  s.radius = node["radius"].as_float();
  if (!(s.radius > 0)) node["radius"].fail_expected("a positive radius");
  s.material = material_reference(node["material"]);
  Color emission;
  if (auto e = node.find("emission")) emission = parse_radiance(*e);
  else if (auto it = material_emission_.find(s.material); it != material_emission_.end()) emission = it->second.factor;
  if (!is_black(emission)) {
    s.light = static_cast<int>(scene_.lights.size());
    scene_.lights.push_back(make_sphere_light(s.center, s.radius, emission));
    light_sizes_.push_back({node["radius"], "emitting sphere's radius", s.center, s.radius, false});
  }
  bounds_.expand(s.center - Vec3(s.radius));
  bounds_.expand(s.center + Vec3(s.radius));
  scene_.geometry.add_sphere(s);
}

void JsonSceneBuilder::add_quad_shape(const JsonNode& node) {
  node.expect_object({"type", "name", "origin", "edge_u", "edge_v", "material", "emission", "sampling"});
  const QuadGeometry q = parse_quad(node);
  TriangleMesh mesh = quad_mesh(q);
  if (auto n = node.find("name")) mesh.name = n->as_string();
  mesh.material = material_reference(node["material"]);
  const QuadSampling sampling = quad_sampling(node);
  MaterialEmission emission;
  if (auto e = node.find("emission")) emission.factor = parse_radiance(*e);
  else if (auto it = material_emission_.find(mesh.material); it != material_emission_.end()) emission = it->second;
  // A textured or two-sided emitter needs the general mesh light; a plain one gets the quad light's sampling. The
  // mesh light samples its two triangles as `sampling` says: by solid angle (spherical triangles) or by area.
  if (emission.emits() && !emission.texture && !emission.two_sided) {
    mesh.light = static_cast<int>(scene_.lights.size());
    scene_.lights.push_back(make_quad_light(q.origin, q.edge_u, q.edge_v, emission.factor, sampling));
    light_sizes_.push_back(quad_light_size(node, q.origin, q.edge_u, q.edge_v, true));
    emission = {};
  }
  add_mesh(std::move(mesh), emission,
           sampling == QuadSampling::Area ? TriangleSampling::Area : TriangleSampling::SphericalTriangle);
}

namespace {

/// Triangles without area (a repeated corner, or collinear corners) have no surface to hit or to sample: dropped
/// with a warning, as glTF's are; a mesh with none left is an error.
void drop_degenerate_triangles(const JsonNode& indices, TriangleMesh& mesh) {
  std::vector<uint32_t> kept;
  kept.reserve(mesh.indices.size());
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    const Vec3 e = cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    if (e.x == 0 && e.y == 0 && e.z == 0) continue;
    kept.insert(kept.end(), {a, b, c});
  }
  const size_t dropped = (mesh.indices.size() - kept.size()) / 3;
  if (kept.empty()) indices.fail("every triangle is degenerate (zero area): the mesh has no surface");
  if (dropped > 0)
    std::cerr << indices.file() << ":" << indices.pointer() << ": warning: degenerate triangles dropped (" << dropped
              << ")\n";
  mesh.indices = std::move(kept);
}

}  // namespace

void JsonSceneBuilder::add_mesh_shape(const JsonNode& node) {
  node.expect_object({"type", "name", "positions", "indices", "normals", "uvs", "material", "emission", "sampling",
                      "transform"});
  TriangleMesh mesh;
  if (auto n = node.find("name")) mesh.name = n->as_string();
  mesh.positions = parse_points(node["positions"]);
  if (mesh.positions.size() < 3) node["positions"].fail_expected("at least 3 positions");
  const auto indices = node["indices"].elements();
  if (indices.empty() || indices.size() % 3 != 0)
    node["indices"].fail_expected("a flat array of vertex indices, 3 per triangle");
  for (const auto& i : indices)
    mesh.indices.push_back(static_cast<uint32_t>(i.as_integer(0, static_cast<int64_t>(mesh.positions.size()) - 1)));
  if (auto n = node.find("normals")) {
    mesh.normals = parse_points(*n);
    if (mesh.normals.size() != mesh.positions.size()) n->fail_expected("one normal per position");
    for (size_t i = 0; i < mesh.normals.size(); ++i) {
      // Normalised first (robust: [1e-30, 0, 0] is a normal too), so that a transform's cofactors cannot
      // overflow or underflow it.
      mesh.normals[i] = robust_normalize(mesh.normals[i]);
      if (!(length(mesh.normals[i]) > 0)) n->elements()[i].fail("a normal must not be zero");
    }
  }
  if (auto uv = node.find("uvs")) {
    for (const auto& e : uv->elements()) mesh.uv0.push_back(e.as_vec2());
    if (mesh.uv0.size() != mesh.positions.size()) uv->fail_expected("one uv per position");
  }
  if (auto t = node.find("transform")) {
    const Mat4 m = parse_transform(*t);
    for (auto& p : mesh.positions) p = m.apply_point(p);
    for (auto& n : mesh.normals) n = m.apply_normal(n);
    for (const Vec3& p : mesh.positions)
      if (!is_finite(p)) t->fail("the transformed positions are not finite (beyond the float range)");
    // A mirroring transform flips the winding; swapping two corners keeps the front face where the normals are.
    if (m.determinant3() < 0)
      for (size_t i = 0; i < mesh.indices.size(); i += 3) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
  }
  drop_degenerate_triangles(node["indices"], mesh);
  for (auto& n : mesh.normals) n = robust_normalize(n);
  mesh.material = material_reference(node["material"]);
  MaterialEmission emission;
  if (auto e = node.find("emission")) emission.factor = parse_radiance(*e);
  else if (auto it = material_emission_.find(mesh.material); it != material_emission_.end()) emission = it->second;
  add_mesh(std::move(mesh), emission, json_mesh_sampling(node));
}

void JsonSceneBuilder::add_mesh(TriangleMesh mesh, const MaterialEmission& emission, TriangleSampling sampling) {
  for (const Vec3& p : mesh.positions) bounds_.expand(p);
  if (emission.emits()) {
    mesh.light = static_cast<int>(scene_.lights.size());
    scene_.lights.push_back(make_mesh_light(mesh, emission.factor, emission.texture, emission.two_sided, sampling));
  }
  scene_.geometry.add_mesh(std::move(mesh));
}

void JsonSceneBuilder::add_light(const JsonNode& node) {
  static const std::vector<std::string> types = {"sphere", "quad", "environment"};
  const size_t type = node["type"].as_choice(types, "light type");
  const int index = static_cast<int>(scene_.lights.size());
  if (type == 0) {
    node.expect_object({"type", "center", "radius", "radiance"});
    // A pure emitter: material -1, so a ray that hits it sees its radiance and nothing behind it.
    Sphere s;
    s.center = node["center"].as_vec3();
    s.radius = node["radius"].as_float();
    if (!(s.radius > 0)) node["radius"].fail_expected("a positive radius");
    s.light = index;
    scene_.lights.push_back(make_sphere_light(s.center, s.radius, parse_radiance(node["radiance"])));
    light_sizes_.push_back({node["radius"], "sphere light's radius", s.center, s.radius, false});
    bounds_.expand(s.center - Vec3(s.radius));
    bounds_.expand(s.center + Vec3(s.radius));
    scene_.geometry.add_sphere(s);
  } else if (type == 1) {
    node.expect_object({"type", "origin", "edge_u", "edge_v", "radiance", "sampling"});
    const QuadGeometry q = parse_quad(node);
    const Color radiance = parse_radiance(node["radiance"]);
    scene_.lights.push_back(make_quad_light(q.origin, q.edge_u, q.edge_v, radiance, quad_sampling(node)));
    light_sizes_.push_back(quad_light_size(node, q.origin, q.edge_u, q.edge_v, false));
    TriangleMesh mesh = quad_mesh(q);
    mesh.light = index;
    add_mesh(std::move(mesh), {}, TriangleSampling::SphericalTriangle);
  } else {
    add_environment(node);
  }
}

void JsonSceneBuilder::add_environment(const JsonNode& node) {
  node.expect_object({"type", "radiance", "file", "scale", "rotation"});
  if (scene_.environment >= 0) node.fail("only one environment light is allowed; this is the second");
  if (node.has("radiance") == node.has("file"))
    node.fail("an environment needs exactly one of \"radiance\" (a constant colour) or \"file\" (an .exr/.hdr map)");
  scene_.environment = static_cast<int>(scene_.lights.size());
  if (auto r = node.find("radiance")) {
    for (const char* k : {"scale", "rotation"})
      if (node.has(k)) node[k].fail("\"" + std::string(k) + "\" applies to an environment map (\"file\") only");
    scene_.lights.push_back(make_constant_environment(parse_radiance(*r)));
    return;
  }
  const JsonNode file = node["file"];
  const std::string path = resolve_path(file);
  const std::string ext = lower_extension(path);
  if (ext != ".exr" && ext != ".hdr")
    file.fail("an environment map must be a linear .exr or .hdr file, found " +
              (ext.empty() ? std::string("a name without an extension") : "\"" + ext + "\""));
  const float scale = node.find("scale") ? node["scale"].as_float(0) : 1.0f;
  const float rotation = node.find("rotation") ? node["rotation"].as_float() : 0.0f;
  std::shared_ptr<const Image> image;
  try {
    Image img = read_image(path, false);
    // OpenImageIO reads by contents: an 8-bit PNG named .exr would be taken as linear radiance.
    if (img.format != "openexr" && img.format != "hdr")
      file.fail("an environment map must be a linear .exr or .hdr file; this one is named \"" + ext +
                "\" but holds a " + img.format + " image");
    check_texels(img, path, /*allow_negative=*/false);  // radiance
    image = std::make_shared<const Image>(std::move(img));
  } catch (const ImageError& e) {
    file.fail(std::string("cannot read image: ") + e.what());
  }
  scene_.input_images.push_back(path);
  scene_.lights.push_back(make_image_environment(std::move(image), scale, rotation));
}

}  // namespace lumis
