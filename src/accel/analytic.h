// Exact analytic primitives (sphere, disk, cylinder, cone) for Embree user geometry: each lives in
// a canonical frame (centre at the origin, axis = +z) and is intersected there in double precision.
#pragma once

#include "core/vec.h"
#include "scene/shape.h"

namespace phos::accel::detail {

// Double-precision 3-vector: the analytic intersection runs in double so that hits of rays coming
// from far away, and the sign of t for rays spawned next to the surface, are exact enough.
struct D3 {
    double x = 0, y = 0, z = 0;
    D3() = default;
    D3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    explicit D3(Vec3 v) : x(v.x), y(v.y), z(v.z) {}
    D3 operator+(D3 o) const { return {x + o.x, y + o.y, z + o.z}; }
    D3 operator-(D3 o) const { return {x - o.x, y - o.y, z - o.z}; }
    D3 operator*(double s) const { return {x * s, y * s, z * s}; }
    double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    Vec3 to_float() const { return {float(x), float(y), float(z)}; }
};
inline double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// Affine map as a row-major 3x4 matrix (the implied last row is 0 0 0 1).
struct Affine {
    double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

    static Affine from(const Transform& t);
    D3 point(D3 p) const {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    D3 vector(D3 v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    // Multiplies by the transpose of the 3x3 part: with the inverse map, this transforms normals.
    D3 transpose_vector(D3 v) const {
        return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z, m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
                m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
    }
    Affine operator*(const Affine& o) const;
    double determinant() const;
    // Inverse; returns false when the 3x3 part is singular.
    bool inverse(Affine& out) const;
    // Infinity norm of the 3x3 part (max absolute row sum).
    double norm() const;
};

// A hit in canonical space: `part` says which surface piece (side, cap) was hit.
struct CanonicalHit {
    double t = 0;
    D3 p;
    int part = 0;
};

enum Part { kSide = 0, kCapTop = 1, kCapBottom = 2 };

struct Analytic {
    scene::Shape::Kind kind = scene::Shape::Kind::Sphere;
    double radius = 1, inner = 0, height = 1;
    bool capped = true;
    // A partial sphere (scene::Shape::partial): hits outside z_min <= z <= z_max or beyond phi_max
    // are rejected; theta_z_min/max = acos(z_min/max / radius) for pbrt's v.
    bool partial = false;
    double z_min = 0, z_max = 0, phi_max = 0, theta_z_min = 0, theta_z_max = 0;
    bool pbrt_uv = false;  // a full sphere's v = 1 - theta / pi (scene::Shape::pbrt_uv)
    Affine to_space;       // canonical frame -> the geometry's space (world, or the object's space)
    Affine to_canon;       // inverse of to_space
    bool flip = false;     // reverse_orientation XOR the shape transform swaps handedness (pbrt)
    double size = 0;       // rough extent in the geometry's space, for the error bound
    int shape = -1;        // index of the shape (in Scene::shapes or in its Object)
    const scene::Shape* source = nullptr;
};

// Builds the canonical description of an analytic shape; returns false (with `why`) if it is
// degenerate (zero radius or height, zero axis, singular transform).
bool make_analytic(const scene::Shape& shape, int index, Analytic& out, const char*& why);

// Closest hit of o + t d with t in (tmin, tmax) in canonical space.
bool intersect_canonical(const Analytic& a, D3 o, D3 d, double tmin, double tmax, CanonicalHit& hit);

// Tight axis-aligned bounds of the shape in the geometry's space.
void analytic_bounds(const Analytic& a, D3& lo, D3& hi);

// Surface geometry at a canonical hit, in the geometry's space: the point (re-projected onto the
// surface), the unit outward normal (flipped by `flip`), a unit tangent along u, and the uv.
// On capped cylinders and cones the point is kept `inset` (canonical units, about the spawn
// offset) away from the rim where cap and side meet: a point a rounding error beyond the rim
// would spawn rays outside the neighbouring piece, which then escape the closed shape.
struct AnalyticSurface {
    D3 p, n, dpdu;
    Vec2 uv;
};
AnalyticSurface analytic_surface(const Analytic& a, const CanonicalHit& hit, double inset);

}  // namespace phos::accel::detail
