// Curves as plain data: cubic Bezier or uniform B-spline segments swept with a varying radius
// (pbrt's `curve` shape), as flat ray-facing bands, round tubes or ribbons oriented by normals.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace phos::scene {

struct CurveSet {
    enum class Type {
        Flat,      // a band of width 2r that always faces the ray
        Cylinder,  // a tube of radius r around the centre curve
        Ribbon,    // a band of width 2r whose normal follows the `normals` spline
    };
    enum class Basis {
        Bezier,   // each segment: 4 consecutive control points, interpolating the ends
        BSpline,  // each segment: 4 consecutive control points of a uniform cubic B-spline
    };
    Type type = Type::Flat;
    Basis basis = Basis::Bezier;
    std::vector<Vec3> points;        // control points
    std::vector<float> radii;        // one per control point: the radius spline (same basis)
    std::vector<Vec3> normals;       // ribbons: one per control point, the normal spline
    std::vector<uint32_t> segments;  // each segment's first control point
    size_t segment_count() const { return segments.size(); }
};

}  // namespace phos::scene
