#include "core/tangents.h"

#include "core/frame.h"

namespace lumis {

void generate_tangents(TriangleMesh& mesh, int uv_set) {
  const std::vector<Vec2>& uv = uv_set == 1 ? mesh.uv1 : mesh.uv0;
  const size_t n = mesh.positions.size();
  if (uv.size() != n) return;
  std::vector<Vec3> dpdu(n), dpdv(n), normal(n);
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t i[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    const Vec3 e1 = mesh.positions[i[1]] - mesh.positions[i[0]], e2 = mesh.positions[i[2]] - mesh.positions[i[0]];
    const Vec2 d1 = uv[i[1]] - uv[i[0]], d2 = uv[i[2]] - uv[i[0]];
    const Vec3 face_normal = cross(e1, e2);
    for (uint32_t k : i) normal[k] += face_normal;
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 1e-20f)) continue;
    const Vec3 su = (e1 * d2.y - e2 * d1.y) / det, sv = (e2 * d1.x - e1 * d2.x) / det;
    if (!is_finite(su) || !is_finite(sv)) continue;
    for (uint32_t k : i) {
      dpdu[k] += su;
      dpdv[k] += sv;
    }
  }
  mesh.tangents.resize(n);
  for (size_t k = 0; k < n; ++k) {
    Vec3 nk = mesh.normals.size() == n ? mesh.normals[k] : normal[k];
    const float nl = length(nk);
    nk = nl > 0 ? nk / nl : Vec3(0, 0, 1);
    Vec3 t = dpdu[k] - nk * dot(nk, dpdu[k]);
    const float tl = length(t);
    if (!(tl > 1e-20f) || !std::isfinite(tl)) {
      const Vec3 s = Frame::from_normal(nk).s;
      mesh.tangents[k] = {s.x, s.y, s.z, 1};
      continue;
    }
    t = t / tl;
    // glTF v grows downward in the image, the normal map's +Y points up: the bitangent follows -dP/dv.
    const float w = dot(cross(nk, t), -dpdv[k]) < 0 ? -1.0f : 1.0f;
    mesh.tangents[k] = {t.x, t.y, t.z, w};
  }
}

}  // namespace lumis
