// Shapes as plain data: triangle meshes and analytic primitives, each with a material, an optional
// area light, the media on its two sides and an object-to-world transform.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/transform.h"
#include "core/vec.h"
#include "scene/curves.h"
#include "scene/medium.h"

namespace phos::scene {

struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;      // empty, or one per position (shading normals)
    std::vector<Vec2> uvs;          // empty, or one per position
    std::vector<uint32_t> indices;  // 3 per triangle, counter-clockwise seen from the front
    // Exact bilinear patches (pbrt's non-planar `bilinearmesh` patches): 4 indices per patch in
    // pbrt's order p00 p10 p01 p11 (scene/bilinear_patch.h). The front is the side of
    // dp/du x dp/dv, or of -(dp/du x dp/dv) when `patches_flipped`; with `normals` it is the side
    // of the interpolated normal. Without `uvs`, a patch's uv is its (u, v).
    std::vector<uint32_t> patches;
    bool patches_flipped = false;
    size_t triangle_count() const { return indices.size() / 3; }
    size_t patch_count() const { return patches.size() / 4; }
};

struct Shape {
    enum class Kind {
        Mesh,      // `mesh`
        Sphere,    // centre, radius
        Box,       // axis-aligned box [box_min, box_max] in object space
        Disk,      // centre, normal, radius (inner_radius for an annulus)
        Cylinder,  // centre of the axis segment, unit `axis`, radius, height; caps if `capped`
        Cone,      // centre of the axis segment, unit `axis` towards the apex, base radius, height
        Curves,    // `curves` (pbrt `curve`), in the space of to_world
    };
    Kind kind = Kind::Mesh;
    TriangleMesh mesh;
    CurveSet curves;
    Vec3 center{0.0f};
    float radius = 1.0f;
    float inner_radius = 0.0f;
    Vec3 normal{0, 1, 0};
    Vec3 axis{0, 1, 0};
    float height = 1.0f;
    bool capped = true;
    Vec3 box_min{0.0f}, box_max{1.0f};
    // Sphere only, when `partial` (pbrt's zmin, zmax, phimax): the open surface with
    // z_min <= z <= z_max along `axis` (object units from the centre, within [-radius, radius]) and
    // azimuth 0 <= phi <= phi_max radians, phi measured from Frame(axis).s (core/frame.h).
    bool partial = false;
    float z_min = -1.0f, z_max = 1.0f, phi_max = 2 * kPi;
    // Sphere only: (u, v) as pbrt-v4 gives a full sphere, v = 1 - theta / pi from the +axis pole
    // (0 at the -axis pole), instead of theta / pi; the pbrt loader sets it, with axis +z.
    bool pbrt_uv = false;

    int material = 0;
    int area_light = -1;  // index into Scene::lights, or -1
    // pbrt's "alpha" cut-out: a hit is kept with probability alpha (a constant, or the float texture
    // `alpha_texture` at the hit's uv when >= 0), so 0 removes the surface for every ray, 1 keeps it.
    float alpha = 1;
    int alpha_texture = -1;
    bool reverse_orientation = false;  // flip the outward normal (pbrt ReverseOrientation)
    MediumInterface media;
    Transform to_world;  // object space to world space
    std::string origin;  // "file:line" where it was defined, for messages
};

// A named group of shapes placed several times (pbrt ObjectBegin/ObjectInstance).
struct Object {
    std::string name;
    std::vector<Shape> shapes;
};

struct Instance {
    int object = 0;
    Transform to_world;
};

}  // namespace phos::scene
