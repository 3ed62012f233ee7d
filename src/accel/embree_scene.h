// The Embree 3 wrapper: builds a BVH from a scene::Scene (triangle meshes, exact analytic spheres,
// disks, cylinders, cones, boxes, instances) and answers closest-hit and occlusion queries.
#pragma once

#include <cstdint>
#include <memory>

#include "accel/ray.h"
#include "core/bounds.h"
#include "scene/scene.h"

namespace phos::accel {

namespace detail {
struct CanonicalHit;  // accel/analytic.h
}

// Conventions of the hits (pbrt's where pbrt has one):
// - Triangles (meshes, and boxes as 12 triangles): ng is the counter-clockwise winding normal of
//   the world-space triangle, flipped if reverse_orientation XOR to_world swaps handedness (so a
//   box stays outward under mirroring). With per-vertex normals, ns is their interpolation (normal
//   transform, flipped by reverse_orientation as in pbrt-v4) and ng is turned to ns's side.
//   uv: mesh uvs, else the barycentrics (b1, b2).
// - Exact bilinear patches of a mesh (TriangleMesh::patches, pbrt's non-planar bilinearmesh patches;
//   accel/bilinear_patch.h): ng = dp/du x dp/dv, flipped if patches_flipped XOR reverse_orientation
//   XOR to_world swaps handedness; with per-vertex normals ns is their bilinear interpolation and ng
//   is turned to its side. uv: the corners' uvs interpolated bilinearly, else the patch's (u, v).
//   `primitive` is the patch's index in TriangleMesh::patches / 4.
// - Analytic shapes: outward normal, flipped if reverse_orientation XOR to_world swaps handedness.
//   Sphere: pole along Shape::axis (+y by default), u = phi / 2pi around it (phi = atan2(y, x) for
//   a +z axis), v = theta / pi from the +axis pole. Disk: u = phi / 2pi, v = (r_out - r) /
//   (r_out - r_in). Cylinder/cone side: v = 0 at the base (centre - axis h/2) to 1 at the top;
//   caps: v = r / radius. Cone apex at centre + axis h/2; Shape::capped closes cylinder and cone.
// - Curves (pbrt `curve`, accel/curves.h): u along each cubic segment, v across it (0.5 on the
//   centre curve); cylinders' outward normal, ribbons' normal on the side of their normal spline,
//   flat curves' normal facing the ray; each flipped if reverse_orientation XOR to_world swaps
//   handedness. `primitive` is the segment.
// - Instances: the instance transform carries p, normals and dpdu to world without any flip;
//   `shape` is the index within the object and `instance` the index in Scene::instances.
// - Degenerate shapes (zero radius, ...) are skipped with a warning; malformed meshes (index out of
//   range, non-finite vertex) and instances of missing objects throw InputError.
class EmbreeScene {
public:
    // Keeps a reference to `scene`, which must outlive this object. `device_config` is Embree's
    // device configuration (rtcNewDevice; null: its defaults, the best kernels for this CPU); tests
    // pass e.g. "isa=avx2" to run the kernels other CPUs get.
    explicit EmbreeScene(const scene::Scene& scene, const char* device_config = nullptr);
    // A temporary scene would be gone before the first ray: refused at compile time.
    explicit EmbreeScene(scene::Scene&& scene, const char* device_config = nullptr) = delete;
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Closest hit in (ray.tmin, ray.tmax); fills `hit` and returns true if there is one.
    bool intersect(const Ray& ray, SurfaceHit& hit) const;
    // The same for up to 16 rays at once through Embree's packet interface (rtcIntersect16):
    // found[k] and hits[k] for rays[k], k < n. Each hit is the one intersect() gives (Embree's
    // packet and single-ray kernels compute the same hits; tests/accel checks it); packets save
    // traversal work when many independent rays are in flight (the photon tracer's wavefront).
    void intersect16(const Ray* rays, int n, SurfaceHit* hits, bool* found) const;
    // True if anything lies in (ray.tmin, ray.tmax).
    bool occluded(const Ray& ray) const;
    // World-space bounds of all geometry.
    Bounds bounds() const;
    // Bytes the accelerator keeps beside Embree's BVH for a scene of `triangles` mesh triangles:
    // each triangle's constants (normal, tangent, error bounds), for the first 2^20 of them, so
    // that a hit only computes what depends on where it landed.
    static double triangle_constants_bytes(double triangles);
    const scene::Scene& scene() const { return scene_; }

private:
    struct Impl;
    struct RawHit {  // what Embree reports for one ray
        unsigned geom, prim, inst;
        float u, v, t;
        Vec3 ng;         // Embree's unnormalised geometric normal (curves read it)
        const Ray* ray;  // the ray traced
    };
    // The SurfaceHit of an Embree hit (exact hit point, normals, tangent, error bound).
    void finish_hit(const RawHit& raw, const detail::CanonicalHit& canonical, SurfaceHit& hit) const;
    const scene::Scene& scene_;
    bool mixes_ = false;  // the scene has mix materials: hits resolve them (scene/material_mix.h)
    std::unique_ptr<Impl> impl_;
};

}  // namespace phos::accel
