// Shape constructors shared by tests (analytic primitives, quads, tessellated spheres).
#pragma once

#include <cmath>

#include "scene/scene.h"

namespace phos::testing {

inline scene::Shape sphere(Vec3 c, float r, int material = 0) {
    scene::Shape s;
    s.kind = scene::Shape::Kind::Sphere;
    s.center = c;
    s.radius = r;
    s.material = material;
    return s;
}

inline scene::Shape box(Vec3 lo, Vec3 hi) {
    scene::Shape s;
    s.kind = scene::Shape::Kind::Box;
    s.box_min = lo;
    s.box_max = hi;
    return s;
}

inline scene::Shape disk(Vec3 c, Vec3 n, float r, float inner = 0) {
    scene::Shape s;
    s.kind = scene::Shape::Kind::Disk;
    s.center = c;
    s.normal = n;
    s.radius = r;
    s.inner_radius = inner;
    return s;
}

inline scene::Shape cylinder(Vec3 c, Vec3 axis, float r, float h, bool capped) {
    scene::Shape s;
    s.kind = scene::Shape::Kind::Cylinder;
    s.center = c;
    s.axis = axis;
    s.radius = r;
    s.height = h;
    s.capped = capped;
    return s;
}

inline scene::Shape cone(Vec3 c, Vec3 axis, float r, float h, bool capped = true) {
    scene::Shape s = cylinder(c, axis, r, h, capped);
    s.kind = scene::Shape::Kind::Cone;
    return s;
}

// A quad p0 p1 p2 p3 (counter-clockwise seen from the front) as two triangles.
inline scene::Shape quad(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3) {
    scene::Shape s;
    s.kind = scene::Shape::Kind::Mesh;
    s.mesh.positions = {p0, p1, p2, p3};
    s.mesh.indices = {0, 1, 2, 0, 2, 3};
    return s;
}

// A scene holding one default material and a 20 x 20 quad in the plane y = 0 facing +y (a floor
// that bounds whatever lies above it).
inline scene::Scene floor_scene() {
    scene::Scene s;
    s.materials.emplace_back();
    scene::Shape q = quad({-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10});
    q.material = 0;
    s.shapes.push_back(q);
    return s;
}

// A closed UV-sphere mesh (outward, counter-clockwise from outside), optionally with normals.
inline scene::Shape mesh_sphere(Vec3 c, float r, int nu, int nv, bool normals) {
    scene::Shape s;
    s.kind = scene::Shape::Kind::Mesh;
    auto& m = s.mesh;
    for (int j = 0; j <= nv; ++j) {
        const double th = M_PI * j / nv;
        for (int i = 0; i < nu; ++i) {
            const double ph = 2 * M_PI * i / nu;
            const Vec3 d(float(std::sin(th) * std::cos(ph)), float(std::cos(th)),
                         float(std::sin(th) * std::sin(ph)));
            m.positions.push_back(c + d * r);
            if (normals) m.normals.push_back(d);
        }
    }
    auto id = [&](int i, int j) { return uint32_t(j * nu + (i % nu)); };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            // Rows run from the top pole down and columns eastwards, so (i, j) -> (i+1, j) -> (i, j+1)
            // is counter-clockwise seen from outside.
            if (j > 0) m.indices.insert(m.indices.end(), {id(i, j), id(i + 1, j), id(i, j + 1)});
            if (j + 1 < nv) m.indices.insert(m.indices.end(), {id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return s;
}

}  // namespace phos::testing
