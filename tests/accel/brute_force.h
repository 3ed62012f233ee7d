// Reference ray intersector for the accel tests: plain loops over every shape in double precision,
// formulated independently of src/accel (world-space Moller-Trumbore, slab test for boxes,
// implicit forms with the shape's own axis for quadrics), with the same orientation conventions.
#pragma once

#include <cmath>
#include <optional>

#include "scene/scene.h"

namespace phos::testing {

struct Dv {
    double x = 0, y = 0, z = 0;
    Dv() = default;
    Dv(double a, double b, double c) : x(a), y(b), z(c) {}
    explicit Dv(Vec3 v) : x(v.x), y(v.y), z(v.z) {}
    Dv operator+(Dv o) const { return {x + o.x, y + o.y, z + o.z}; }
    Dv operator-(Dv o) const { return {x - o.x, y - o.y, z - o.z}; }
    Dv operator*(double s) const { return {x * s, y * s, z * s}; }
    double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    Vec3 f() const { return {float(x), float(y), float(z)}; }
};
inline double dotd(Dv a, Dv b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Dv crossd(Dv a, Dv b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline Dv unitd(Dv a) { return a * (1.0 / std::sqrt(dotd(a, a))); }

// 4x4 affine matrix in double with its inverse computed here (not Transform's float inverse).
struct Md {
    double a[4][4];
    double inv[4][4];
    explicit Md(const Transform& t) {
        double g[4][8];
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                a[i][j] = t.matrix()(i, j);
                g[i][j] = a[i][j];
                g[i][j + 4] = i == j;
            }
        for (int c = 0; c < 4; ++c) {
            int p = c;
            for (int r = c + 1; r < 4; ++r)
                if (std::fabs(g[r][c]) > std::fabs(g[p][c])) p = r;
            for (int j = 0; j < 8; ++j) std::swap(g[c][j], g[p][j]);
            const double s = 1 / g[c][c];
            for (int j = 0; j < 8; ++j) g[c][j] *= s;
            for (int r = 0; r < 4; ++r)
                if (r != c) {
                    const double f = g[r][c];
                    for (int j = 0; j < 8; ++j) g[r][j] -= f * g[c][j];
                }
        }
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) inv[i][j] = g[i][j + 4];
    }
    Dv point(Dv p) const { return mul(a, p, 1); }
    Dv vector(Dv v) const { return mul(a, v, 0); }
    Dv inv_point(Dv p) const { return mul(inv, p, 1); }
    Dv inv_vector(Dv v) const { return mul(inv, v, 0); }
    Dv normal(Dv n) const {  // inverse transpose
        return {inv[0][0] * n.x + inv[1][0] * n.y + inv[2][0] * n.z,
                inv[0][1] * n.x + inv[1][1] * n.y + inv[2][1] * n.z,
                inv[0][2] * n.x + inv[1][2] * n.y + inv[2][2] * n.z};
    }
    double det() const {
        return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
               a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    }
    static Dv mul(const double m[4][4], Dv p, double w) {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3] * w,
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3] * w,
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3] * w};
    }
};

struct RefHit {
    double t = 1e300;
    int shape = -1, instance = -1;
    Dv n;  // unit world-space geometric normal (orientation conventions of SurfaceHit::ng)
};

// Smallest root of a t^2 + b t + c = 0 in (lo, hi), plain formula (double is ample here).
inline void quad_roots(double a, double b, double c, double r[2], int& n) {
    n = 0;
    if (a == 0) {
        if (b != 0) r[n++] = -c / b;
        return;
    }
    const double disc = b * b - 4 * a * c;
    if (disc < 0) return;
    const double s = std::sqrt(disc);
    r[0] = (-b - s) / (2 * a), r[1] = (-b + s) / (2 * a);
    if (r[0] > r[1]) std::swap(r[0], r[1]);
    n = 2;
}

// Closest hit of a shape for the ray o + t d (in the space the shape's to_world maps into).
// Returns the normal in that space.
inline bool ref_shape(const scene::Shape& s, Dv o, Dv d, double tmin, double tmax, double& t, Dv& n) {
    using K = scene::Shape::Kind;
    const Md M(s.to_world);
    const bool flip = s.reverse_orientation != (M.det() < 0);
    bool found = false;
    auto offer = [&](double tt, Dv nn) {
        if (tt > tmin && tt < tmax && tt < t) t = tt, n = nn, found = true;
    };
    if (s.kind == K::Mesh) {
        std::vector<Dv> P, N;
        for (Vec3 p : s.mesh.positions) P.push_back(M.point(Dv(p)));
        for (Vec3 q : s.mesh.normals)
            N.push_back(unitd(M.normal(Dv(q))) * (s.reverse_orientation ? -1.0 : 1.0));
        for (size_t k = 0; k + 2 < s.mesh.indices.size(); k += 3) {
            const uint32_t i0 = s.mesh.indices[k], i1 = s.mesh.indices[k + 1], i2 = s.mesh.indices[k + 2];
            const Dv e1 = P[i1] - P[i0], e2 = P[i2] - P[i0];
            const Dv pv = crossd(d, e2);
            const double det = dotd(e1, pv);
            if (det == 0) continue;
            const Dv tv = o - P[i0];
            const double u = dotd(tv, pv) / det;
            if (u < 0 || u > 1) continue;
            const Dv qv = crossd(tv, e1);
            const double v = dotd(d, qv) / det;
            if (v < 0 || u + v > 1) continue;
            const double tt = dotd(e2, qv) / det;
            Dv ng = unitd(crossd(e1, e2)) * (flip ? -1.0 : 1.0);
            if (!N.empty()) {
                const Dv ns = N[i0] * (1 - u - v) + N[i1] * u + N[i2] * v;
                if (dotd(ng, ns) < 0) ng = ng * -1.0;
            }
            offer(tt, ng);
        }
        return found;
    }
    // Quadrics and boxes: intersect in object space, normal back by the inverse transpose.
    const Dv oo = M.inv_point(o), dd = M.inv_vector(d);
    double to = t;
    Dv no;
    bool f2 = false;
    auto offer_o = [&](double tt, Dv nn) {
        if (tt > tmin && tt < tmax && tt < to) to = tt, no = nn, f2 = true;
    };
    const Dv c(s.center);
    const Dv ax = unitd(Dv(s.kind == K::Disk ? s.normal : s.axis));
    const double r = s.radius, h = s.height;
    auto disk = [&](Dv centre, Dv nrm, double rad, double rin, Dv out) {
        const double den = dotd(dd, nrm);
        if (den == 0) return;
        const double tt = dotd(centre - oo, nrm) / den;
        const Dv q = oo + dd * tt - centre;
        const double r2 = dotd(q, q);
        if (r2 <= rad * rad && r2 >= rin * rin) offer_o(tt, out);
    };
    double R[2];
    int nr;
    switch (s.kind) {
        case K::Box: {
            const Vec3 lo = min(s.box_min, s.box_max), hi = max(s.box_min, s.box_max);
            for (int a = 0; a < 3; ++a)
                for (int side = 0; side < 2; ++side) {
                    if (dd[a] == 0) continue;
                    const double plane = side ? hi[a] : lo[a];
                    const double tt = (plane - oo[a]) / dd[a];
                    const Dv q = oo + dd * tt;
                    bool in = true;
                    for (int b = 0; b < 3; ++b)
                        if (b != a && (q[b] < lo[b] || q[b] > hi[b])) in = false;
                    Dv nn(0, 0, 0);
                    (a == 0 ? nn.x : (a == 1 ? nn.y : nn.z)) = side ? 1 : -1;
                    if (in) offer_o(tt, nn);
                }
            // Boxes are triangle meshes: pbrt's mesh rule keeps them outward under mirroring.
            if (f2) n = unitd(M.normal(no)) * (s.reverse_orientation ? -1.0 : 1.0), t = to;
            return f2;
        }
        case K::Sphere: {
            const Dv w = oo - c;
            quad_roots(dotd(dd, dd), 2 * dotd(w, dd), dotd(w, w) - r * r, R, nr);
            for (int i = 0; i < nr; ++i) offer_o(R[i], (w + dd * R[i]) * (1 / r));
            break;
        }
        case K::Disk:
            disk(c, ax, r, s.inner_radius, ax);
            break;
        case K::Cylinder: {
            const Dv w = oo - c;
            const Dv wp = w - ax * dotd(w, ax), dp = dd - ax * dotd(dd, ax);
            quad_roots(dotd(dp, dp), 2 * dotd(wp, dp), dotd(wp, wp) - r * r, R, nr);
            for (int i = 0; i < nr; ++i) {
                const Dv q = w + dd * R[i];
                if (std::fabs(dotd(q, ax)) <= h / 2) offer_o(R[i], unitd(q - ax * dotd(q, ax)));
            }
            if (s.capped) {
                disk(c + ax * (h / 2), ax, r, 0, ax);
                disk(c - ax * (h / 2), ax, r, 0, ax * -1.0);
            }
            break;
        }
        case K::Cone: {
            const double k = r / h;
            const Dv apex = c + ax * (h / 2);
            const Dv e = apex - oo;
            const double es = dotd(e, ax), ds = dotd(dd, ax);
            const Dv ep = e - ax * es, dp = dd - ax * ds;
            quad_roots(dotd(dp, dp) - k * k * ds * ds, -2 * dotd(ep, dp) + 2 * k * k * es * ds,
                       dotd(ep, ep) - k * k * es * es, R, nr);
            for (int i = 0; i < nr; ++i) {
                const Dv q = apex - (oo + dd * R[i]);
                const double sa = dotd(q, ax);
                if (sa < 0 || sa > h) continue;
                const Dv radial = unitd((q - ax * sa) * -1.0);
                offer_o(R[i], unitd(radial + ax * k));
            }
            if (s.capped) disk(c - ax * (h / 2), ax, r, 0, ax * -1.0);
            break;
        }
        default:
            break;
    }
    if (f2) n = unitd(M.normal(no)) * (flip ? -1.0 : 1.0), t = to;
    return f2;
}

inline std::optional<RefHit> ref_intersect(const scene::Scene& sc, Dv o, Dv d, double tmin, double tmax) {
    RefHit best;
    best.t = tmax;
    bool found = false;
    for (size_t i = 0; i < sc.shapes.size(); ++i) {
        double t = best.t;
        Dv n;
        if (ref_shape(sc.shapes[i], o, d, tmin, best.t, t, n)) best = {t, int(i), -1, n}, found = true;
    }
    for (size_t j = 0; j < sc.instances.size(); ++j) {
        const Md I(sc.instances[j].to_world);
        const Dv oi = I.inv_point(o), di = I.inv_vector(d);
        const auto& shapes = sc.objects[size_t(sc.instances[j].object)].shapes;
        for (size_t i = 0; i < shapes.size(); ++i) {
            double t = best.t;
            Dv n;
            if (ref_shape(shapes[i], oi, di, tmin, best.t, t, n))
                best = {t, int(i), int(j), unitd(I.normal(n))}, found = true;
        }
    }
    if (!found) return std::nullopt;
    return best;
}

}  // namespace phos::testing
