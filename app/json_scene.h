// Internal to the scene loader: turns the "materials", "shapes" and "lights" sections of a lumis JSON scene (and
// glTF contents) into Scene objects. Every error is a SceneError at the JSON pointer of the offending value.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/gltf_loader.h"
#include "app/json_reader.h"
#include "core/transform.h"
#include "integrators/scene.h"

namespace lumis {

/// How a material emits when a shape uses it (JSON "pbr" emissive or a glTF material's emissive).
struct MaterialEmission {
  Color factor;
  std::optional<Texture> texture;
  bool two_sided = false;
  bool emits() const { return !is_black(factor); }
};

/// A mesh's "sampling" member ("spherical_triangle", the default, or "area").
TriangleSampling json_mesh_sampling(const JsonNode& node);

class JsonSceneBuilder {
 public:
  /// file: the scene file (for messages); relative paths resolve against its folder.
  JsonSceneBuilder(Scene& scene, const std::string& file);

  void add_materials(const JsonNode& node);  ///< the "materials" object
  void add_shape(const JsonNode& node);      ///< one element of "shapes"
  void add_light(const JsonNode& node);      ///< one element of "lights"

  /// Add a loaded glTF's meshes. remap[i] >= 0 replaces glTF material i by scene material remap[i] (with that
  /// material's emission); otherwise the glTF material is used as it is. Returns whether any mesh emits.
  bool add_gltf(const GltfScene& gltf, const std::vector<int>& remap, TriangleSampling sampling);

  /// World-space bounds of everything added so far (for framing a camera).
  const Bounds3& bounds() const { return bounds_; }

  /// A sphere or quad light as added: where its size is given, its centre, and its size (radius, shorter edge).
  struct LightSize {
    JsonNode at;
    const char* kind;  ///< "sphere light's radius", ...
    Vec3 centre;
    float size;
    bool quad;  ///< its corners are rounded where they stand: its distance from the origin counts too
  };
  /// With the whole scene and its camera in place: a warning in Scene::small_lights for each light smaller than
  /// kMinLightSize of its distance to the far side of the scene (for a quad, also of its distance to the origin).
  void note_small_lights();

 private:
  Scene& scene_;
  std::string file_;
  std::filesystem::path folder_;
  std::map<std::string, int> material_index_;
  std::map<int, MaterialEmission> material_emission_;
  std::map<std::pair<std::string, bool>, std::shared_ptr<const Image>> images_;
  Bounds3 bounds_;
  std::vector<LightSize> light_sizes_;

  /// A path value resolved against the scene's folder; the file must exist.
  std::string resolve_path(const JsonNode& node) const;
  /// An image file as a texture (colour textures are decoded from sRGB). Loaded once per path.
  Texture load_texture(const JsonNode& node, bool srgb);
  int material_reference(const JsonNode& node) const;
  std::unique_ptr<Material> parse_material(const JsonNode& node, MaterialEmission& emission);
  Mat4 parse_transform(const JsonNode& node) const;
  /// Radiance: three finite non-negative numbers, not all zero.
  Color parse_radiance(const JsonNode& node) const;

  void add_sphere_shape(const JsonNode& node);
  void add_quad_shape(const JsonNode& node);
  void add_mesh_shape(const JsonNode& node);
  void add_gltf_shape(const JsonNode& node);
  /// Add a mesh as geometry; with a non-black emission it also becomes a mesh light.
  void add_mesh(TriangleMesh mesh, const MaterialEmission& emission, TriangleSampling sampling);
  void add_environment(const JsonNode& node);
  /// The LightSize of a quad light, or of an emitting quad shape (node: its JSON object): centre, shorter edge.
  static LightSize quad_light_size(const JsonNode& node, Vec3 origin, Vec3 edge_u, Vec3 edge_v, bool shape);
};

/// A camera looking at the centre of `bounds` from the +Z side (slightly above and to the right), with a 40 degree
/// vertical field of view, far enough back that the bounding sphere fits the image of the given aspect ratio.
Camera frame_bounds(const Bounds3& bounds, float aspect);
/// Give the scene a framing camera for `bounds` at its settings' aspect ratio, and remember the bounds
/// (Scene::framed) so that a new image size can frame them again.
void frame_camera(Scene& scene, const Bounds3& bounds);

// Embree's triangle test multiplies three lengths (a vertex relative to the ray's origin, dotted with the product of
// two edges): with every point within L of the origin that is at most about 83 L^3, which must fit in float (3.4e38),
// so L < 1.6e12. Beyond, a finite ray misses every triangle: at 1e13 scene units triangles cast no shadows (a
// helper's finding, 2026-12-07; the limit was 1e15, set for Embree's 1.8e18 bound on ray origins). Every coordinate
// of the geometry and the camera stays within this many scene units of the origin. (A framing camera stands about 3
// extents away, 3 / aspect for a tall image: an extreme aspect ratio can put it out of range.)
inline constexpr float kMaxCoordinate = 1e12f;

// Embree's sphere test rounds the ray's closest approach to the centre by a few float ulps of the distance, and a
// quad's corners are rounded to float where they stand: a light far smaller than those lengths is hit as rounding
// falls (measured: `mis` was right at a radius of 6.5e-6 of the scene's span around it, got fireflies at 2.2e-6 and
// went black at 2e-9). Below this fraction, 4.5 times above the fireflies, the loader warns. (1e-4 warned of a 0.1
// light over a 2000-unit ground plane, which every variant renders alike.)
inline constexpr double kMinLightSize = 1e-5;

}  // namespace lumis
