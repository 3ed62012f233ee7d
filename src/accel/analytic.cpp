// Canonical-frame analytic primitives: construction from scene::Shape, double-precision ray
// intersection (numerically stable quadratics), tight bounds and surface geometry at a hit.
#include "accel/analytic.h"

#include <algorithm>
#include <cmath>

namespace phos::accel::detail {

namespace {

constexpr double kTwoPi = 6.283185307179586476925;

double length(D3 v) { return std::sqrt(dot(v, v)); }
D3 normalized(D3 v) {
    const double l = length(v);
    return l > 0 ? v * (1.0 / l) : v;
}

// Rigid map taking canonical +z to `axis` and the origin to `center` (Duff et al. 2017 basis, the
// same construction as core/frame.h, so a +z axis gives the identity and phi = atan2(y, x)).
Affine canonical_frame(D3 center, D3 n) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    const D3 s(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    const D3 t(b, sign + n.y * n.y * a, -n.y);
    Affine f;
    for (int r = 0; r < 3; ++r) {
        f.m[r][0] = s[r];
        f.m[r][1] = t[r];
        f.m[r][2] = n[r];
        f.m[r][3] = center[r];
    }
    return f;
}

// Roots of a t^2 + 2 b t + c = 0 given disc = b^2 - a c >= 0, in ascending order; the
// citardauq form avoids cancellation between -b and the square root.
void stable_roots(double a, double b, double c, double disc, double& t0, double& t1) {
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    if (q == 0) {
        t0 = t1 = 0;
        return;
    }
    t0 = q / a;
    t1 = c / q;
    if (t0 > t1) std::swap(t0, t1);
}

struct Best {
    double tmin, tmax;
    CanonicalHit hit;
    bool found = false;
    void offer(double t, D3 p, int part) {
        if (t > tmin && t < tmax) {
            tmax = t;
            hit = {t, p, part};
            found = true;
        }
    }
};

// Hit of the plane z = z0 within radius r (and outside radius ri).
void cap(D3 o, D3 d, double z0, double r, double ri, int part, Best& best) {
    if (d.z == 0) return;
    const double t = (z0 - o.z) / d.z;
    if (!(t > best.tmin && t < best.tmax)) return;
    D3 p = o + d * t;
    const double r2 = p.x * p.x + p.y * p.y;
    if (r2 > r * r || r2 < ri * ri) return;
    p.z = z0;
    best.offer(t, p, part);
}

// The ray's two parameters on the canonical sphere of radius s.radius (false: it misses).
bool sphere_roots(const Analytic& s, D3 o, D3 d, double& t0, double& t1) {
    const double a = dot(d, d);
    if (a == 0) return false;
    const double b = dot(o, d);
    // b^2 - a c written as a (r^2 - |f|^2) with f the closest approach: no catastrophic
    // cancellation for rays starting far away (pbrt-v4's formulation).
    const D3 f = o - d * (b / a);
    const double disc = a * (s.radius * s.radius - dot(f, f));
    if (disc < 0) return false;
    const double c = dot(o, o) - s.radius * s.radius;
    stable_roots(a, b, c, disc, t0, t1);
    return true;
}

void sphere(const Analytic& s, D3 o, D3 d, Best& best) {
    double t0, t1;
    if (!sphere_roots(s, o, d, t0, t1)) return;
    best.offer(t0, o + d * t0, kSide);
    best.offer(t1, o + d * t1, kSide);
}

// pbrt-v4's partial sphere: each root's point, moved onto the sphere, is kept only within the z
// range and the azimuth range, so a ray can pass through the cut and hit the far side.
void partial_sphere(const Analytic& s, D3 o, D3 d, Best& best) {
    double roots[2];
    if (!sphere_roots(s, o, d, roots[0], roots[1])) return;
    for (double t : roots) {
        if (!(t > best.tmin && t < best.tmax)) continue;
        const D3 p = o + d * t;
        const double len = length(p);
        D3 q = len > 0 ? p * (s.radius / len) : p;
        if (q.x == 0 && q.y == 0) q.x = 1e-5 * s.radius;  // phi defined at the poles (pbrt)
        double phi = std::atan2(q.y, q.x);
        if (phi < 0) phi += kTwoPi;
        if (q.z < s.z_min || q.z > s.z_max || phi > s.phi_max) continue;
        best.offer(t, p, kSide);
        return;  // the roots are ascending: the first one kept is the closest
    }
}

void cylinder(const Analytic& s, D3 o, D3 d, Best& best) {
    const double h2 = 0.5 * s.height;
    const double a = d.x * d.x + d.y * d.y;
    if (a > 0) {
        const double b = o.x * d.x + o.y * d.y;
        const double fx = o.x - d.x * (b / a), fy = o.y - d.y * (b / a);
        const double disc = a * (s.radius * s.radius - (fx * fx + fy * fy));
        if (disc >= 0) {
            const double c = o.x * o.x + o.y * o.y - s.radius * s.radius;
            double t0, t1;
            stable_roots(a, b, c, disc, t0, t1);
            for (double t : {t0, t1}) {
                const D3 p = o + d * t;
                if (p.z >= -h2 && p.z <= h2) best.offer(t, p, kSide);
            }
        }
    }
    if (s.capped) {
        cap(o, d, h2, s.radius, 0, kCapTop, best);
        cap(o, d, -h2, s.radius, 0, kCapBottom, best);
    }
}

void cone(const Analytic& s, D3 o, D3 d, Best& best) {
    // x^2 + y^2 = k^2 w^2 with w = apex_z - z the distance below the apex, 0 <= w <= height.
    const double k = s.radius / s.height, k2 = k * k, za = 0.5 * s.height;
    const double ow = za - o.z, dw = -d.z;
    const double a = d.x * d.x + d.y * d.y - k2 * dw * dw;
    const double b = o.x * d.x + o.y * d.y - k2 * ow * dw;
    const double c = o.x * o.x + o.y * o.y - k2 * ow * ow;
    const double scale = d.x * d.x + d.y * d.y + k2 * dw * dw;
    double roots[2];
    int n = 0;
    if (std::fabs(a) <= 1e-14 * scale) {
        // Ray parallel to a generating line: the quadratic degenerates to 2 b t + c = 0.
        if (b != 0) roots[n++] = -c / (2 * b);
    } else {
        const double disc = b * b - a * c;
        if (disc >= 0) {
            stable_roots(a, b, c, disc, roots[0], roots[1]);
            n = 2;
        }
    }
    for (int i = 0; i < n; ++i) {
        const D3 p = o + d * roots[i];
        const double w = za - p.z;
        if (w >= 0 && w <= s.height) best.offer(roots[i], p, kSide);
    }
    if (s.capped) cap(o, d, -za, s.radius, 0, kCapBottom, best);
}

// Half-extent along each axis of the circle {centre + r (cos f e0 + sin f e1)}, where e0, e1 are
// columns 0, 1 of `m`.
D3 circle_half_extent(const Affine& m, double r) {
    D3 e;
    for (int i = 0; i < 3; ++i) {
        const double v = r * std::sqrt(m.m[i][0] * m.m[i][0] + m.m[i][1] * m.m[i][1]);
        (i == 0 ? e.x : (i == 1 ? e.y : e.z)) = v;
    }
    return e;
}

void grow(D3& lo, D3& hi, D3 c, D3 e) {
    lo = {std::min(lo.x, c.x - e.x), std::min(lo.y, c.y - e.y), std::min(lo.z, c.z - e.z)};
    hi = {std::max(hi.x, c.x + e.x), std::max(hi.y, c.y + e.y), std::max(hi.z, c.z + e.z)};
}

}  // namespace

Affine Affine::from(const Transform& t) {
    Affine a;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) a.m[r][c] = t.matrix()(r, c);
    return a;
}

Affine Affine::operator*(const Affine& o) const {
    Affine r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = j == 3 ? m[i][3] : 0.0;
            for (int k = 0; k < 3; ++k) s += m[i][k] * o.m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

double Affine::determinant() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

bool Affine::inverse(Affine& out) const {
    const double det = determinant();
    if (!(std::fabs(det) > 0) || !std::isfinite(det)) return false;
    const double id = 1.0 / det;
    Affine r;
    r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * id;
    r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * id;
    r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * id;
    r.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * id;
    r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * id;
    r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * id;
    r.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * id;
    r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * id;
    r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * id;
    for (int i = 0; i < 3; ++i)
        r.m[i][3] = -(r.m[i][0] * m[0][3] + r.m[i][1] * m[1][3] + r.m[i][2] * m[2][3]);
    out = r;
    return true;
}

double Affine::norm() const {
    double n = 0;
    for (int i = 0; i < 3; ++i) n = std::max(n, std::fabs(m[i][0]) + std::fabs(m[i][1]) + std::fabs(m[i][2]));
    return n;
}

bool make_analytic(const scene::Shape& shape, int index, Analytic& out, const char*& why) {
    using Kind = scene::Shape::Kind;
    Analytic a;
    a.kind = shape.kind;
    a.radius = shape.radius;
    a.inner = shape.inner_radius;
    a.height = shape.height;
    a.capped = shape.capped;
    a.shape = index;
    a.source = &shape;
    a.pbrt_uv = shape.kind == Kind::Sphere && shape.pbrt_uv;
    if (!(a.radius > 0) || !std::isfinite(a.radius)) return why = "radius must be positive", false;
    if (a.kind == Kind::Sphere && shape.partial) {
        a.partial = true;
        a.z_min = std::clamp(double(std::min(shape.z_min, shape.z_max)), -a.radius, a.radius);
        a.z_max = std::clamp(double(std::max(shape.z_min, shape.z_max)), -a.radius, a.radius);
        a.phi_max = std::clamp(double(shape.phi_max), 0.0, kTwoPi);
        a.theta_z_min = std::acos(std::clamp(a.z_min / a.radius, -1.0, 1.0));
        a.theta_z_max = std::acos(std::clamp(a.z_max / a.radius, -1.0, 1.0));
        if (!(a.z_max > a.z_min) || !(a.phi_max > 0)) return why = "partial sphere of zero area", false;
    }
    if ((a.kind == Kind::Cylinder || a.kind == Kind::Cone) && (!(a.height > 0) || !std::isfinite(a.height)))
        return why = "height must be positive", false;
    if (a.kind == Kind::Disk && (!(a.inner >= 0) || !(a.inner < a.radius)))
        return why = "inner radius must lie in [0, radius)", false;
    const D3 dir(a.kind == Kind::Disk ? shape.normal : shape.axis);
    const double len = length(dir);
    if (!(len > 0) || !std::isfinite(len)) return why = "axis / normal must be a non-zero vector", false;

    const Affine world = Affine::from(shape.to_world);
    a.to_space = world * canonical_frame(D3(shape.center), dir * (1.0 / len));
    if (!a.to_space.inverse(a.to_canon)) return why = "singular transform", false;
    a.flip = shape.reverse_orientation != (world.determinant() < 0);
    a.size =
        world.norm() * std::max(a.radius, a.kind == Kind::Sphere || a.kind == Kind::Disk ? 0.0 : a.height);
    out = a;
    return true;
}

bool intersect_canonical(const Analytic& a, D3 o, D3 d, double tmin, double tmax, CanonicalHit& hit) {
    using Kind = scene::Shape::Kind;
    Best best{tmin, tmax, {}};
    switch (a.kind) {
        case Kind::Sphere:
            if (a.partial)
                partial_sphere(a, o, d, best);
            else
                sphere(a, o, d, best);
            break;
        case Kind::Disk:
            cap(o, d, 0.0, a.radius, a.inner, kSide, best);
            break;
        case Kind::Cylinder:
            cylinder(a, o, d, best);
            break;
        case Kind::Cone:
            cone(a, o, d, best);
            break;
        default:
            break;
    }
    if (best.found) hit = best.hit;
    return best.found;
}

void analytic_bounds(const Analytic& a, D3& lo, D3& hi) {
    using Kind = scene::Shape::Kind;
    lo = D3(HUGE_VAL, HUGE_VAL, HUGE_VAL);
    hi = D3(-HUGE_VAL, -HUGE_VAL, -HUGE_VAL);
    const Affine& m = a.to_space;
    const double h2 = 0.5 * a.height;
    switch (a.kind) {
        case Kind::Sphere: {
            if (a.partial) {
                // pbrt-v4's box of a partial sphere: [-r, r]^2 x [z_min, z_max], each corner mapped.
                for (int i = 0; i < 8; ++i) {
                    const D3 c(i & 1 ? a.radius : -a.radius, i & 2 ? a.radius : -a.radius,
                               i & 4 ? a.z_max : a.z_min);
                    grow(lo, hi, m.point(c), D3(0, 0, 0));
                }
                break;
            }
            D3 e;
            for (int i = 0; i < 3; ++i) {
                const double v = a.radius * std::sqrt(m.m[i][0] * m.m[i][0] + m.m[i][1] * m.m[i][1] +
                                                      m.m[i][2] * m.m[i][2]);
                (i == 0 ? e.x : (i == 1 ? e.y : e.z)) = v;
            }
            grow(lo, hi, m.point({0, 0, 0}), e);
            break;
        }
        case Kind::Disk:
            grow(lo, hi, m.point({0, 0, 0}), circle_half_extent(m, a.radius));
            break;
        case Kind::Cylinder:
            grow(lo, hi, m.point({0, 0, h2}), circle_half_extent(m, a.radius));
            grow(lo, hi, m.point({0, 0, -h2}), circle_half_extent(m, a.radius));
            break;
        case Kind::Cone:
            grow(lo, hi, m.point({0, 0, h2}), D3(0, 0, 0));
            grow(lo, hi, m.point({0, 0, -h2}), circle_half_extent(m, a.radius));
            break;
        default:
            break;
    }
    // Pad for the rounding of the box to float and of the hit computation.
    const double mag = std::max({std::fabs(lo.x), std::fabs(lo.y), std::fabs(lo.z), std::fabs(hi.x),
                                 std::fabs(hi.y), std::fabs(hi.z), a.size});
    const double pad = 1e-6 * mag;
    lo = lo - D3(pad, pad, pad);
    hi = hi + D3(pad, pad, pad);
}

AnalyticSurface analytic_surface(const Analytic& a, const CanonicalHit& hit, double inset) {
    using Kind = scene::Shape::Kind;
    D3 p = hit.p, n;
    const double k = a.kind == Kind::Cone ? a.radius / a.height : 0.0, h2 = 0.5 * a.height;
    if (a.capped && (a.kind == Kind::Cylinder || a.kind == Kind::Cone)) {
        // Keep points off the rim between cap and side (see the header).
        const double r0 = std::sqrt(p.x * p.x + p.y * p.y);
        if (hit.part != kSide) {
            const double rmax = a.radius - inset * (1 + 2 * k);
            if (r0 > rmax && rmax > 0.5 * a.radius) p.x *= rmax / r0, p.y *= rmax / r0;
        } else {
            const double lo = -h2 + inset * (1 + 2 * k), hi = k > 0 ? h2 - 3 * inset / k : h2 - inset;
            if (lo < hi) p.z = std::clamp(p.z, lo, hi);
        }
    }
    double phi = std::atan2(p.y, p.x);
    if (phi < 0) phi += kTwoPi;
    const double rho = std::sqrt(p.x * p.x + p.y * p.y);
    Vec2 uv;
    const float u = float(phi / kTwoPi);
    if (hit.part != kSide) {
        // Flat cap of a cylinder or cone: u around, v outwards from the axis.
        p.z = hit.part == kCapTop ? 0.5 * a.height : -0.5 * a.height;
        n = D3(0, 0, hit.part == kCapTop ? 1 : -1);
        uv = {u, float(std::min(rho / a.radius, 1.0))};
    } else {
        switch (a.kind) {
            case Kind::Sphere: {
                // Re-project onto the sphere: removes the error of o + t d along the ray.
                p = p * (a.radius / length(p));
                n = p * (1.0 / a.radius);
                const double theta = std::acos(std::clamp(p.z / a.radius, -1.0, 1.0));
                if (a.partial) {
                    // pbrt-v4: u = phi / phi_max, v = (theta - theta_z_min) / (theta_z_max - theta_z_min).
                    uv = {float(std::min(phi / a.phi_max, 1.0)),
                          float(std::clamp((theta - a.theta_z_min) / (a.theta_z_max - a.theta_z_min), 0.0,
                                           1.0))};
                    break;
                }
                const float v = float(theta / (0.5 * kTwoPi));
                uv = {u, a.pbrt_uv ? 1 - v : v};
                break;
            }
            case Kind::Disk:
                p.z = 0;
                n = D3(0, 0, 1);
                uv = {u, float(std::clamp((a.radius - rho) / (a.radius - a.inner), 0.0, 1.0))};
                break;
            case Kind::Cylinder:
                if (rho > 0) p.x *= a.radius / rho, p.y *= a.radius / rho;
                n = D3(p.x, p.y, 0) * (1.0 / a.radius);
                uv = {u, float(std::clamp(p.z / a.height + 0.5, 0.0, 1.0))};
                break;
            case Kind::Cone: {
                const double w = 0.5 * a.height - p.z;
                // Re-project horizontally onto the cone (also after the rim clamp moved z).
                const double rw = std::sqrt(p.x * p.x + p.y * p.y);
                if (rw > 0) p.x *= k * w / rw, p.y *= k * w / rw;
                n = normalized(D3(p.x, p.y, k * k * w));
                if (!(dot(n, n) > 0)) n = D3(0, 0, 1);  // the apex
                uv = {u, float(std::clamp(p.z / a.height + 0.5, 0.0, 1.0))};
                break;
            }
            default:
                break;
        }
    }
    // Tangent along increasing phi; at the axis (rho = 0) the limit direction for phi = 0.
    const D3 dpdu_c = rho > 0 ? D3(-p.y / rho, p.x / rho, 0) : D3(0, 1, 0);

    AnalyticSurface s;
    s.p = a.to_space.point(p);
    s.n = normalized(a.to_canon.transpose_vector(n));
    if (a.flip) s.n = s.n * -1.0;
    s.dpdu = normalized(a.to_space.vector(dpdu_c));
    s.uv = uv;
    return s;
}

}  // namespace phos::accel::detail
