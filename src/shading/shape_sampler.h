// Samples points on the emitting surface of a scene::Shape in world space, for area lights:
// uniformly by area (photon emission, and direct light in general) or, for a sphere seen from
// outside, uniformly over the solid angle of its visible cap (direct light). A partial sphere (pbrt's
// zmin, zmax, phimax) is sampled uniformly by area over its actual surface.
//
// Emission side: the side the accel layer's geometric normal (SurfaceHit::ng) points to, so that
// Le(hit.ng, wo) and the light's own samples agree:
//  - analytic shapes (sphere, disk, cylinder, cone): to_world.normal(object outward normal), flipped
//    if reverse_orientation XOR to_world.swaps_handedness();
//  - meshes: the cross product of the world-space edges (counter-clockwise front), flipped if
//    reverse_orientation XOR swaps_handedness (pbrt-v4); where the mesh has shading normals, the
//    geometric normal is turned to the side of the interpolated shading normal (which goes through
//    to_world.normal and flips with reverse_orientation only);
//  - boxes (12 triangles wound counter-clockwise from outside): the mesh rule, which works out as
//    to_world.normal(outward normal) flipped if reverse_orientation.
//
// Exactness: meshes (vertices transformed to world space), disks/annuli, box faces and the caps of
// cylinders and cones are sampled exactly uniformly under any affine transform (an affine map has a
// constant area Jacobian on a plane). Spheres, cylinder sides and cone sides are exact under
// similarity transforms (rotation, uniform scale, translation, mirroring). Under a non-uniform scale
// or shear those curved parts fall back to a fine tessellation (sampled uniformly by triangle area,
// with pdf 1 / tessellated area) whose samples are projected back onto the true surface, so the
// density is right to about 0.1%. A mesh's exact bilinear patches are sampled uniformly by area under
// any transform (rejection against their largest area element; their areas by quadrature).
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec.h"
#include "scene/shape.h"
#include "shading/distribution1d.h"

namespace phos::shading {

struct ShapeSample {
    Vec3 p;         // world-space point on the surface
    Vec3 n;         // unit normal on the emitting side (see the rule above)
    float pdf = 0;  // area density (sample_area) or solid-angle density (sample)
    // A point of a mesh: its triangle and barycentrics (b1, b2) there (-1: not a mesh point), so a
    // light can find the surface's uv.
    int triangle = -1;
    Vec2 barycentric;
};

class ShapeSampler {
public:
    // Throws InputError for a shape that cannot be sampled (non-finite parameters).
    explicit ShapeSampler(const scene::Shape& shape);

    // Total world-space surface area (of the tessellation for fallback parts).
    float area() const { return area_; }
    // Uniform by area: pdf = 1 / area().
    ShapeSample sample_area(Vec2 u) const;
    // A point seen from `ref`, pdf in solid angle at `ref` (0 if the point is seen edge-on).
    ShapeSample sample(Vec3 ref, Vec2 u) const;
    // Solid-angle density with which sample(ref) returns point p (normal n) in direction wi.
    float pdf(Vec3 ref, Vec3 wi, Vec3 p, Vec3 n) const;
    // True if some part had to be tessellated (non-similarity transform of a curved surface).
    bool tessellated() const { return projection_ != Projection::None; }

private:
    enum class PatchKind : uint8_t {
        Triangle,
        Parallelogram,
        Annulus,
        Sphere,
        PartialSphere,
        Bilinear,
        CylinderSide,
        ConeSide
    };
    // One uniformly-sampleable piece of surface, in world space.
    //  Triangle / Parallelogram: corner o, edges e1, e2, normal n.
    //  Annulus: centre o, semi-axis vectors e1, e2 (images of two orthogonal radii), a = inner/outer.
    //  Sphere: centre o, a = radius, b = +1 (outward) or -1.
    //  Bilinear: p(u, v) = o + e1 u + e2 v + n u v (n is the twist, not a normal), a = the largest
    //            area element |dp/du x dp/dv| (at a corner), b = the sign of the front (+1: dp/du x
    //            dp/dv), triangle = the patch's index.
    //  PartialSphere: uniform in z and phi over the object-space part (the obj_ members), mapped to
    //                 world (area-preserving up to the similarity's scale, Archimedes).
    //  CylinderSide: axis-segment centre o, n = unit axis, e1, e2 = orthogonal radius vectors,
    //                a = height, b = sign.  ConeSide: o = apex, n = unit axis towards the apex, rest
    //                as the cylinder.
    struct Patch {
        PatchKind kind = PatchKind::Triangle;
        bool project = false;   // a tessellation triangle: project samples onto the true surface
        uint32_t triangle = 0;  // mesh triangle index (for shading normals)
        Vec3 o, e1, e2, n;
        float a = 0, b = 1;
    };
    enum class Projection : uint8_t { None, Sphere, CylinderSide, ConeSide };

    void add_patch(const Patch& patch, float area);
    void add_disk(const scene::Shape& s, Vec3 center, Vec3 normal, float radius, float inner);
    void add_mesh(const scene::Shape& s);
    void add_box(const scene::Shape& s);
    void add_curved(const scene::Shape& s, Projection kind);
    void tessellate(const scene::Shape& s, Projection kind);
    ShapeSample sample_patch(const Patch& patch, Vec2 u) const;
    // A point (u, v) of a Bilinear patch with density proportional to its area element.
    static Vec2 sample_bilinear(const Patch& patch, Vec2 u);
    // Moves a point of the tessellation onto the true curved surface (object space) and returns it
    // with its emitting-side world normal.
    void project(Vec3& p, Vec3& n) const;
    // World normal from an object-space outward normal, with the orientation rule applied.
    Vec3 world_normal(Vec3 n_object) const;

    // Meshes with shading normals: world-space vertex normals (flipped if reverse_orientation) and
    // the index buffer, to orient each sample's normal the way the accel layer does.
    std::vector<Vec3> shading_normals_;
    std::vector<uint32_t> indices_;
    std::vector<uint32_t> patch_indices_;  // the mesh's bilinear patches, with shading normals
    std::vector<Patch> patches_;
    std::vector<float> areas_;
    Distribution1D by_area_;
    float area_ = 0;
    float sign_ = 1;  // -1 when reverse_orientation XOR swaps_handedness
    Transform to_world_;
    // The curved part being tessellated (object-space parameters of the shape).
    Projection projection_ = Projection::None;
    Vec3 obj_center_{0.0f}, obj_axis_{0, 1, 0};
    float obj_radius_ = 1, obj_height_ = 1;
    // A partial sphere (scene::Shape::partial): its clamped z range and azimuth.
    bool obj_partial_ = false;
    float obj_z_min_ = -1, obj_z_max_ = 1, obj_phi_max_ = 2 * kPi;
    // Sphere under a similarity transform: solid-angle sampling of the visible cap from outside.
    bool sphere_cone_ = false;
    Vec3 sphere_center_{0.0f};
    float sphere_radius_ = 0;
};

}  // namespace phos::shading
