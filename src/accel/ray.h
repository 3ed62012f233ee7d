// Rays, surface hits and robust ray spawning shared by every integrator and the photon tracer.
#pragma once

#include <cmath>

#include "core/frame.h"
#include "core/vec.h"
#include "scene/medium.h"

namespace phos::accel {

struct Ray {
    Vec3 origin;
    Vec3 dir;  // need not be normalised; t is measured in units of |dir|
    float tmin = 0.0f;
    float tmax = kInf;
};

// Everything shading needs to know about the closest hit.
struct SurfaceHit {
    float t = kInf;
    Vec3 p;              // world-space hit point
    Vec3 ng;             // unit geometric normal, pointing to the shape's outside (after reverse_orientation)
    Vec3 ns;             // unit shading normal (interpolated where the mesh has normals), same side as ng
    Vec2 uv;             // surface parameterisation (mesh uv, or the primitive's own)
    Vec3 dpdu;           // tangent along u (unit; arbitrary but consistent if the shape has none)
    int shape = -1;      // index into Scene::shapes, or of the instanced object's shape
    int instance = -1;   // index into Scene::instances, or -1 for top-level shapes
    int primitive = -1;  // triangle index within a mesh, 0 for analytic shapes
    int material = -1;
    int area_light = -1;  // index into Scene::lights when the surface emits
    scene::MediumInterface media;
    float error = 0.0f;  // conservative bound on the position error of p, for spawning
    // shading_frame(ng, ns, dpdu) where the accelerator keeps it for the primitive (flat
    // triangles: the same for every hit on them), else null. Whoever changes ng, ns or dpdu of a
    // hit must reset it.
    const ShadingFrame* shading = nullptr;
};

// Offsets `p` off the surface along the geometric normal towards the side `dir` points to, far
// enough that a ray from the result does not re-hit the same surface (no acne) and close enough not
// to skip touching geometry (no leaks). (Inline with spawn_ray: every bounce of every path.)
inline Vec3 offset_origin(const SurfaceHit& hit, Vec3 dir) {
    // pbrt: distance = dot(|n|, error vector); with an isotropic bound that is error * |n|_1.
    const float d = hit.error * (std::fabs(hit.ng.x) + std::fabs(hit.ng.y) + std::fabs(hit.ng.z));
    Vec3 offset = hit.ng * d;
    if (dot(dir, hit.ng) < 0) offset = -offset;
    Vec3 po = hit.p + offset;
    // Round away from p so that the float addition cannot land back on the surface.
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0)
            po[i] = next_float(po[i], kInf);
        else if (offset[i] < 0)
            po[i] = next_float(po[i], -kInf);
    }
    return po;
}
// A ray leaving the surface in direction `dir`.
inline Ray spawn_ray(const SurfaceHit& hit, Vec3 dir) {
    Ray r;
    r.origin = offset_origin(hit, dir);
    r.dir = dir;
    return r;
}
// A shadow ray from the surface towards point `target` (stops just short of it).
Ray spawn_ray_to(const SurfaceHit& hit, Vec3 target);
// A shadow ray between two surface points, offset at both ends.
Ray spawn_ray_between(const SurfaceHit& from, const SurfaceHit& to);
// A shadow ray from a point off any surface (in a medium) towards point `target`.
Ray ray_to(Vec3 from, Vec3 target);

}  // namespace phos::accel
