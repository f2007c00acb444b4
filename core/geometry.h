// Scene geometry on Embree 3: world-space triangle meshes and analytic spheres and the ray queries on them (rays
// and the surface record, Hit, are in core/ray.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/ray.h"
#include "core/texture.h"

namespace lumis {

/// Every ray query made on one thread while the log is set (Geometry::record_queries), in call order: `lumis bench`
/// times them again without shading (app/bench_replay.cpp), which gives Embree's own time for exactly a render's
/// rays. Off (no log) in every normal render.
struct QueryLog {
  enum class Call : uint8_t {
    Intersect1,   ///< rtcIntersect1 on each ray (intersect, intersect_each)
    Intersect16,  ///< one coherent rtcIntersect16 packet (intersect16)
    Occluded1,    ///< rtcOccluded1 (occluded)
    Occluded16,   ///< one rtcOccluded16 packet (occluded16)
    LightHits,    ///< all_light_hits on each ray
    Intersect16Incoherent,  ///< one rtcIntersect16 packet without the coherent flag (intersect_each, packets)
  };
  struct Entry {
    Call call;
    uint8_t n;       ///< rays, 1..16
    uint32_t first;  ///< index of the first in `rays`
  };
  std::vector<Ray> rays;
  std::vector<Entry> calls;
  /// Append one call on rays[0..n) (n <= 16).
  void add(Call call, const Ray* r, int n) {
    calls.push_back({call, static_cast<uint8_t>(n), static_cast<uint32_t>(rays.size())});
    rays.insert(rays.end(), r, r + n);
  }
};

/// Alpha test for glTF alphaMode MASK: a hit is ignored when factor * texture alpha * vertex alpha < cutoff.
struct AlphaMask {
  float cutoff = 0.5f;
  float factor = 1.0f;
  std::optional<Texture> texture;  ///< base colour texture (alpha channel)
};

/// A world-space triangle mesh. Front faces wind counter-clockwise; the geometric normal is
/// normalize(cross(p1 - p0, p2 - p0)).
struct TriangleMesh {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;     ///< per vertex, optional (empty = flat shading)
  std::vector<Vec4> tangents;    ///< per vertex xyz + handedness w, optional
  std::vector<Vec2> uv0, uv1;    ///< per vertex, optional
  std::vector<Vec4> colors;      ///< per vertex RGBA (COLOR_0), optional
  std::vector<uint32_t> indices; ///< 3 per triangle
  int material = -1;             ///< index into the scene's materials
  int light = -1;                ///< index into the scene's lights when emissive, else -1
  std::optional<AlphaMask> alpha;

  size_t triangle_count() const { return indices.size() / 3; }
};

/// Alpha of mesh m (which has m.alpha) on triangle prim at barycentrics (u, v) = weights of its vertices 1 and 2:
/// factor x vertex alpha x texture alpha; a point is cut out when this is below m.alpha->cutoff.
float alpha_at(const TriangleMesh& m, unsigned prim, float u, float v);

struct Sphere {
  Vec3 center;
  float radius = 1;
  int material = -1;  ///< -1: a pure emitter (sphere light) that only emits
  int light = -1;
};

/// Barycentrics (b1, b2: the weights of p1 and p2) of a point p in the plane of triangle (p0, p1, p2), clamped to
/// the triangle: sub-triangle areas over the area through the unit normal, so that no squared cross product
/// leaves float's range at very large or small scales; (0, 0) for a degenerate triangle.
inline Vec2 triangle_barycentrics(Vec3 p, Vec3 p0, Vec3 p1, Vec3 p2) {
  const Vec3 c = cross(p1 - p0, p2 - p0);
  const Vec3 n = robust_normalize(c);
  const float inv = 1 / robust_length(c);
  if (!std::isfinite(inv) || n == Vec3{}) return {0, 0};
  const float b1 = clamp(dot(cross(p - p0, p2 - p0), n) * inv, 0, 1);
  return {b1, clamp(dot(cross(p1 - p0, p - p0), n) * inv, 0, 1 - b1)};
}

/// One intersection of a ray with light geometry (see Geometry::all_light_hits).
struct LightHitRecord {
  uint32_t geom_id, prim_id;
  float t, u, v;
};

class Geometry {
 public:
  Geometry();
  ~Geometry();
  Geometry(const Geometry&) = delete;
  Geometry& operator=(const Geometry&) = delete;

  /// Add a mesh; returns its geometry id. Call commit() after the last add.
  uint32_t add_mesh(TriangleMesh mesh);
  /// Add a sphere; returns its geometry id.
  uint32_t add_sphere(Sphere sphere);
  /// Build the BVH.
  void commit();

  /// Closest hit in (ray.tmin, ray.tmax). The ray must be finite (checked).
  bool intersect(const Ray& ray, Hit& hit) const;
  /// Closest hits of up to 16 coherent rays (camera rays) in one Embree packet query: found[i] and hits[i] as
  /// intersect(rays[i], hits[i]) would give, for i < n (an invalid ray is a miss).
  void intersect16(const Ray* rays, int n, Hit* hits, bool* found) const;
  /// intersect16 on each packet of coherent rays, packet p holding rays [packet_end[p - 1], packet_end[p])
  /// (packet_end[-1] = 0, each packet at most 16 rays): the same results, with the hit records of one packet read
  /// while the next ones are traced.
  void intersect_packets(const Ray* rays, const int* packet_end, int n_packets, Hit* hits, bool* found) const;
  /// found[k] = intersect(rays[k], hits[k]) for every lane k = lanes[i], i < m (other lanes' found and hits
  /// untouched); in chunks of 16 lanes. On scenes with large records (prefetches_hit_records()) a chunk's hit
  /// records are prefetched and read while the next chunks are traced, so that their memory loads overlap with
  /// Embree's work instead of each stalling its ray. packets = false: one rtcIntersect1 per ray, the same results
  /// bit for bit; true: each chunk of two or more rays as one incoherent rtcIntersect16 packet, the same hits with
  /// t rounded as Embree's packet kernels round it (the last bits).
  void intersect_each(const Ray* rays, const int* lanes, int m, Hit* hits, bool* found, bool packets = false) const;
  /// Whether anything lies in (ray.tmin, ray.tmax).
  bool occluded(const Ray& ray) const;
  /// occluded(rays[i]) for i < n (n <= 16) in one Embree packet query (shadow rays of neighbouring paths).
  void occluded16(const Ray* rays, int n, bool* occluded) const;
  /// Every intersection of the ray with geometry that carries a light (light >= 0), ignoring all other geometry
  /// and occlusion, in any order; at most max_hits are stored, the return value is the number found (more than
  /// max_hits: query again with room for them all). The one-sample MIS density needs every light whose solid angle
  /// contains a direction, visible or not.
  int all_light_hits(const Ray& ray, LightHitRecord* out, int max_hits) const;

  bool is_mesh(uint32_t geom_id) const;
  const TriangleMesh& mesh(uint32_t geom_id) const;
  const Sphere& sphere(uint32_t geom_id) const;
  size_t geometry_count() const;
  size_t triangle_count() const;
  Bounds3 bounds() const;
  /// Fill the Hit of a ray with primitive prim_id at Embree's barycentrics (b1, b2); hit.p holds o + t d on entry.
  void fill_hit(uint32_t geom_id, uint32_t prim_id, float b1, float b2, Hit& hit) const;
  /// Whether the queries prefetch hit records (set by commit: when the triangle records outgrow a core's cache).
  bool prefetches_hit_records() const;
  /// The committed RTCScene (as void*, so this header needs no Embree include); for raw-throughput benchmarks.
  void* embree_scene() const;
  /// From now on, every query the calling thread makes (on any Geometry) is appended to log; nullptr stops.
  static void record_queries(QueryLog* log);

 private:
  /// Start loading what fill_hit will read for a hit on (geom_id, prim_id).
  void prefetch_hit_record(uint32_t geom_id, uint32_t prim_id) const;
  /// Start loading the shading normals and uvs of the hit's corners (reads its indices: prefetch those first).
  void prefetch_hit_attributes(uint32_t geom_id, uint32_t prim_id) const;
  /// Embree's answer for one ray, kept until its hit record is filled.
  struct RawHit {
    uint32_t geom_id, prim_id;
    float u, v, t;
  };
  enum class Trace { Single, Incoherent16, Coherent16 };
  static constexpr int kMaxChunks = 16;
  /// The closest hits of chunks of up to 16 rays (chunk c: list positions [chunk_end[c - 1], chunk_end[c]) of lanes,
  /// or of the rays themselves when lanes is null; chunk_end[-1] = start), three stages in a pipeline: trace,
  /// prefetch, fill.
  void pipeline(const Ray* rays, const int* lanes, int start, const int* chunk_end, int chunks, Hit* hits,
                bool* found, Trace how) const;
  /// The pipeline's first stage for one chunk (m <= 16): trace, keep the raw hits, prefetch their records if asked.
  void trace16(const Ray* rays, const int* lanes, int first, int m, RawHit* raw, bool* got, Trace how,
               bool prefetch) const;
  /// The pipeline's last stage for one chunk: hits[k] and found[k] of its lanes k from raw and got.
  void fill16(const Ray* rays, const int* lanes, int first, int m, const RawHit* raw, const bool* got, Hit* hits,
              bool* found) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lumis
