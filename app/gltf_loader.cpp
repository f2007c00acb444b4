// Loading a glTF file: its extensions and node hierarchy validated, and its default scene flattened into world-space
// meshes. Parsing (through tinygltf) is in gltf_parse.cpp, accessors in gltf_accessor.cpp (their types in
// gltf_components.cpp), materials in gltf_materials.cpp (their textures in gltf_textures.cpp), primitives in
// gltf_primitives.cpp, node transforms, instancing and cameras in gltf_nodes.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/gltf_internal.h"

namespace lumis {

namespace fs = std::filesystem;
using namespace gltf;

namespace {

void check_extensions(Context& ctx) {
  static const std::set<std::string> supported = {"KHR_texture_transform", "KHR_materials_emissive_strength",
                                                   "EXT_mesh_gpu_instancing"};
  std::string refused;  // every one, so that a user knows at once what to convert away
  size_t n_refused = 0;
  for (const auto& e : ctx.model.extensionsRequired)
    if (!supported.count(e)) refused += (n_refused++ ? ", " : "") + e;
  if (n_refused)
    ctx.fail("extensionsRequired", (n_refused > 1 ? "required extensions " + refused + " are" :
                                                    "required extension " + refused + " is") + " not supported");
  // Lamps (KHR_lights_punctual, as Blender exports them) get a warning of their own: a dark or sky-lit render would
  // otherwise leave a user wondering where they went. The name list is enough for other extensions.
  const auto& lamps = ctx.model.lights;
  std::string ignored;
  for (const auto& e : ctx.model.extensionsUsed)
    if (!supported.count(e) && !(e == "KHR_lights_punctual" && !lamps.empty()))
      ignored += (ignored.empty() ? "" : ", ") + e;
  if (!ignored.empty()) ctx.warn("ignored glTF extensions: " + ignored);
  if (lamps.empty()) return;
  std::map<std::string, int> kinds;  // "point", "spot", "directional"
  for (const auto& l : lamps) ++kinds[l.type.empty() ? "untyped" : l.type];
  std::string counts;
  for (const auto& [type, n] : kinds) counts += (counts.empty() ? "" : ", ") + std::to_string(n) + " " + type;
  ctx.warn("KHR_lights_punctual: not rendering the file's " + std::to_string(lamps.size()) +
           (lamps.size() == 1 ? " light (" : " lights (") + counts +
           "): lumis has no point, spot or directional lights (it renders emissive materials as a glTF file's lights)");
}

/// Every child index in range, every node with at most one parent, and no cycles (checked without recursion).
std::vector<int> check_hierarchy(const Context& ctx) {
  const auto& nodes = ctx.model.nodes;
  std::vector<int> parent(nodes.size(), -1);
  for (size_t i = 0; i < nodes.size(); ++i)
    for (size_t k = 0; k < nodes[i].children.size(); ++k) {
      const int c = nodes[i].children[k];
      const std::string at = indexed("nodes", i) + indexed(".children", k);
      if (c < 0 || static_cast<size_t>(c) >= nodes.size())
        ctx.fail(at, "node index " + std::to_string(c) + " out of range (the file has " +
                         std::to_string(nodes.size()) + " nodes)");
      if (static_cast<size_t>(c) == i) ctx.fail(at, "node is its own child (the hierarchy has a cycle)");
      if (parent[c] >= 0)
        ctx.fail(at, "nodes[" + std::to_string(c) + "] already has parent nodes[" + std::to_string(parent[c]) +
                         "] (nodes must form a tree)");
      parent[c] = static_cast<int>(i);
    }
  // With one parent each, a cycle is a parent chain that returns to a node still being walked.
  std::vector<char> state(nodes.size(), 0);  // 0 unseen, 1 on the current walk, 2 reaches a root
  for (size_t start = 0; start < nodes.size(); ++start) {
    std::vector<int> walk;
    int n = static_cast<int>(start);
    while (n >= 0 && state[n] == 0) {
      state[n] = 1;
      walk.push_back(n);
      n = parent[n];
    }
    if (n >= 0 && state[n] == 1) ctx.fail(indexed("nodes", n), "the node hierarchy has a cycle");
    for (int w : walk) state[w] = 2;
  }
  return parent;
}

}  // namespace

GltfScene load_gltf(const std::string& path, const Mat4& transform, bool read_cameras) {
  GltfScene scene;
  Context ctx;
  ctx.file = path;
  ctx.base_dir = fs::path(path).parent_path().string();
  ctx.warnings = &scene.warnings;
  ctx.image_files = &scene.image_files;
  if (!transform.is_finite()) ctx.fail("", "the transform given to the loader is not finite");
  parse_file(ctx, path);
  for (const auto& b : ctx.model.buffers)  // a .glb's own buffer has no URI
    if (!b.uri.empty() && b.uri.rfind("data:", 0) != 0) scene.buffer_files.push_back(resolve_uri(ctx, b.uri));
  check_extensions(ctx);
  scene.materials = convert_materials(ctx);
  const std::vector<int> parent = check_hierarchy(ctx);

  // The default scene, else scene 0, else (no scenes at all) every root node.
  std::vector<int> roots;
  const auto& model = ctx.model;
  std::string nodes_drawn = "node";  // which nodes are drawn, for why_empty
  if (model.defaultScene >= 0 || !model.scenes.empty()) {
    const int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    nodes_drawn = model.defaultScene >= 0 ? "node of its default scene, " + indexed("scenes", s) + ","
                                          : "node of scenes[0] (the file names no default scene)";
    if (static_cast<size_t>(s) >= model.scenes.size())
      ctx.fail("scene", "scene index " + std::to_string(s) + " out of range");
    roots = model.scenes[s].nodes;
    std::vector<char> listed(model.nodes.size(), 0);
    for (size_t k = 0; k < roots.size(); ++k) {
      const std::string at = indexed("scenes", s) + indexed(".nodes", k);
      if (roots[k] < 0 || static_cast<size_t>(roots[k]) >= model.nodes.size())
        ctx.fail(at, "node index " + std::to_string(roots[k]) + " out of range");
      if (parent[roots[k]] >= 0) ctx.fail(at, "scene nodes must be roots, but this node has a parent");
      if (listed[roots[k]]++)
        ctx.fail(at, "node " + std::to_string(roots[k]) + " is listed twice (it would be drawn twice)");
    }
  } else {
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (parent[i] < 0) roots.push_back(static_cast<int>(i));
    if (!roots.empty()) ctx.warn("the file has no scenes: showing all root nodes");
  }

  AccessorCache acc(ctx);
  PrimitiveBuilder builder(ctx, acc, scene);
  int orthographic = 0;
  bool mesh_nodes = false;
  // Depth-first, pre-order, in file order (a tree, checked above, so the stack cannot grow without bound).
  std::vector<std::pair<int, Mat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, transform);
  while (!stack.empty()) {
    const auto [n, parent_world] = stack.back();
    stack.pop_back();
    const tinygltf::Node& node = model.nodes[n];
    const std::string at = indexed("nodes", n);
    const Mat4 world = parent_world * local_transform(ctx, node, at);
    if (!world.is_finite()) ctx.fail(at, "world transform is not finite");
    if (node.skin >= 0) ctx.warn_once("skin", "skins ignored (skinned meshes are drawn in their bind pose)");
    if (node.camera >= 0 && read_cameras) {
      if (scene.cameras.empty()) {
        set_camera(ctx, scene, node, world, at, orthographic);  // the default camera: its errors are the file's
      } else {
        try {  // another camera is only a choice (--camera): a broken one is left out with a warning
          set_camera(ctx, scene, node, world, at, orthographic);
        } catch (const SceneError& e) {
          ctx.warn("camera skipped: " + e.location + ": " + e.detail);
        }
      }
    }
    if (node.mesh >= 0) {
      mesh_nodes = true;
      const std::vector<Mat4> instances = gpu_instances(ctx, acc, node, at);
      if (instances.empty()) builder.add_mesh(node.mesh, world, at);
      for (const Mat4& inst : instances) builder.add_mesh(node.mesh, world * inst, at);
    }
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.emplace_back(*c, world);
  }
  builder.finish();
  if (orthographic > 0)
    scene.warnings.push_back("orthographic cameras skipped (" + std::to_string(orthographic) + ")");
  for (const auto& m : scene.meshes)
    for (const Vec3& p : m.positions) scene.bounds.expand(p);
  // A file whose meshes only other scenes (or no node) use: "has no triangle meshes" would send its author looking
  // for them in the wrong place.
  if (scene.meshes.empty())
    scene.why_empty = !model.meshes.empty() && !mesh_nodes
                          ? "no " + nodes_drawn + " has a mesh (the file's " + std::to_string(model.meshes.size()) +
                                (model.meshes.size() == 1 ? " mesh is" : " meshes are") + " not drawn)"
                          : "the glTF file has no triangle meshes";
  return scene;
}

}  // namespace lumis
