// Displaced triangle meshes as pbrt-v4 builds them for `plymesh` with `displacement`
// (TriQuadMesh::Displace): refine until every edge is shorter than a length, move each vertex along
// its normal by a displacement, then recompute the vertex normals.
#pragma once

#include <functional>

#include "scene/shape.h"

namespace phos::scene {

// The length of the edge between two object-space vertices as the refinement measures it (pbrt-v4:
// in render space, so through the shape's transform).
using EdgeLength = std::function<float(Vec3 a, Vec3 b)>;
// The distance to move a vertex along its unit normal n, at object-space point p and uv.
using Displacement = std::function<float(Vec3 p, Vec3 n, Vec2 uv)>;

// Splits triangles at the midpoint of their longest edge, recursively, until every edge is shorter
// than `max_edge` (pbrt-v4's TriQuadMesh::Refine). A split edge gets one new vertex shared by the
// triangles on both sides, with the mean position and uv and the normalised mean normal, so the
// refined mesh stays watertight. Throws InputError (before refining, from an estimate, or while
// refining) if the result would exceed `max_triangles` triangles, or an edge length is not finite.
void refine_mesh(TriangleMesh& mesh, float max_edge, const EdgeLength& edge_length, size_t max_triangles);

// Area-weighted vertex normals: the sum of the (unnormalised) winding normals of the triangles at
// each vertex, normalised (pbrt-v4's ComputeNormals).
std::vector<Vec3> vertex_normals(const TriangleMesh& mesh);

// refine_mesh, then each vertex p += n * displace(p, n, uv) with the vertex normals (the mesh's
// own, or vertex_normals when it has none), then the normals recomputed with vertex_normals.
// A mesh without uvs is displaced with uv (0, 0) at every vertex.
void displace_mesh(TriangleMesh& mesh, float max_edge, const EdgeLength& edge_length,
                   const Displacement& displace, size_t max_triangles);

}  // namespace phos::scene
