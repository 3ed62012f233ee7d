// Curves (scene::CurveSet, pbrt's `curve` shape) as Embree 3 curve geometry: flat curves as
// RTC_GEOMETRY_TYPE_FLAT_*, cylinders as ROUND_* and ribbons as NORMAL_ORIENTED_*, each with the
// Bezier or B-spline basis; and the surface at a hit reported by Embree.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <string>

#include "accel/analytic.h"
#include "scene/shape.h"

namespace phos::accel::detail {

// The four cubic basis functions w and their derivatives dw at u in [0, 1]: Bernstein polynomials
// of degree 3 (Bezier) or the uniform cubic B-spline's.
void curve_basis(scene::CurveSet::Basis b, double u, double w[4], double dw[4]);

// One curve shape as Embree holds it, in the geometry's space (world, or the object's space).
struct CurveGeom {
    const float* vertices = nullptr;     // Embree's vertex buffer: x y z r per control point
    const float* normals = nullptr;      // ribbons: Embree's normal buffer, x y z per control point
    const uint32_t* segments = nullptr;  // Embree's index buffer: each segment's first control point
    scene::CurveSet::Type type = scene::CurveSet::Type::Flat;
    scene::CurveSet::Basis basis = scene::CurveSet::Basis::Bezier;
    bool flip = false;  // reverse_orientation XOR the shape transform swaps handedness (pbrt)
    const scene::Shape* source = nullptr;
    int shape = -1;  // index of the shape (in Scene::shapes or in its Object)
};

// A new, uncommitted Embree geometry holding `shape`'s curves moved by shape.to_world (control
// points by the transform, radii by its linear scale |det|^(1/3), ribbon normals by its normal
// transform), and `out` pointing into its buffers. Returns null with `why` for an empty or
// degenerate curve set; throws InputError for a malformed one (a segment or a count out of range,
// a non-finite value).
RTCGeometry new_curve_geometry(RTCDevice device, const scene::Shape& shape, int index, CurveGeom& out,
                               std::string& why);

// Surface geometry at a hit of segment `prim` at curve parameter u, for the ray o + t d in the
// geometry's space, with Embree's unnormalised geometric normal ng:
// - p = o + t d; uv = (u, v) as pbrt-v4: u along the segment, v across it from 0 to 1 (0.5 on the
//   centre curve, v > 0.5 on the side of d x dC/du);
// - n: cylinders the outward normal, ribbons Embree's normal turned to the side of the normal
//   spline, flat curves the normal facing the ray (-d without its component along the curve);
//   each flipped by CurveGeom::flip;
// - dpdu: the unit tangent dC/du;
// - error: a bound on how far p may lie from the surface Embree intersected (flat curves: the
//   width, as pbrt-v4, since a flat curve turns to face every ray).
struct CurveSurface {
    D3 p, n, dpdu;
    Vec2 uv;
    double error = 0;
};
CurveSurface curve_surface(const CurveGeom& c, unsigned prim, float u, D3 ng, D3 o, D3 d, double t);

}  // namespace phos::accel::detail
