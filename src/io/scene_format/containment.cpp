// Point-in-object tests for the `.scene` loader: ray parity against mesh triangles (in double,
// along a direction no axis-aligned wall is parallel to) and distance for spheres.
#include "io/scene_format/containment.h"

#include <cmath>
#include <limits>

namespace phos::io::scene_format {

namespace {

struct D3 {
    double x, y, z;
};
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 d3(Vec3 v) { return {v.x, v.y, v.z}; }

// Moller-Trumbore: does the ray o + t d (t > 0) cross triangle (a, b, c)?
bool crosses(D3 o, D3 d, D3 a, D3 b, D3 c) {
    const D3 e1 = sub(b, a), e2 = sub(c, a), p = cross(d, e2);
    const double det = dot(e1, p);
    if (std::fabs(det) < 1e-300) return false;
    const double inv = 1 / det;
    const D3 s = sub(o, a);
    const double u = dot(s, p) * inv;
    if (u < 0 || u > 1) return false;
    const D3 q = cross(s, e1);
    const double v = dot(d, q) * inv;
    if (v < 0 || u + v > 1) return false;
    return dot(e2, q) * inv > 0;
}

double box_volume(const scene::Shape& s) {
    if (s.kind == scene::Shape::Kind::Sphere) {
        const double r = double(s.radius);
        return 8 * r * r * r;
    }
    Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const Vec3& p : s.mesh.positions) {
        const Vec3 w = s.to_world.point(p);
        lo = min(lo, w);
        hi = max(hi, w);
    }
    const Vec3 e = hi - lo;
    return double(e.x) * double(e.y) * double(e.z);
}

}  // namespace

bool contains(const scene::Shape& shape, Vec3 p) {
    if (shape.kind == scene::Shape::Kind::Sphere) return length(p - shape.center) < shape.radius;
    if (shape.kind != scene::Shape::Kind::Mesh) return false;
    const D3 o = d3(p), d{0.5773502691896258, 0.5801, 0.5745};  // slightly off the diagonal
    int crossings = 0;
    const auto& m = shape.mesh;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
        if (crosses(o, d, d3(shape.to_world.point(m.positions[m.indices[t]])),
                    d3(shape.to_world.point(m.positions[m.indices[t + 1]])),
                    d3(shape.to_world.point(m.positions[m.indices[t + 2]]))))
            ++crossings;
    return crossings % 2 == 1;
}

int innermost_container(const std::vector<scene::Shape>& shapes, const std::vector<int>& candidates, Vec3 p,
                        int skip) {
    int best = -1;
    double best_volume = std::numeric_limits<double>::infinity();
    for (int c : candidates) {
        if (c == skip || !contains(shapes[size_t(c)], p)) continue;
        const double v = box_volume(shapes[size_t(c)]);
        if (v < best_volume) best = c, best_volume = v;
    }
    return best;
}

Vec3 reference_point(const scene::Shape& shape) {
    if (shape.kind == scene::Shape::Kind::Sphere) return shape.center + Vec3(0, shape.radius, 0);
    return shape.mesh.positions.empty() ? Vec3(0.0f) : shape.to_world.point(shape.mesh.positions[0]);
}

}  // namespace phos::io::scene_format
