// Loop subdivision of a triangle mesh (Loop 1987, "Smooth Subdivision Surfaces Based on Triangles"),
// as pbrt-v4's LoopSubdivide does it for the `loopsubdiv` shape: refined `levels` times, then every
// vertex moved to its limit position and given the limit surface's normal.
#pragma once

#include <vector>

#include "core/vec.h"
#include "scene/shape.h"

namespace phos::scene {

// Subdivides the mesh of `positions` and `indices` (3 per triangle, counter-clockwise around the
// front) `levels` times. Each level splits every triangle in four: even (old) vertices move by
// Warren's weights, beta = 3/16 for valence 3 and 3 / (8 n) otherwise, and 3/4, 1/8, 1/8 with their
// two boundary neighbours on the boundary; odd (edge) vertices are 3/8, 3/8, 1/8, 1/8 of the edge's
// ends and the two opposite vertices inside, the edge's midpoint on the boundary. Then each vertex
// goes to its limit position (gamma = 1 / (n + 3 / (8 beta)) inside; 3/5, 1/5, 1/5 on the boundary)
// and takes the normal of the limit tangents S x T (Halstead et al. 1993 masks, the one-ring in
// pbrt's order), which points against the triangles' winding: pbrt-v4 makes a triangle face its
// shading normal, so a mesh wound counter-clockwise from outside faces inward in pbrt-v4, and so it
// does here. Vertices no triangle uses are dropped. The result has 4^levels x the triangles,
// per-vertex normals and no uvs.
// Throws InputError (no location; the caller adds it) for an index out of range, a degenerate
// triangle (a repeated vertex), an edge shared by more than two triangles or by two that run it the
// same way (inconsistent orientation), or a vertex whose triangles do not form one fan.
TriangleMesh loop_subdivide(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices,
                            int levels);

}  // namespace phos::scene
