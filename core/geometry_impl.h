// Geometry's private state, shared by core/geometry.cpp (building the scene, hit records, shadow and light
// queries) and core/geometry_query.cpp (the pipelined closest-hit queries).
#pragma once

#include <embree3/rtcore.h>

#include <deque>
#include <vector>

#include "core/geometry.h"

namespace lumis {

// The calling thread's query log (lumis bench only); one load and a predictable branch per query otherwise.
extern constinit thread_local QueryLog* t_query_log;

struct Geometry::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  RTCScene light_scene = nullptr;  // light geometry only, for all_light_hits
  // deque: element addresses stay stable, Embree shares the vertex and index arrays.
  std::deque<TriangleMesh> meshes;
  // Per mesh, the three corners of every triangle in order and its unit geometric normal (48 bytes per
  // triangle): fill_hit reads one record instead of an index and then three vertices (two dependent cache misses
  // on large meshes), and no normal is computed per hit.
  struct TriangleRecord {
    Vec3 p0, p1, p2, ng;
  };
  std::deque<std::vector<TriangleRecord>> records;
  std::deque<Sphere> spheres;
  struct Slot {  // pointers into the deques above (their elements do not move)
    const TriangleMesh* mesh = nullptr;     // null for a sphere
    const TriangleRecord* records = nullptr;  // the mesh's, by primitive
    const Sphere* sphere = nullptr;         // null for a mesh
    bool has_tiny = false;  // a mesh with a triangle below float's range for |cross|^2 (fill_hit's special case)
    bool has_attributes = false;  // shading normals or uvs: fill_hit reads the indices and these
  };
  std::vector<Slot> slots;  // by geometry id
  size_t triangles = 0;
  bool prefetch = false;  // the triangle records outgrow the caches: prefetch hit records (set by commit)
  Bounds3 bounds;
};

}  // namespace lumis
