// JSON scene pieces shared by shapes and lights: file paths, textures, materials, transforms, camera framing.
#include "app/json_scene.h"

#include <algorithm>
#include <cstdio>

#include "app/scene_error.h"
#include "core/image_io.h"

namespace lumis {

JsonSceneBuilder::JsonSceneBuilder(Scene& scene, const std::string& file)
    : scene_(scene), file_(file), folder_(std::filesystem::path(file).parent_path()) {}

std::string JsonSceneBuilder::resolve_path(const JsonNode& node) const {
  const std::string s = node.as_string();
  if (s.empty()) node.fail_expected("a file path");
  std::filesystem::path p(s);
  if (p.is_relative()) p = folder_ / p;
  std::error_code ec;
  if (std::filesystem::is_directory(p, ec)) node.fail("is a folder, expected a file: " + p.string());
  if (!std::filesystem::exists(p, ec)) node.fail("file not found: " + p.string());
  if (!std::filesystem::is_regular_file(p, ec))
    node.fail("is not a regular file (a pipe, device or socket): " + p.string());
  return p.string();
}

Texture JsonSceneBuilder::load_texture(const JsonNode& node, bool srgb) {
  const std::string path = resolve_path(node);
  auto& image = images_[{path, srgb}];
  if (!image) {
    try {
      Image img = read_image(path, srgb);
      check_texels(img, path, /*allow_negative=*/!srgb);  // colour textures (sRGB ones) are >= 0
      image = std::make_shared<const Image>(std::move(img));
    } catch (const ImageError& e) {
      node.fail(std::string("cannot read image: ") + e.what());
    }
    scene_.input_images.push_back(path);
  }
  Texture t;
  t.image = image;
  return t;
}

Color JsonSceneBuilder::parse_radiance(const JsonNode& node) const {
  const Color c = node.as_vec3(0.0f);
  if (is_black(c)) node.fail("expected a radiance with at least one positive component, found [0, 0, 0]");
  return c;
}

int JsonSceneBuilder::material_reference(const JsonNode& node) const {
  const std::string name = node.as_string();
  const auto it = material_index_.find(name);
  if (it != material_index_.end()) return it->second;
  std::vector<std::string> names;
  for (const auto& [n, i] : material_index_) names.push_back(n);
  node.fail("unknown material \"" + name + "\"; defined materials: " + (names.empty() ? "(none)" : join_names(names)));
}

void JsonSceneBuilder::add_materials(const JsonNode& node) {
  for (const auto& [name, m] : node.members()) {
    MaterialEmission emission;
    auto material = parse_material(m, emission);
    const int index = static_cast<int>(scene_.materials.size());
    scene_.materials.push_back(std::move(material));
    material_index_[name] = index;
    if (emission.emits()) material_emission_[index] = emission;
  }
}

std::unique_ptr<Material> JsonSceneBuilder::parse_material(const JsonNode& node, MaterialEmission& emission) {
  static const std::vector<std::string> types = {"diffuse", "pbr", "ggx"};
  const size_t type = node["type"].as_choice(types, "material type");
  if (types[type] == "diffuse") {
    node.expect_object({"type", "albedo", "texture"});
    const Color albedo = node.find("albedo") ? node["albedo"].as_vec3(0, 1) : Color(0.8f);
    std::optional<Texture> texture;
    if (auto t = node.find("texture")) texture = load_texture(*t, true);
    return make_diffuse_material(albedo, std::move(texture));
  }
  if (types[type] == "ggx") {
    node.expect_object({"type", "f0", "color", "roughness"});
    if (node.has("f0") && node.has("color"))
      node["color"].fail("give either \"f0\" or \"color\" (the same thing), not both");
    if (!node.has("f0") && !node.has("color")) node.fail("missing required key \"f0\" (or its alias \"color\")");
    const Color f0 = node[node.has("f0") ? "f0" : "color"].as_vec3(0, 1);
    return make_ggx_material(f0, node["roughness"].as_float(0, 1));
  }
  node.expect_object({"type", "base_color", "base_color_texture", "metallic", "roughness", "metallic_roughness_texture",
                      "normal_texture", "normal_scale", "emissive", "emissive_texture", "double_sided"});
  PbrParams p;
  if (auto v = node.find("base_color")) p.base_color = v->as_vec3(0, 1);
  if (auto v = node.find("base_color_texture")) p.base_color_texture = load_texture(*v, true);
  if (auto v = node.find("metallic")) p.metallic = v->as_float(0, 1);
  if (auto v = node.find("roughness")) p.roughness = v->as_float(0, 1);
  if (auto v = node.find("metallic_roughness_texture")) p.metallic_roughness_texture = load_texture(*v, false);
  if (auto v = node.find("normal_texture")) p.normal_texture = load_texture(*v, false);
  if (auto v = node.find("normal_scale")) p.normal_scale = v->as_float();
  if (auto v = node.find("emissive")) p.emissive = v->as_vec3(0);
  if (auto v = node.find("emissive_texture")) p.emissive_texture = load_texture(*v, true);
  if (auto v = node.find("double_sided")) p.double_sided = v->as_bool();
  emission = {p.emissive, p.emissive_texture, p.double_sided};
  return make_pbr_material(std::move(p));
}

Mat4 JsonSceneBuilder::parse_transform(const JsonNode& node) const {
  node.expect_object({"translate", "rotate", "scale", "matrix"});
  if (auto m = node.find("matrix")) {
    for (const char* k : {"translate", "rotate", "scale"})
      if (node.has(k)) node[k].fail("\"matrix\" replaces translate/rotate/scale; give one or the other");
    const auto e = m->elements();
    if (e.size() != 16) m->fail_expected("an array of 16 numbers (row-major 4x4)");
    Mat4 r;
    for (int i = 0; i < 16; ++i) r.m[i / 4][i % 4] = e[i].as_float();
    if (r.m[3][0] != 0 || r.m[3][1] != 0 || r.m[3][2] != 0 || r.m[3][3] != 1)
      m->fail("the last row must be [0, 0, 0, 1] (affine transforms only)");
    // Singular relative to its own scale (Hadamard: |det| <= the product of the column lengths), in double: an
    // absolute bound (1e-12) rejected a uniform scale of 1e-5, which "scale" accepts.
    const auto at = [&](int i, int j) { return static_cast<double>(r.m[i][j]); };
    const double det = r.determinant3();
    double columns = 1;
    for (int j = 0; j < 3; ++j) columns *= std::sqrt(at(0, j) * at(0, j) + at(1, j) * at(1, j) + at(2, j) * at(2, j));
    if (!(std::abs(det) > 1e-6 * columns)) m->fail("the matrix is singular (it flattens the shape)");
    return r;
  }
  Mat4 r;
  if (auto s = node.find("scale")) {
    const Vec3 v = s->value().is_array() ? s->as_vec3() : Vec3(s->as_float());
    if (v.x == 0 || v.y == 0 || v.z == 0) s->fail("scale must not be zero (it flattens the shape)");
    r = Mat4::scale(v);
  }
  // Euler angles in degrees, applied X first, then Y, then Z, all about the fixed world axes.
  if (auto a = node.find("rotate")) {
    const Vec3 deg = a->as_vec3();
    r = Mat4::rotate_axis({1, 0, 0}, deg.x) * r;
    r = Mat4::rotate_axis({0, 1, 0}, deg.y) * r;
    r = Mat4::rotate_axis({0, 0, 1}, deg.z) * r;
  }
  if (auto t = node.find("translate")) r = Mat4::translate(t->as_vec3()) * r;
  return r;
}

Camera frame_bounds(const Bounds3& bounds, float aspect) {
  Vec3 center(0.0f);
  float radius = 1;
  if (!bounds.empty()) {
    center = bounds.center();
    radius = 0.5f * length(bounds.diagonal());
    if (!(radius > 0) || !std::isfinite(radius)) radius = 1;
  }
  Camera c;
  c.fov_y_degrees = 40;
  // The narrower of the two half-angles decides how far back the bounding sphere fits.
  const float half_y = 0.5f * c.fov_y_degrees * kPi / 180;
  const float half_x = std::atan(std::tan(half_y) * aspect);
  const float distance = 1.05f * radius / std::sin(std::min(half_x, half_y));
  c.from = center + normalize(Vec3(0.35f, 0.25f, 1.0f)) * distance;
  c.to = center;
  c.up = {0, 1, 0};
  return c;
}

void frame_camera(Scene& scene, const Bounds3& bounds) {
  scene.framed = bounds;
  scene.camera = frame_bounds(bounds, float(scene.settings.width) / float(scene.settings.height));
}

JsonSceneBuilder::LightSize JsonSceneBuilder::quad_light_size(const JsonNode& node, Vec3 origin, Vec3 edge_u,
                                                              Vec3 edge_v, bool shape) {
  const float lu = length(edge_u), lv = length(edge_v);
  const bool u_shorter = lu <= lv;
  const char* kind = shape ? (u_shorter ? "emitting quad's edge_u" : "emitting quad's edge_v")
                           : (u_shorter ? "quad light's edge_u" : "quad light's edge_v");
  return {node[u_shorter ? "edge_u" : "edge_v"], kind, origin + edge_u * 0.5f + edge_v * 0.5f, u_shorter ? lu : lv,
          true};
}

void JsonSceneBuilder::note_small_lights() {
  const Bounds3 b = scene_.geometry.bounds();
  for (const LightSize& l : light_sizes_) {
    // The farthest a ray's origin can be: a corner of the geometry's box, or the camera.
    const Vec3 c = l.centre;
    double span = length(scene_.camera.from - c);
    for (int k = 0; k < (b.empty() ? 0 : 8); ++k) {
      const Vec3 corner{(k & 1 ? b.hi : b.lo).x, (k & 2 ? b.hi : b.lo).y, (k & 4 ? b.hi : b.lo).z};
      span = std::max(span, static_cast<double>(length(corner - c)));
    }
    const double scale = std::max(span, l.quad ? static_cast<double>(max_component(abs(c))) : 0.0);
    if (!(l.size < kMinLightSize * scale)) continue;
    char text[512];
    std::snprintf(text, sizeof text,
                  "warning: the %s, %g, is less than %g times the %s, %.4g: rays miss or hit a light this small as "
                  "float rounding falls, so uniform, bsdf and mis can render it too dark or with fireflies (light "
                  "and nee_mis sample it directly and are not affected)",
                  l.kind, l.size, kMinLightSize,
                  l.quad && scale > span ? "distance from the origin to its centre" : "span of the scene around it",
                  scale);
    scene_.small_lights.push_back(l.at.file() + ":" + l.at.pointer() + ": " + text);
  }
}

}  // namespace lumis
