// Curves as Embree curve geometry: buffers from scene::CurveSet, and the hit surface (cubic Bezier
// and uniform cubic B-spline bases, e.g. Farin, "Curves and Surfaces for CAGD", ch. 4 and 7).
#include "accel/curves.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/frame.h"

namespace phos::accel::detail {
namespace {

constexpr double kUlp = 0x1p-24;

double length(D3 v) { return std::sqrt(dot(v, v)); }
D3 normalized(D3 v) {
    const double l = length(v);
    return l > 0 ? v * (1.0 / l) : v;
}
double max_abs(D3 v) { return std::max(std::fabs(v.x), std::max(std::fabs(v.y), std::fabs(v.z))); }

RTCGeometryType embree_type(const scene::CurveSet& c) {
    using T = scene::CurveSet::Type;
    const bool bezier = c.basis == scene::CurveSet::Basis::Bezier;
    switch (c.type) {
        case T::Cylinder:
            return bezier ? RTC_GEOMETRY_TYPE_ROUND_BEZIER_CURVE : RTC_GEOMETRY_TYPE_ROUND_BSPLINE_CURVE;
        case T::Ribbon:
            return bezier ? RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BEZIER_CURVE
                          : RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BSPLINE_CURVE;
        case T::Flat:
            break;
    }
    return bezier ? RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE : RTC_GEOMETRY_TYPE_FLAT_BSPLINE_CURVE;
}

std::string where(const scene::Shape& s) { return s.origin.empty() ? std::string("curve") : s.origin; }

}  // namespace

void curve_basis(scene::CurveSet::Basis b, double u, double w[4], double dw[4]) {
    const double s = 1 - u;
    if (b == scene::CurveSet::Basis::Bezier) {
        // Bernstein polynomials of degree 3.
        w[0] = s * s * s, w[1] = 3 * u * s * s, w[2] = 3 * u * u * s, w[3] = u * u * u;
        dw[0] = -3 * s * s, dw[1] = 3 * s * s - 6 * u * s, dw[2] = 6 * u * s - 3 * u * u, dw[3] = 3 * u * u;
    } else {
        // Uniform cubic B-spline.
        w[0] = s * s * s / 6, w[1] = (3 * u * u * u - 6 * u * u + 4) / 6;
        w[2] = (-3 * u * u * u + 3 * u * u + 3 * u + 1) / 6, w[3] = u * u * u / 6;
        dw[0] = -s * s / 2, dw[1] = (3 * u * u - 4 * u) / 2, dw[2] = (-3 * u * u + 2 * u + 1) / 2,
        dw[3] = u * u / 2;
    }
}

RTCGeometry new_curve_geometry(RTCDevice device, const scene::Shape& shape, int index, CurveGeom& out,
                               std::string& why) {
    const scene::CurveSet& c = shape.curves;
    const size_t np = c.points.size(), ns = c.segments.size();
    const bool ribbon = c.type == scene::CurveSet::Type::Ribbon;
    if (np == 0 || ns == 0) {
        why = "no curve segments";
        return nullptr;
    }
    if (c.radii.size() != np)
        throw InputError(where(shape) + ": curve has " + std::to_string(c.radii.size()) + " radii for " +
                         std::to_string(np) + " control points");
    if (ribbon && c.normals.size() != np)
        throw InputError(where(shape) + ": ribbon curve has " + std::to_string(c.normals.size()) +
                         " normals for " + std::to_string(np) + " control points");
    for (uint32_t s : c.segments)
        if (size_t(s) + 4 > np)
            throw InputError(where(shape) + ": curve segment at control point " + std::to_string(s) +
                             " runs past the " + std::to_string(np) + " control points");
    for (size_t i = 0; i < np; ++i)
        if (!is_finite(c.points[i]) || !std::isfinite(c.radii[i]) || (ribbon && !is_finite(c.normals[i])))
            throw InputError(where(shape) + ": curve has a non-finite control point, radius or normal");
    const Affine m = Affine::from(shape.to_world);
    const double scale = std::cbrt(std::fabs(m.determinant()));
    if (!(scale > 0)) {
        why = "singular transform";
        return nullptr;
    }

    RTCGeometry g = rtcNewGeometry(device, embree_type(c));
    if (!g) {
        why = "Embree has no such curve geometry";
        return nullptr;
    }
    auto* vb = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), np));
    auto* ib = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(uint32_t), ns));
    float* nb = nullptr;
    if (ribbon)
        nb = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), np));
    if (!vb || !ib || (ribbon && !nb)) {
        rtcReleaseGeometry(g);
        throw InputError(where(shape) + ": cannot allocate curve buffers");
    }
    for (size_t i = 0; i < np; ++i) {
        const Vec3 w = m.point(D3(c.points[i])).to_float();
        vb[4 * i] = w.x, vb[4 * i + 1] = w.y, vb[4 * i + 2] = w.z;
        vb[4 * i + 3] = float(c.radii[i] * scale);
        if (nb) {
            Vec3 n = shape.to_world.normal(c.normals[i]);
            const float l = length(n);
            n = l > 0 ? n / l : n;
            nb[3 * i] = n.x, nb[3 * i + 1] = n.y, nb[3 * i + 2] = n.z;
        }
    }
    std::copy(c.segments.begin(), c.segments.end(), ib);
    out.vertices = vb;
    out.normals = nb;
    out.segments = ib;
    out.type = c.type;
    out.basis = c.basis;
    out.flip = shape.reverse_orientation != shape.to_world.swaps_handedness();
    out.source = &shape;
    out.shape = index;
    return g;
}

CurveSurface curve_surface(const CurveGeom& c, unsigned prim, float u, D3 ng, D3 o, D3 d, double t) {
    using T = scene::CurveSet::Type;
    const double uu = std::clamp(double(u), 0.0, 1.0);
    double w[4], dw[4];
    curve_basis(c.basis, uu, w, dw);
    const uint32_t first = c.segments[prim];
    D3 centre, tangent, spline_normal;
    double radius = 0;
    for (int k = 0; k < 4; ++k) {
        const float* v = c.vertices + 4 * (size_t(first) + size_t(k));
        const D3 cp(v[0], v[1], v[2]);
        centre = centre + cp * w[k];
        tangent = tangent + cp * dw[k];
        radius += v[3] * w[k];
        if (c.normals) {
            const float* n = c.normals + 3 * (size_t(first) + size_t(k));
            spline_normal = spline_normal + D3(n[0], n[1], n[2]) * w[k];
        }
    }
    radius = std::max(radius, 0.0);
    CurveSurface s;
    s.p = o + d * t;
    s.dpdu = normalized(tangent);
    const D3 offset = s.p - centre;
    if (!(dot(s.dpdu, s.dpdu) > 0)) s.dpdu = normalized(D3(Frame(normalized(d).to_float()).s));
    D3 n = normalized(ng);
    switch (c.type) {
        case T::Cylinder:
            if (!(dot(n, n) > 0)) n = normalized(offset);
            if (dot(n, offset) < 0) n = n * -1.0;
            break;
        case T::Ribbon:
            if (!(dot(n, n) > 0)) n = normalized(spline_normal - s.dpdu * dot(spline_normal, s.dpdu));
            if (dot(n, spline_normal) < 0) n = n * -1.0;
            break;
        case T::Flat:
            n = normalized(s.dpdu * dot(d, s.dpdu) - d);
            break;
    }
    if (!(dot(n, n) > 0)) n = D3(Frame(s.dpdu.to_float()).s);
    if (c.flip) n = n * -1.0;
    s.n = n;
    // v as pbrt-v4's edge function gives it: the signed distance across the curve as the ray sees
    // it, over the width.
    const D3 side = normalized(cross(d, tangent));
    const double v = radius > 0 ? 0.5 + dot(offset, side) / (2 * radius) : 0.5;
    s.uv = {float(uu), float(std::clamp(v, 0.0, 1.0))};
    // Embree intersects curves in float with iterative solvers: allow a small fraction of the
    // radius beside the rounding of p; a flat curve is re-oriented for every ray, so a spawned ray
    // must clear the whole width (pbrt-v4's error bound for curves).
    const double rounding = 64 * kUlp * std::max(max_abs(s.p), max_abs(centre) + radius);
    s.error = c.type == T::Flat ? 2 * radius + rounding : 1e-3 * radius + rounding;
    return s;
}

}  // namespace phos::accel::detail
