// Per-vertex tangent generation for normal mapping when a mesh has no TANGENT attribute.
#pragma once

#include "core/geometry.h"

namespace lumis {

/// Fill mesh.tangents from the uv set's derivatives (Lengyel's per-triangle dP/du, dP/dv, summed per vertex and
/// made orthogonal to the vertex normal). w is the handedness under glTF's convention: bitangent = w cross(n, t)
/// points toward decreasing v (the normal map's green axis, "up" in the image). World space, not normalised per
/// triangle area (larger triangles weigh more). Vertices without a usable uv gradient get an arbitrary tangent.
void generate_tangents(TriangleMesh& mesh, int uv_set);

}  // namespace lumis
