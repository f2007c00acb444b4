// Shared pieces of the glTF loader (gltf_loader.cpp, gltf_parse.cpp, gltf_accessor.cpp, gltf_components.cpp,
// gltf_materials.cpp, gltf_textures.cpp, gltf_nodes.cpp, gltf_primitives.cpp, gltf_uri.cpp, gltf_json_checks.cpp).
// Not a public API.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "app/gltf_loader.h"
#include "app/json_reader.h"
#include "app/scene_error.h"
#include "core/image.h"
#include "core/transform.h"

namespace lumis::gltf {

/// What every part of the loader needs: the parsed file, where it came from, and where warnings go.
struct Context {
  std::string file;      ///< as given by the caller, for messages
  std::string base_dir;  ///< folder that relative URIs resolve against
  tinygltf::Model model;
  std::vector<std::string>* warnings = nullptr;
  std::vector<std::string>* image_files = nullptr;  ///< GltfScene::image_files
  std::set<std::string> warned;  ///< warning keys already reported (one warning per kind)

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw SceneError(file, where, what);
  }
  void warn(const std::string& text) { warnings->push_back(text); }
  /// Report a kind of warning only the first time.
  void warn_once(const std::string& key, const std::string& text) {
    if (warned.insert(key).second) warn(text);
  }
};

/// "name[i]", the way glTF paths index arrays.
inline std::string indexed(const std::string& name, size_t i) { return name + "[" + std::to_string(i) + "]"; }

// --- component and element types (gltf_components.cpp) ---

/// Bytes of one component of TINYGLTF_COMPONENT_TYPE_*; 0 for a type glTF 2.0 accessors do not allow.
int component_size(int ctype);
/// Components of one element of TINYGLTF_TYPE_* (MAT3: 9); 0 when unknown.
int type_components(int type);
/// "VEC3" and the like, for messages.
std::string type_name(int type);
/// "normalized UNSIGNED_BYTE" and the like, for messages.
std::string component_name(int ctype, bool normalized);
/// One component at `p` as float; normalized integers follow glTF's max(c / (2^(n-1) - 1), -1) and c / (2^n - 1).
float decode_component(const unsigned char* p, int ctype, bool normalized);
/// One unsigned integer component at `p` (indices).
uint32_t decode_uint(const unsigned char* p, int ctype);

// --- accessors (gltf_accessor.cpp) ---

/// Float view of an accessor: `components` per element, normalized integers mapped to [0,1] / [-1,1].
struct FloatData {
  int components = 0;
  std::vector<float> values;  ///< count * components
  size_t count() const { return components ? values.size() / components : 0; }
};

/// The component types (TINYGLTF_COMPONENT_TYPE_*, each plain or normalized) that core glTF 2.0 allows an accessor
/// where it is used. lumis does not support KHR_mesh_quantization, which allows more for vertex attributes.
struct ComponentTypes {
  std::vector<std::pair<int, bool>> allowed;  ///< (component type, normalized)
  bool quantizable = true;                    ///< KHR_mesh_quantization would allow others (said in messages)
};
/// FLOAT only: POSITION, NORMAL, TANGENT, instance TRANSLATION and SCALE.
inline const ComponentTypes kFloat = {{{TINYGLTF_COMPONENT_TYPE_FLOAT, false}}};
/// FLOAT or normalized unsigned integers: TEXCOORD_n.
inline const ComponentTypes kFloatOrUnorm = {{{TINYGLTF_COMPONENT_TYPE_FLOAT, false},
                                              {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, true},
                                              {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, true}}};
/// COLOR_n: the same types, which KHR_mesh_quantization does not widen for colours.
inline const ComponentTypes kColor = {kFloatOrUnorm.allowed, /*quantizable=*/false};
/// FLOAT or normalized signed integers: instance ROTATION (EXT_mesh_gpu_instancing).
inline const ComponentTypes kFloatOrSnorm = {{{TINYGLTF_COMPONENT_TYPE_FLOAT, false},
                                              {TINYGLTF_COMPONENT_TYPE_BYTE, true},
                                              {TINYGLTF_COMPONENT_TYPE_SHORT, true}}};

/// Decoded accessors, each read and validated once however many primitives share it.
class AccessorCache {
 public:
  explicit AccessorCache(Context& ctx) : ctx_(ctx) {}
  /// Accessor `index`, referenced from `where`; its element type must be one of `types` (TINYGLTF_TYPE_*) and its
  /// component type one of `components`. With `finite`, NaN or Inf values are an error.
  const FloatData& floats(int index, const std::string& where, std::vector<int> types,
                          const ComponentTypes& components, bool finite = true);
  /// Scalar unsigned-integer accessor (indices).
  const std::vector<uint32_t>& uints(int index, const std::string& where);

 private:
  Context& ctx_;
  std::map<int, FloatData> floats_;
  std::map<int, std::vector<uint32_t>> uints_;
};

/// Raw bytes of a validated buffer view (offset and length inside its buffer).
std::pair<const unsigned char*, size_t> buffer_view_bytes(const Context& ctx, int view, const std::string& where);

// --- parsing (gltf_parse.cpp) ---

/// Reads `path` (.gltf or .glb, told by its first bytes) into ctx.model through tinygltf, after checking its JSON text
/// (nesting depth, matrix nodes, negative offsets, '+' in URIs), and checks its version, its buffer files and its
/// external images; any fault is ctx.fail with the glTF path, in glTF terms where tinygltf's message is not.
void parse_file(Context& ctx, const std::string& path);

// --- valid files tinygltf 2.7 refuses (gltf_lenient.cpp) ---

/// The JSON text to give tinygltf instead of the file's: the document without its animations, when a channel's
/// target has no node (optional in glTF; tinygltf refuses the file). Nothing when the file's own text will do.
std::optional<std::string> text_for_tinygltf(const Json& doc);

/// Loads the glTF file at `path` (a .glb when `binary`, its binary chunk kept) with `json` as its JSON text.
bool load_text(tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& err, std::string& warn,
               const std::string& path, bool binary, const std::string& json);

/// tinygltf's errors without those on what glTF allows: a skin without inverseBindMatrices.
std::string without_spec_valid_complaints(std::string err);

// --- URIs (gltf_uri.cpp) ---

/// A relative URI's file name: percent-escapes such as %20 decoded, a '+' kept (RFC 3986).
std::string decode_uri(const std::string& uri);

/// Path of a relative URI (decode_uri) in the glTF file's folder.
std::string resolve_uri(const Context& ctx, const std::string& uri);

/// Why `file` (a buffer's or image's) cannot be read: "not found", "is a folder" or "is not a regular file (a pipe,
/// device or socket)", which would block a read; empty for a regular file (links followed).
std::string unreadable_reason(const std::string& file);

/// buffers[i]'s URI: an external file must be in the glTF file's folder and hold byte_length bytes. When explaining
/// why tinygltf rejected the file (`uri` as the JSON gives it), also: not empty (a .glb's own buffer has no uri at
/// all), and a data: URI is base64 of a media type tinygltf decodes, holding byte_length bytes.
void check_buffer_uri(const Context& ctx, size_t i, const std::string& uri, uint64_t byte_length, bool explaining);

/// tinygltf 2.7 decodes a buffer's or image's URI as a web form does, '+' as a space, joins it to the folder and
/// hands the path to FsCallbacks::ExpandFilePath: expand_plus_uri gives it its '+' back. `plus` maps tinygltf's
/// reading of each URI that holds a '+' to the file name it means.
struct PlusUris {
  std::map<std::string, std::string> plus;
};

/// The buffers' and images' URIs in the glTF JSON `doc` that hold a '+'. Two URIs that tinygltf reads alike but that
/// name different files ("a+b.bin", "a%20b.bin") are an error.
PlusUris plus_uris(const Context& ctx, const Json& doc);

/// FsCallbacks::ExpandFilePath (user data: a PlusUris): `path` with a file name tinygltf misread put right.
std::string expand_plus_uri(const std::string& path, void* plus_uris);

// --- nodes (gltf_nodes.cpp) ---

// --- checks of the JSON text (gltf_json_checks.cpp) ---

/// The glTF JSON `doc` (the file's text parsed before tinygltf reads it; not an object: nothing checked, tinygltf
/// reports it): a field lumis reads that has the wrong type (which tinygltf would ignore silently, keeping its
/// default), an index beyond int's range, a negative byte offset, length or stride, a node with both "matrix" and
/// translation/rotation/scale, a baseColorFactor or emissiveFactor of another length, an accessor type glTF has not,
/// or a perspective camera without yfov is an error naming its glTF path.
void check_json(const Context& ctx, const Json& doc);

/// A node's transform in its parent's space: `matrix`, or translation x rotation x scale (rotation normalised).
Mat4 local_transform(const Context& ctx, const tinygltf::Node& node, const std::string& at);
/// EXT_mesh_gpu_instancing: one matrix per instance (T R S, in the node's space), or none when absent.
std::vector<Mat4> gpu_instances(Context& ctx, AccessorCache& acc, const tinygltf::Node& node, const std::string& at);
/// Adds the node's perspective camera (world transform `world`) to scene.cameras (the first is the default);
/// counts orthographic ones, which lumis does not render.
void set_camera(Context& ctx, GltfScene& scene, const tinygltf::Node& node, const Mat4& world, const std::string& at,
                int& orthographic);

// --- textures (gltf_textures.cpp) ---

/// The file's images, each (image, sRGB) pair decoded once (to R, G, B and optionally A) and shared by every texture
/// that uses it. Files an image came from are added to ctx.image_files when first used.
class ImageCache {
 public:
  explicit ImageCache(Context& ctx) : ctx_(ctx) {}
  /// Decode the given (image, sRGB) pairs on all cores; errors surface later, in get(), in file order.
  void prefetch(const std::set<std::pair<int, bool>>& keys);
  /// images[index], decoded with or without the sRGB curve; `where` names the reference in errors.
  std::shared_ptr<const Image> get(int index, bool srgb, const std::string& where);

 private:
  Image load(int index, bool srgb);

  Context& ctx_;
  std::map<std::pair<int, bool>, std::shared_ptr<const Image>> cache_;
  std::set<int> recorded_;  ///< images whose file is in ctx_.image_files
};

/// An extension's number (tinygltf::Value), finite as a float, or an error at `where`.
float number(const Context& ctx, const tinygltf::Value& v, const std::string& where);
/// A material's texture reference (index, texCoord, extensions) to a Texture; `where` is e.g.
/// "materials[2].pbrMetallicRoughness.baseColorTexture".
Texture make_texture(Context& ctx, ImageCache& images, int index, int tex_coord,
                     const tinygltf::ExtensionMap& extensions, bool srgb, const std::string& where);

// --- materials (gltf_materials.cpp) ---

/// Convert every material of the file, in order (textures decoded once each and shared).
std::vector<GltfMaterial> convert_materials(Context& ctx);

// --- primitives (gltf_primitives.cpp) ---

/// Turns (mesh, world transform) instances into world-space TriangleMeshes appended to the scene.
class PrimitiveBuilder {
 public:
  PrimitiveBuilder(Context& ctx, AccessorCache& acc, GltfScene& scene) : ctx_(ctx), acc_(acc), scene_(scene) {}
  /// Every primitive of meshes[mesh] placed by `world`; `node_at` names the node for messages.
  void add_mesh(int mesh, const Mat4& world, const std::string& node_at);
  /// Summary warnings (skipped primitives, dropped triangles).
  void finish();

 private:
  /// A primitive's vertex data in its own space, decoded once however often it is instanced.
  struct Decoded {
    bool skip = false;
    std::vector<Vec3> positions, normals;
    std::vector<Vec4> tangents, colors;
    std::vector<Vec2> uv0, uv1;
    std::vector<uint32_t> indices;  ///< 3 per triangle, strips and fans already converted
    int material = -1;
  };
  const Decoded& decode(int mesh, int prim);

  Context& ctx_;
  AccessorCache& acc_;
  GltfScene& scene_;
  std::map<std::pair<int, int>, Decoded> cache_;
  int default_material_ = -1;
  size_t skipped_non_triangles_ = 0, degenerate_ = 0;
};

}  // namespace lumis::gltf
