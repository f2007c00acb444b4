#include "core/geometry.h"

#include "core/embree_util.h"
#include "core/geometry_impl.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace lumis {

namespace {

struct AlphaData {
  const TriangleMesh* mesh;
};

}  // namespace

float alpha_at(const TriangleMesh& m, unsigned prim, float u, float v) {
  const AlphaMask& a = *m.alpha;
  float alpha = a.factor;
  const uint32_t i0 = m.indices[3 * prim], i1 = m.indices[3 * prim + 1], i2 = m.indices[3 * prim + 2];
  const float b0 = 1 - u - v;
  if (!m.colors.empty()) alpha *= b0 * m.colors[i0].w + u * m.colors[i1].w + v * m.colors[i2].w;
  if (a.texture) {
    const auto& uvs = a.texture->tex_coord == 1 ? m.uv1 : m.uv0;
    Vec2 uv{0, 0};
    if (!uvs.empty()) uv = uvs[i0] * b0 + uvs[i1] * u + uvs[i2] * v;
    alpha *= a.texture->sample(uv).w;
  }
  return alpha;
}

namespace {

void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* mesh = static_cast<const TriangleMesh*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    if (alpha_at(*mesh, prim, u, v) < mesh->alpha->cutoff) args->valid[i] = 0;
  }
}


/// Unit normal of triangle (p0, p1, p2), normalize(cross(p1 - p0, p2 - p0)), at any scale: far outside unit scale
/// the cross product is rescaled (huge triangles, edges beyond ~1e8 units, overflow |c|^2); `tiny` is set when
/// |c|^2 < 1e-30 (edges below ~3e-8 units, as in a scene scaled by 1e-9). A degenerate triangle gets +z.
Vec3 face_normal(Vec3 p0, Vec3 p1, Vec3 p2, bool& tiny) {
  const Vec3 c = cross(p1 - p0, p2 - p0);
  const float c2 = length_squared(c);
  if (c2 >= 1e-30f && c2 <= 1e30f) [[likely]] return c / std::sqrt(c2);
  tiny = !(c2 >= 1e-30f);
  const Vec3 ng = robust_normalize(c);
  return ng == Vec3{} ? Vec3{0, 0, 1} : ng;
}

/// A floor under a tiny triangle's hit-point error bound. Embree decides which side of the triangle a ray starts
/// on by the sign of a product of its cross product with a length; for triangles this small that product is a
/// float denormal, whose error is a few of the smallest denormals (1.4e-45) whatever the coordinates. An origin
/// moved kDenormalProduct / |cross| off the plane keeps it 16 of those off zero. Measured
/// (Geometry.SpawnedRaysNeverMeetTheirSurfaceAgain, scales 1e-12 and 1e-11, triangles down to 1e-15 across): of
/// 557,021 rays, 1,861 met their own triangle again with no floor, 54 with 0.7 of the smallest denormal, 2 with 1,
/// none with 2 or more.
constexpr double kDenormalProduct = 16 * double(std::numeric_limits<float>::denorm_min());

/// |cross(p1 - p0, p2 - p0)| in double, exact to rounding for any float corners (no overflow or underflow).
double cross_length(Vec3 p0, Vec3 p1, Vec3 p2) {
  const double ax = double(p1.x) - p0.x, ay = double(p1.y) - p0.y, az = double(p1.z) - p0.z;
  const double bx = double(p2.x) - p0.x, by = double(p2.y) - p0.y, bz = double(p2.z) - p0.z;
  const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  return std::sqrt(cx * cx + cy * cy + cz * cz);
}

void embree_error(void*, RTCError code, const char* str) {
  std::fprintf(stderr, "lumis: embree error %d: %s\n", static_cast<int>(code), str ? str : "");
}

}  // namespace

constinit thread_local QueryLog* t_query_log = nullptr;

Geometry::Geometry() : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("cannot create the Embree device");
  rtcSetDeviceErrorFunction(impl_->device, embree_error, nullptr);
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_MEDIUM);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  impl_->light_scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->light_scene, static_cast<RTCSceneFlags>(RTC_SCENE_FLAG_ROBUST |
                                                                  RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
}

Geometry::~Geometry() {
  if (impl_->light_scene) rtcReleaseScene(impl_->light_scene);
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

uint32_t Geometry::add_mesh(TriangleMesh mesh) {
  auto& m = impl_->meshes.emplace_back(std::move(mesh));
  std::vector<Impl::TriangleRecord>& records = impl_->records.emplace_back(m.triangle_count());
  bool has_tiny = false;
  for (size_t i = 0; i < records.size(); ++i) {
    Impl::TriangleRecord& r = records[i];
    r.p0 = m.positions[m.indices[3 * i]], r.p1 = m.positions[m.indices[3 * i + 1]];
    r.p2 = m.positions[m.indices[3 * i + 2]];
    bool tiny = false;
    r.ng = face_normal(r.p0, r.p1, r.p2, tiny);
    has_tiny |= tiny;
  }
  // Embree reads vertex arrays 16 bytes at a time: one spare element keeps the last read in bounds.
  m.positions.reserve(m.positions.size() + 1);
  m.positions.emplace_back();
  m.positions.pop_back();
  RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(), 0, sizeof(Vec3),
                             m.positions.size());
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                             3 * sizeof(uint32_t), m.triangle_count());
  if (m.alpha) {
    rtcSetGeometryUserData(g, &m);
    rtcSetGeometryIntersectFilterFunction(g, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(g, alpha_filter);
  }
  rtcCommitGeometry(g);
  const uint32_t id = rtcAttachGeometry(impl_->scene, g);
  if (m.light >= 0) rtcAttachGeometryByID(impl_->light_scene, g, id);
  rtcReleaseGeometry(g);
  if (id >= impl_->slots.size()) impl_->slots.resize(id + 1);
  impl_->slots[id] = {&m, records.data(), nullptr, has_tiny, !m.normals.empty() || !m.uv0.empty()};
  impl_->triangles += m.triangle_count();
  for (const Vec3& p : m.positions) impl_->bounds.expand(p);
  return id;
}

uint32_t Geometry::add_sphere(Sphere sphere) {
  auto& s = impl_->spheres.emplace_back(sphere);
  RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
  v[0] = s.center.x;
  v[1] = s.center.y;
  v[2] = s.center.z;
  v[3] = s.radius;
  rtcCommitGeometry(g);
  const uint32_t id = rtcAttachGeometry(impl_->scene, g);
  if (s.light >= 0) rtcAttachGeometryByID(impl_->light_scene, g, id);
  rtcReleaseGeometry(g);
  if (id >= impl_->slots.size()) impl_->slots.resize(id + 1);
  impl_->slots[id] = {nullptr, nullptr, &impl_->spheres.back(), false, false};
  impl_->bounds.expand(s.center - Vec3(s.radius));
  impl_->bounds.expand(s.center + Vec3(s.radius));
  return id;
}

void Geometry::commit() {
  // About the size of a core's L2 cache: below it, prefetching the records costs more than it hides.
  impl_->prefetch = impl_->triangles * sizeof(Impl::TriangleRecord) > (size_t(1) << 20);
  rtcCommitScene(impl_->scene);
  rtcCommitScene(impl_->light_scene);
}

bool Geometry::is_mesh(uint32_t id) const { return impl_->slots[id].mesh != nullptr; }
const TriangleMesh& Geometry::mesh(uint32_t id) const { return *impl_->slots[id].mesh; }
const Sphere& Geometry::sphere(uint32_t id) const { return *impl_->slots[id].sphere; }
size_t Geometry::geometry_count() const { return impl_->slots.size(); }
size_t Geometry::triangle_count() const { return impl_->triangles; }
Bounds3 Geometry::bounds() const { return impl_->bounds; }
void* Geometry::embree_scene() const { return impl_->scene; }
bool Geometry::prefetches_hit_records() const { return impl_->prefetch; }

void Geometry::fill_hit(uint32_t geom_id, uint32_t prim_id, float b1, float b2, Hit& hit) const {
  hit.geom_id = geom_id;
  hit.prim_id = prim_id;
  const Impl::Slot& slot = impl_->slots[geom_id];
  if (!slot.mesh) {
    const Sphere& s = *slot.sphere;
    // b1, b2 unused: the caller set hit.p; reproject it onto the sphere to remove the error of o + t d.
    const Vec3 n = normalize(hit.p - s.center);
    hit.p = s.center + n * s.radius;
    hit.p_error = Vec3((max_component(abs(s.center)) + s.radius) * kErrorScale);
    hit.ng = hit.ns = n;
    hit.tangent = {};
    hit.uv[0] = hit.uv[1] = {};
    hit.color = {1, 1, 1, 1};
    hit.material = s.material;
    hit.light = s.light;
    return;
  }
  const TriangleMesh& m = *slot.mesh;
  const Impl::TriangleRecord& record = slot.records[prim_id];
  const Vec3 p0 = record.p0, p1 = record.p1, p2 = record.p2, ng = record.ng;
  float tiny_error = 0;
  if (slot.has_tiny) [[unlikely]] {
    // Tiny triangles (see face_normal): Embree's barycentrics come out wrong while t stays right (measured; most
    // likely its reciprocal of a triple product of about |c| |cos|, which clamps inputs below 1e-18), so they are
    // recomputed from the hit point o + t d.
    bool tiny = false;
    face_normal(p0, p1, p2, tiny);
    if (tiny) {
      const Vec2 b = triangle_barycentrics(hit.p, p0, p1, p2);
      b1 = b.x, b2 = b.y;
      const double c = cross_length(p0, p1, p2);
      if (c > 0) tiny_error = static_cast<float>(std::min(kDenormalProduct / c, double(FLT_MAX)));
    }
  }
  const float b0 = 1 - b1 - b2;
  hit.p = p0 * b0 + p1 * b1 + p2 * b2;
  // The same bound on every axis: Embree's intersection error grows with the coordinates involved, not just
  // with the hit point's own (an axis-aligned plane through the origin still needs an offset).
  hit.p_error = Vec3(max_component(max(abs(p0), max(abs(p1), abs(p2)))) * kErrorScale + tiny_error);
  hit.ng = ng;
  hit.ns = ng;  // from the register: read back from hit.ng, it waited on a failed store forward
  hit.tangent = {};
  hit.uv[0] = hit.uv[1] = {};
  hit.color = {1, 1, 1, 1};
  hit.material = m.material;
  hit.light = m.light;
  if (m.normals.empty() && m.tangents.empty() && m.uv0.empty() && m.uv1.empty() && m.colors.empty()) return;
  const uint32_t i0 = m.indices[3 * prim_id], i1 = m.indices[3 * prim_id + 1], i2 = m.indices[3 * prim_id + 2];
  if (!m.normals.empty()) {
    const Vec3 n = m.normals[i0] * b0 + m.normals[i1] * b1 + m.normals[i2] * b2;
    const float l = length(n);
    if (l > 0 && std::isfinite(l)) hit.ns = n / l;
  }
  if (!m.tangents.empty()) {
    const Vec4 t0 = m.tangents[i0], t1 = m.tangents[i1], t2 = m.tangents[i2];
    const Vec3 t = t0.xyz() * b0 + t1.xyz() * b1 + t2.xyz() * b2;
    hit.tangent = {t.x, t.y, t.z, t0.w < 0 ? -1.0f : 1.0f};
  }
  if (!m.uv0.empty()) hit.uv[0] = m.uv0[i0] * b0 + m.uv0[i1] * b1 + m.uv0[i2] * b2;
  if (!m.uv1.empty()) hit.uv[1] = m.uv1[i0] * b0 + m.uv1[i1] * b1 + m.uv1[i2] * b2;
  if (!m.colors.empty()) {
    const Vec4 a = m.colors[i0], b = m.colors[i1], d = m.colors[i2];
    hit.color = {a.x * b0 + b.x * b1 + d.x * b2, a.y * b0 + b.y * b1 + d.y * b2, a.z * b0 + b.z * b1 + d.z * b2,
                 a.w * b0 + b.w * b1 + d.w * b2};
  }
}

}  // namespace lumis
