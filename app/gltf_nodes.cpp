// glTF nodes: each node's local transform (matrix, or translation x rotation x scale), EXT_mesh_gpu_instancing's
// per-instance matrices, and perspective cameras (app/gltf_internal.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/gltf_internal.h"
#include "core/transform.h"

namespace lumis::gltf {

Mat4 local_transform(const Context& ctx, const tinygltf::Node& node, const std::string& at) {
  Mat4 m;
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) ctx.fail(at + ".matrix", "expected 16 numbers");
    // Column-major: elements 3, 7, 11, 15 are the last row, which an affine transform (all glTF allows) has as
    // (0, 0, 0, 1); a projective one would be read as if it were affine.
    const std::vector<double>& e = node.matrix;
    if (std::abs(e[3]) > 1e-6 || std::abs(e[7]) > 1e-6 || std::abs(e[11]) > 1e-6 || std::abs(e[15] - 1) > 1e-6) {
      char row[96];
      std::snprintf(row, sizeof row, "(%g, %g, %g, %g)", e[3], e[7], e[11], e[15]);
      ctx.fail(at + ".matrix", std::string("not an affine transform: its last row is ") + row +
                                   ", expected (0, 0, 0, 1) (elements 3, 7, 11 and 15, column-major)");
    }
    m = Mat4::from_column_major(node.matrix.data());
  } else {
    auto vec = [&](const std::vector<double>& v, size_t n, const char* name) {
      if (v.size() != n) ctx.fail(at + "." + name, "expected " + std::to_string(n) + " numbers");
      return v;
    };
    if (!node.translation.empty()) {
      const auto t = vec(node.translation, 3, "translation");
      m = m * Mat4::translate({float(t[0]), float(t[1]), float(t[2])});
    }
    if (!node.rotation.empty()) {
      const auto r = vec(node.rotation, 4, "rotation");
      // Normalised in double before the float conversion (1e-50 is 0 in float), scaled by the largest component
      // first so that the squares of 1e200 do not overflow; length 0 is no rotation at all.
      const double big = std::max({std::abs(r[0]), std::abs(r[1]), std::abs(r[2]), std::abs(r[3])});
      const double len = big > 0 && std::isfinite(big)
                             ? big * std::sqrt((r[0] / big) * (r[0] / big) + (r[1] / big) * (r[1] / big) +
                                               (r[2] / big) * (r[2] / big) + (r[3] / big) * (r[3] / big))
                             : big;
      if (!(len > 0) || !std::isfinite(len)) {
        char found[32];
        std::snprintf(found, sizeof found, "%g", len);
        ctx.fail(at + ".rotation",
                 std::string("expected a unit quaternion (x, y, z, w), found one of length ") + found);
      }
      m = m * Mat4::rotate_quaternion(
                  {float(r[0] / len), float(r[1] / len), float(r[2] / len), float(r[3] / len)});
    }
    if (!node.scale.empty()) {
      const auto s = vec(node.scale, 3, "scale");
      m = m * Mat4::scale({float(s[0]), float(s[1]), float(s[2])});
    }
  }
  if (!m.is_finite()) ctx.fail(at, "transform is not finite");
  return m;
}

/// EXT_mesh_gpu_instancing: one matrix per instance (T R S, in the node's space), or none when absent.
std::vector<Mat4> gpu_instances(Context& ctx, AccessorCache& acc, const tinygltf::Node& node, const std::string& at) {
  auto it = node.extensions.find("EXT_mesh_gpu_instancing");
  if (it == node.extensions.end()) return {};
  const std::string eat = at + ".extensions.EXT_mesh_gpu_instancing.attributes";
  // (tinygltf reads an empty object as no value: `{}` lands here too, and the extension asks for one attribute.)
  if (!it->second.IsObject() || !it->second.Has("attributes") || !it->second.Get("attributes").IsObject())
    ctx.fail(eat, "expected an object with at least one of TRANSLATION, ROTATION and SCALE (accessor indices)");
  const tinygltf::Value& attrs = it->second.Get("attributes");
  std::vector<Mat4> out;
  size_t count = 0;
  bool any = false;
  const FloatData *t = nullptr, *r = nullptr, *s = nullptr;
  auto get = [&](const char* name, int type, const ComponentTypes& components) -> const FloatData* {
    if (!attrs.Has(name)) return nullptr;
    if (!attrs.Get(name).IsInt()) ctx.fail(eat + "." + name, "expected an accessor index");
    const FloatData& d = acc.floats(attrs.Get(name).GetNumberAsInt(), eat + "." + name, {type}, components);
    if (any && d.count() != count)
      ctx.fail(eat + "." + name, "has " + std::to_string(d.count()) + " elements, expected " +
                                     std::to_string(count) + " like the other instance attributes");
    count = d.count();
    any = true;
    return &d;
  };
  t = get("TRANSLATION", TINYGLTF_TYPE_VEC3, kFloat);
  r = get("ROTATION", TINYGLTF_TYPE_VEC4, kFloatOrSnorm);
  s = get("SCALE", TINYGLTF_TYPE_VEC3, kFloat);
  if (!any) return {};
  for (size_t i = 0; i < count; ++i) {
    Mat4 m;
    if (t) m = m * Mat4::translate({t->values[3 * i], t->values[3 * i + 1], t->values[3 * i + 2]});
    if (r) {
      const Vec4 q{r->values[4 * i], r->values[4 * i + 1], r->values[4 * i + 2], r->values[4 * i + 3]};
      if (q.x == 0 && q.y == 0 && q.z == 0 && q.w == 0)
        ctx.fail(eat + ".ROTATION", "element " + std::to_string(i) + " is (0, 0, 0, 0), expected a unit quaternion");
      m = m * Mat4::rotate_quaternion(q);
    }
    if (s) m = m * Mat4::scale({s->values[3 * i], s->values[3 * i + 1], s->values[3 * i + 2]});
    out.push_back(m);
  }
  return out;
}

void set_camera(Context& ctx, GltfScene& scene, const tinygltf::Node& node, const Mat4& world, const std::string& at,
                int& orthographic) {
  const auto& cams = ctx.model.cameras;
  if (node.camera < 0 || static_cast<size_t>(node.camera) >= cams.size())
    ctx.fail(at + ".camera", "camera index " + std::to_string(node.camera) + " out of range");
  const tinygltf::Camera& c = cams[node.camera];
  const std::string cat = indexed("cameras", node.camera);
  if (c.type == "orthographic") {
    ++orthographic;
    return;
  }
  if (c.type != "perspective") ctx.fail(cat + ".type", "'" + c.type + "', expected perspective or orthographic");
  const auto& p = c.perspective;
  if (!(p.yfov > 0 && p.yfov < kPi)) ctx.fail(cat + ".perspective.yfov", "expected an angle in (0, pi) radians");
  if (!(p.znear >= 0) || !std::isfinite(p.znear)) ctx.fail(cat + ".perspective.znear", "expected a number >= 0");
  Camera cam;
  cam.from = world.apply_point({0, 0, 0});
  // The view direction as a vector: world.apply_point({0, 0, -1}) rounded back onto `from` 1e9 units out. `to`
  // stands as far off as `from` is from the origin (at least 1), so rounding it barely turns the view.
  const Vec3 view = world.apply_vector({0, 0, -1});
  const float scale = length(view);
  if (!is_finite(cam.from) || !std::isfinite(scale) || !(scale > 0))
    ctx.fail(at, "camera node transform is degenerate");
  cam.to = cam.from + view * (std::max(1.0f, max_component(abs(cam.from))) / scale);
  cam.up = normalize(world.apply_vector({0, 1, 0}));
  // znear is in camera space: scale it like the view direction.
  cam.near_clip = static_cast<float>(p.znear) * scale;
  if (!std::isfinite(cam.near_clip))
    ctx.fail(cat + ".perspective.znear", "expected a number >= 0 that stays finite in float once scaled by the "
                                         "camera node's transform");
  cam.fov_y_degrees = static_cast<float>(p.yfov * 180.0 / kPi);
  if (!(cam.fov_y_degrees > 0))  // 1e-50 passed the check above and is 0 in float
    ctx.fail(cat + ".perspective.yfov", "expected an angle in (0, pi) radians that is not 0 in float");
  if (!is_finite(cam.to) || !is_finite(cam.up) || cam.to == cam.from)
    ctx.fail(at, "camera node transform is degenerate");
  std::optional<float> aspect;
  if (p.aspectRatio > 0) aspect = static_cast<float>(p.aspectRatio);
  scene.cameras.push_back({node.name, c.name, at, cam, aspect});
  if (scene.cameras.size() == 1) {  // the first perspective camera is the default
    scene.camera = cam;
    scene.camera_aspect = aspect;
  }
}

}  // namespace lumis::gltf
