// The partial derivatives dp/du and dp/dv of the surface at a hit, for the uv the hit reports
// (SurfaceHit::uv): what bump and normal mapping differentiate against (pbrt-v4's shading dpdu and
// dpdv, PBR 4th ed. sec. 6.2 and 10.5.2). The accelerator reports only a unit tangent; these are
// computed on demand from the scene's shapes, only for materials that need them.
#pragma once

#include "accel/ray.h"
#include "core/vec.h"
#include "scene/scene.h"

namespace phos::accel {

// World-space derivatives; both perpendicular to hit.ns where the shape has shading normals.
//  - Triangles: pbrt-v4's from the vertices and uvs (the barycentric (b1, b2) without uvs:
//    dpdu = p1 - p0, dpdv = p2 - p0); with per-vertex normals pbrt-v4's shading pair: dpdu made
//    perpendicular to ns (ss = (ns x dpdu) x ns) and dpdv = ns x ss. Degenerate uvs: a unit pair
//    around the normal.
//  - Bilinear patches: dp/du, dp/dv of the patch at the hit, by the chain rule through the
//    corners' uvs when the mesh has uvs (its (u, v) found from the point by Newton's method).
//  - Spheres (full and partial), disks, cylinders, cones and their caps: the closed forms of
//    their parameterisations (accel/embree_scene.h), through shape and instance transforms.
//  - Curves: dpdu the centre curve's dC/du; dpdv across it, dpdu x ns scaled to the width (v's
//    direction for normals facing the ray: flat curves, tubes, ribbons seen from their front).
//  - Boxes and anything degenerate: hit.dpdu and ns x hit.dpdu (unit).
struct SurfaceDerivatives {
    Vec3 dpdu, dpdv;
};
SurfaceDerivatives surface_derivatives(const scene::Scene& scene, const SurfaceHit& hit);

}  // namespace phos::accel
