// dp/du and dp/dv at a hit, per shape kind (see surface_derivatives.h).
#include "accel/surface_derivatives.h"

#include <array>
#include <cmath>

#include "accel/analytic.h"
#include "accel/curves.h"

namespace phos::accel {

using detail::Affine;
using detail::D3;

namespace {

constexpr double kTwoPi = 6.283185307179586476925;

D3 unit(D3 v) {
    const double l = std::sqrt(detail::dot(v, v));
    return l > 0 ? v * (1.0 / l) : v;
}

// The fallback pair: the hit's unit tangent and ns x it.
SurfaceDerivatives unit_pair(const SurfaceHit& hit) { return {hit.dpdu, cross(hit.ns, hit.dpdu)}; }

// Triangle `prim` of `mesh` in object space (pbrt-v4's Triangle::InteractionFromIntersection).
bool triangle_derivatives(const scene::TriangleMesh& mesh, size_t prim, D3& dpdu, D3& dpdv) {
    const uint32_t* idx = &mesh.indices[3 * prim];
    const D3 p0(mesh.positions[idx[0]]), p1(mesh.positions[idx[1]]), p2(mesh.positions[idx[2]]);
    if (mesh.uvs.size() != mesh.positions.size()) {
        dpdu = p1 - p0;  // uv = (b1, b2)
        dpdv = p2 - p0;
        return true;
    }
    const Vec2 t0 = mesh.uvs[idx[0]], t1 = mesh.uvs[idx[1]], t2 = mesh.uvs[idx[2]];
    const double du02 = double(t0.x) - t2.x, dv02 = double(t0.y) - t2.y;
    const double du12 = double(t1.x) - t2.x, dv12 = double(t1.y) - t2.y;
    const double det = du02 * dv12 - dv02 * du12;
    if (!(std::fabs(det) >= 1e-9)) return false;
    const D3 dp02 = p0 - p2, dp12 = p1 - p2;
    dpdu = (dp02 * dv12 - dp12 * dv02) * (1.0 / det);
    dpdv = (dp12 * du02 - dp02 * du12) * (1.0 / det);
    return true;
}

// Whether object-space point p lies on triangle `prim` (for meshes holding both triangles and
// bilinear patches, whose primitive numbers overlap).
bool on_triangle(const scene::TriangleMesh& mesh, size_t prim, D3 p) {
    if (prim >= mesh.triangle_count()) return false;
    const uint32_t* idx = &mesh.indices[3 * prim];
    const D3 p0(mesh.positions[idx[0]]), p1(mesh.positions[idx[1]]), p2(mesh.positions[idx[2]]);
    const D3 e1 = p1 - p0, e2 = p2 - p0, n = detail::cross(e1, e2);
    const double n2 = detail::dot(n, n);
    if (!(n2 > 0)) return false;
    const D3 q = p - p0;
    const double b1 = detail::dot(detail::cross(q, e2), n) / n2,
                 b2 = detail::dot(detail::cross(e1, q), n) / n2;
    const double size = std::sqrt(std::max(detail::dot(e1, e1), detail::dot(e2, e2)));
    const double tol = 1e-4;
    return b1 >= -tol && b2 >= -tol && b1 + b2 <= 1 + tol &&
           std::fabs(detail::dot(q, n)) <= tol * size * std::sqrt(n2);
}

// Patch `prim` (pbrt's corner order p00 p10 p01 p11) in object space at object-space point p.
void patch_derivatives(const scene::TriangleMesh& mesh, size_t prim, D3 p, Vec2 uv, D3& dpdu, D3& dpdv) {
    const uint32_t* idx = &mesh.patches[4 * prim];
    std::array<D3, 4> c;
    for (int k = 0; k < 4; ++k) c[size_t(k)] = D3(mesh.positions[idx[k]]);
    const auto at = [&](double u, double v) {
        return (c[0] * (1 - u) + c[1] * u) * (1 - v) + (c[2] * (1 - u) + c[3] * u) * v;
    };
    const auto du_at = [&](double v) { return (c[1] - c[0]) * (1 - v) + (c[3] - c[2]) * v; };
    const auto dv_at = [&](double u) { return (c[2] - c[0]) * (1 - u) + (c[3] - c[1]) * u; };
    const bool has_uvs = mesh.uvs.size() == mesh.positions.size();
    double u = uv.x, v = uv.y;
    if (has_uvs) {
        // The patch's own (u, v) of p: Gauss-Newton on |at(u, v) - p|^2 from the centre.
        u = v = 0.5;
        for (int it = 0; it < 20; ++it) {
            const D3 r = at(u, v) - p, a = du_at(v), b = dv_at(u);
            const double aa = detail::dot(a, a), ab = detail::dot(a, b), bb = detail::dot(b, b);
            const double ra = detail::dot(r, a), rb = detail::dot(r, b), det = aa * bb - ab * ab;
            if (!(std::fabs(det) > 0)) break;
            const double su = (bb * ra - ab * rb) / det, sv = (aa * rb - ab * ra) / det;
            u = std::clamp(u - su, 0.0, 1.0), v = std::clamp(v - sv, 0.0, 1.0);
            if (std::fabs(su) + std::fabs(sv) < 1e-12) break;
        }
    }
    dpdu = du_at(v);
    dpdv = dv_at(u);
    if (!has_uvs) return;
    // d(s, t)/d(u, v) of the corners' uvs, and dp/ds, dp/dt by the chain rule when invertible.
    const Vec2 t00 = mesh.uvs[idx[0]], t10 = mesh.uvs[idx[1]], t01 = mesh.uvs[idx[2]], t11 = mesh.uvs[idx[3]];
    const double dsdu = (1 - v) * (double(t10.x) - t00.x) + v * (double(t11.x) - t01.x);
    const double dtdu = (1 - v) * (double(t10.y) - t00.y) + v * (double(t11.y) - t01.y);
    const double dsdv = (1 - u) * (double(t01.x) - t00.x) + u * (double(t11.x) - t10.x);
    const double dtdv = (1 - u) * (double(t01.y) - t00.y) + u * (double(t11.y) - t10.y);
    const double det = dsdu * dtdv - dtdu * dsdv;
    if (!(std::fabs(det) > 1e-12)) return;
    const D3 dpds = (dpdu * dtdv - dpdv * dtdu) * (1.0 / det);
    const D3 dpdt = (dpdv * dsdu - dpdu * dsdv) * (1.0 / det);
    dpdu = dpds, dpdv = dpdt;
}

// An analytic shape's derivatives in its canonical frame at canonical point p (the
// parameterisations of accel/analytic.cpp's analytic_surface). False at a pole or the axis.
bool analytic_derivatives(const detail::Analytic& a, D3 p, bool cap, D3& dpdu, D3& dpdv) {
    using Kind = scene::Shape::Kind;
    const double rho = std::sqrt(p.x * p.x + p.y * p.y);
    if (!(rho > 1e-9 * a.radius)) return false;
    const D3 around(-p.y, p.x, 0), out(p.x / rho, p.y / rho, 0);
    dpdu = around * kTwoPi;
    if (cap) {
        dpdv = out * a.radius;  // v = rho / radius
        return true;
    }
    switch (a.kind) {
        case Kind::Sphere: {
            const D3 dtheta(out.x * p.z, out.y * p.z, -rho);  // dp/dtheta
            if (a.partial) {
                dpdu = around * a.phi_max;
                dpdv = dtheta * (a.theta_z_max - a.theta_z_min);
            } else {
                dpdv = dtheta * (a.pbrt_uv ? -0.5 * kTwoPi : 0.5 * kTwoPi);  // v = theta / pi, or 1 - it
            }
            return true;
        }
        case Kind::Disk:
            dpdv = out * -(a.radius - a.inner);  // v = (r_out - rho) / (r_out - r_in)
            return true;
        case Kind::Cylinder:
            dpdv = D3(0, 0, a.height);  // v = z / h + 1/2
            return true;
        case Kind::Cone: {
            const double k = a.radius / a.height;  // rho = k (h/2 - z)
            dpdv = D3(-k * a.height * out.x, -k * a.height * out.y, a.height);
            return true;
        }
        default:
            return false;
    }
}

}  // namespace

SurfaceDerivatives surface_derivatives(const scene::Scene& scene, const SurfaceHit& hit) {
    using Kind = scene::Shape::Kind;
    const scene::Shape* shape = nullptr;
    Affine inst;  // instance to world (identity at the top level)
    if (hit.instance >= 0) {
        if (size_t(hit.instance) >= scene.instances.size()) return unit_pair(hit);
        const scene::Instance& in = scene.instances[size_t(hit.instance)];
        if (in.object < 0 || size_t(in.object) >= scene.objects.size()) return unit_pair(hit);
        const auto& shapes = scene.objects[size_t(in.object)].shapes;
        if (hit.shape < 0 || size_t(hit.shape) >= shapes.size()) return unit_pair(hit);
        shape = &shapes[size_t(hit.shape)];
        inst = Affine::from(in.to_world);
    } else {
        if (hit.shape < 0 || size_t(hit.shape) >= scene.shapes.size()) return unit_pair(hit);
        shape = &scene.shapes[size_t(hit.shape)];
    }
    Affine inst_inv;
    if (!inst.inverse(inst_inv)) return unit_pair(hit);
    const D3 p_geom = inst_inv.point(D3(hit.p));  // in the shape's geometry space (before the instance)
    D3 dpdu, dpdv;
    const size_t prim = hit.primitive >= 0 ? size_t(hit.primitive) : 0;
    switch (shape->kind) {
        case Kind::Mesh: {
            const scene::TriangleMesh& mesh = shape->mesh;
            const Affine to_world = Affine::from(shape->to_world);
            Affine to_object;
            if (!to_world.inverse(to_object)) return unit_pair(hit);
            const D3 p_obj = to_object.point(p_geom);
            const bool patch = !mesh.patches.empty() &&
                               (mesh.indices.empty() || !on_triangle(mesh, prim, p_obj)) &&
                               prim < mesh.patch_count();
            if (patch) {
                patch_derivatives(mesh, prim, p_obj, hit.uv, dpdu, dpdv);
            } else if (prim >= mesh.triangle_count() || !triangle_derivatives(mesh, prim, dpdu, dpdv)) {
                return unit_pair(hit);
            }
            dpdu = inst.vector(to_world.vector(dpdu));
            dpdv = inst.vector(to_world.vector(dpdv));
            if (mesh.normals.size() == mesh.positions.size()) {
                // pbrt-v4's shading pair around the interpolated normal.
                const D3 ns(hit.ns);
                const D3 ts = detail::cross(ns, dpdu);
                if (!(detail::dot(ts, ts) > 0)) return unit_pair(hit);
                dpdu = detail::cross(ts, ns);
                dpdv = ts;
            }
            break;
        }
        case Kind::Sphere:
        case Kind::Disk:
        case Kind::Cylinder:
        case Kind::Cone: {
            detail::Analytic a;
            const char* why = "";
            if (!detail::make_analytic(*shape, hit.shape, a, why)) return unit_pair(hit);
            const D3 p = a.to_canon.point(p_geom);
            // A cap of a capped cylinder or cone: the canonical normal along the axis at an end.
            D3 nc = unit(a.to_space.transpose_vector(inst.transpose_vector(D3(hit.ng))));
            const bool cap = a.capped && (a.kind == Kind::Cylinder || a.kind == Kind::Cone) &&
                             std::fabs(nc.z) > 0.99 && std::fabs(p.z) > 0.5 * a.height * (1 - 1e-4);
            if (!analytic_derivatives(a, p, cap, dpdu, dpdv)) return unit_pair(hit);
            dpdu = inst.vector(a.to_space.vector(dpdu));
            dpdv = inst.vector(a.to_space.vector(dpdv));
            break;
        }
        case Kind::Curves: {
            const scene::CurveSet& c = shape->curves;
            if (prim >= c.segment_count() || size_t(c.segments[prim]) + 4 > c.points.size())
                return unit_pair(hit);
            double w[4], dw[4];
            detail::curve_basis(c.basis, std::clamp(double(hit.uv.x), 0.0, 1.0), w, dw);
            D3 tangent;
            double radius = 0;
            for (size_t k = 0; k < 4; ++k) {
                const size_t i = size_t(c.segments[prim]) + k;
                tangent = tangent + D3(c.points[i]) * dw[k];
                if (i < c.radii.size()) radius += double(c.radii[i]) * w[k];
            }
            const Affine to_world = Affine::from(shape->to_world);
            dpdu = inst.vector(to_world.vector(tangent));
            // v runs across the curve towards d x dC/du (accel/curves.h), which for a normal facing
            // the ray is dpdu x ns; the width scales with the transform's linear scale (|det|^(1/3)),
            // as the curve does.
            const double scale = std::cbrt(std::fabs(to_world.determinant() * inst.determinant()));
            dpdv = unit(detail::cross(dpdu, D3(hit.ns))) * (2 * radius * scale);
            break;
        }
        default:
            return unit_pair(hit);
    }
    const SurfaceDerivatives d{dpdu.to_float(), dpdv.to_float()};
    if (!is_finite(d.dpdu) || !is_finite(d.dpdv) || !(length_squared(cross(d.dpdu, d.dpdv)) > 0))
        return unit_pair(hit);
    return d;
}

}  // namespace phos::accel
