// pbrt `curve` parameters to a scene::CurveSet, following pbrt-v4's CreateCurve (shapes.cpp):
// the same counts, defaults and per-segment conversions (degree elevation, B-spline to Bezier,
// widths interpolated linearly over the segments, ribbon normals slerped between segment ends).
#include "io/pbrt/curves.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace phos::io::pbrt {
namespace {

Vec3 lerp(float t, Vec3 a, Vec3 b) { return a * (1 - t) + b * t; }

// A quadratic Bezier segment as the cubic with the same curve (degree elevation, Farin 5.1).
std::array<Vec3, 4> elevate(Vec3 p0, Vec3 p1, Vec3 p2) {
    return {p0, lerp(2.0f / 3.0f, p0, p1), lerp(1.0f / 3.0f, p1, p2), p2};
}

// Spherical linear interpolation of unit normals, as pbrt-v4's ribbons interpolate theirs.
Vec3 slerp(float t, Vec3 a, Vec3 b) {
    const float angle = std::acos(std::clamp(dot(a, b), -1.0f, 1.0f));
    if (angle < 1e-6f) return a;
    const float s = std::sin(angle);
    return a * (std::sin((1 - t) * angle) / s) + b * (std::sin(t * angle) / s);
}

// The cubic Bezier control points whose curve passes through q0..q3 at u = 0, 1/3, 2/3, 1.
std::array<Vec3, 4> bezier_through(Vec3 q0, Vec3 q1, Vec3 q2, Vec3 q3) {
    return {q0, (q0 * -5.0f + q1 * 18.0f - q2 * 9.0f + q3 * 2.0f) / 6.0f,
            (q0 * 2.0f - q1 * 9.0f + q2 * 18.0f - q3 * 5.0f) / 6.0f, q3};
}

}  // namespace

scene::CurveSet read_curves(const ParamList& params, const Loc& loc, const std::string& d,
                            const std::function<void(const Loc&, const std::string&)>& warn) {
    using Type = scene::CurveSet::Type;
    const Param* pp = params.find("P");
    if (!pp) loc.fail(d + ": missing \"point3 P\"");
    const std::vector<Vec3> cp = params.get_point3s("P");
    for (const Vec3& p : cp)
        if (!is_finite(p)) pp->loc.fail(d + ": non-finite control point");

    const std::string basis = params.get_string("basis", "bezier");
    if (basis != "bezier" && basis != "bspline")
        params.find("basis")->loc.fail(d + ": unknown basis \"" + basis + "\" (\"bezier\" or \"bspline\")");
    const int degree = params.get_int("degree", 3);
    if (degree != 2 && degree != 3)
        params.find("degree")->loc.fail(d + ": degree " + std::to_string(degree) + " (2 or 3 are supported)");
    const std::string type_name = params.get_string("type", "flat");
    Type type = Type::Flat;
    if (type_name == "ribbon")
        type = Type::Ribbon;
    else if (type_name == "cylinder")
        type = Type::Cylinder;
    else if (type_name != "flat")
        params.find("type")->loc.fail(d + ": unknown curve type \"" + type_name +
                                      "\" (\"flat\", \"ribbon\" or \"cylinder\")");

    const size_t n = cp.size(), deg = size_t(degree);
    size_t segments = 0;
    if (basis == "bezier") {
        if (n < deg + 1 || (n - 1) % deg != 0)
            pp->loc.fail(d + ": " + std::to_string(n) + " control points for a degree " +
                         std::to_string(deg) + " Bezier curve (" + std::to_string(deg + 1) + " + k * " +
                         std::to_string(deg) + " are required)");
        segments = (n - 1) / deg;
    } else {
        if (n < deg + 1)
            pp->loc.fail(d + ": " + std::to_string(n) + " control points for a degree " +
                         std::to_string(deg) + " B-spline (at least " + std::to_string(deg + 1) +
                         " are required)");
        segments = n - deg;
    }

    std::vector<Vec3> normals = params.get_point3s("N");
    if (!normals.empty() && type != Type::Ribbon) {
        warn(params.find("N")->loc, d + ": normals \"N\" are only used by \"ribbon\" curves (ignored)");
        normals.clear();
    } else if (type == Type::Ribbon) {
        if (normals.empty()) loc.fail(d + ": ribbon curves need normals \"N\" at the segment ends");
        if (normals.size() != segments + 1)
            params.find("N")->loc.fail(d + ": " + std::to_string(normals.size()) + " normals for " +
                                       std::to_string(segments) + " segments (a ribbon needs " +
                                       std::to_string(segments + 1) + ", one per segment end)");
        for (Vec3& nv : normals) {
            const float l = length(nv);
            if (!(l > 0) || !std::isfinite(l)) params.find("N")->loc.fail(d + ": zero or non-finite normal");
            nv = nv / l;
        }
    }

    const float width = params.get_float("width", 1.0f);
    const float width0 = params.get_float("width0", width), width1 = params.get_float("width1", width);
    for (const auto& [w, name] : {std::pair{width0, "width0"}, std::pair{width1, "width1"}})
        if (!(w >= 0) || !std::isfinite(w)) {
            const Param* q = params.find(name);
            if (!q) q = params.find("width");
            (q ? q->loc : loc).fail(d + ": the width must be finite and >= 0");
        }
    params.get_int("splitdepth", 3);  // pbrt's own subdivision of each segment; nothing to do here

    scene::CurveSet c;
    c.type = type;
    const auto width_at = [&](double t) { return float((1 - t) * width0 + t * width1); };
    if (basis == "bspline" && degree == 3 && type != Type::Ribbon) {
        // Embree's uniform cubic B-spline is pbrt's: the control points are used as they are.
        // Segment s spans parameter s + 1 + u in control-point units, and a radius spline of
        // values linear in the index is linear in the parameter: r_k = width at (k - 1) / segments.
        c.basis = scene::CurveSet::Basis::BSpline;
        c.points = cp;
        for (size_t k = 0; k < n; ++k) c.radii.push_back(0.5f * width_at((double(k) - 1) / double(segments)));
        for (size_t s = 0; s < segments; ++s) c.segments.push_back(uint32_t(s));
        return c;
    }
    c.basis = scene::CurveSet::Basis::Bezier;
    for (size_t s = 0; s < segments; ++s) {
        std::array<Vec3, 4> b;
        if (basis == "bezier") {
            b = degree == 2 ? elevate(cp[2 * s], cp[2 * s + 1], cp[2 * s + 2])
                            : std::array<Vec3, 4>{cp[3 * s], cp[3 * s + 1], cp[3 * s + 2], cp[3 * s + 3]};
        } else if (degree == 2) {
            // A uniform quadratic B-spline segment is the Bezier (mid, p1, mid).
            b = elevate(lerp(0.5f, cp[s], cp[s + 1]), cp[s + 1], lerp(0.5f, cp[s + 1], cp[s + 2]));
        } else {
            const Vec3 p0 = cp[s], p1 = cp[s + 1], p2 = cp[s + 2], p3 = cp[s + 3];
            b = {(p0 + p1 * 4.0f + p2) / 6.0f, (p1 * 2.0f + p2) / 3.0f, (p1 + p2 * 2.0f) / 3.0f,
                 (p1 + p2 * 4.0f + p3) / 6.0f};
        }
        c.segments.push_back(uint32_t(c.points.size()));
        // pbrt: the width goes linearly from width(s / segments) to width((s + 1) / segments); a
        // Bezier spline of equally spaced values is that line.
        const float r0 = 0.5f * width_at(double(s) / double(segments)),
                    r1 = 0.5f * width_at(double(s + 1) / double(segments));
        for (int k = 0; k < 4; ++k) {
            c.points.push_back(b[size_t(k)]);
            c.radii.push_back(r0 + (r1 - r0) * float(k) / 3.0f);
        }
        if (type == Type::Ribbon) {
            const Vec3 n0 = normals[s], n1 = normals[s + 1];
            const std::array<Vec3, 4> nb =
                bezier_through(n0, slerp(1.0f / 3.0f, n0, n1), slerp(2.0f / 3.0f, n0, n1), n1);
            c.normals.insert(c.normals.end(), nb.begin(), nb.end());
        }
    }
    return c;
}

}  // namespace phos::io::pbrt
