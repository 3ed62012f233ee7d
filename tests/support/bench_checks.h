// Checks shared by the loader tests of every format on the bench scenes (../shared/bench): both
// formats must describe the same Cornell-box light.
#pragma once

#include <gtest/gtest.h>

#include "scene/scene.h"

namespace phos::testing {

inline float mesh_area(const scene::TriangleMesh& m) {
    float a = 0;
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        const Vec3 p0 = m.positions[m.indices[3 * t]], p1 = m.positions[m.indices[3 * t + 1]],
                   p2 = m.positions[m.indices[3 * t + 2]];
        a += 0.5f * length(cross(p1 - p0, p2 - p0));
    }
    return a;
}

// The Cornell light: one area light of radiance 15, area 0.05, one-sided, facing -y.
inline void check_cornell_light(const scene::Scene& s) {
    ASSERT_EQ(s.lights.size(), 1u);
    const scene::Light& l = s.lights[0];
    EXPECT_EQ(l.kind, scene::Light::Kind::Area);
    EXPECT_EQ(l.color, Rgb(15.0f));
    EXPECT_FALSE(l.two_sided);
    ASSERT_GE(l.shape, 0);
    const scene::Shape& e = s.shapes[size_t(l.shape)];
    EXPECT_EQ(e.area_light, 0);
    ASSERT_EQ(e.kind, scene::Shape::Kind::Mesh);
    EXPECT_NEAR(mesh_area(e.mesh), 0.05f, 1e-6f);
    EXPECT_EQ(s.materials[size_t(e.material)].diffuse, Rgb(0.0f));
    // winding normal of every emitter triangle faces -y (pbrt orients by N)
    for (size_t t = 0; t < e.mesh.triangle_count(); ++t) {
        const Vec3 p0 = e.mesh.positions[e.mesh.indices[3 * t]],
                   p1 = e.mesh.positions[e.mesh.indices[3 * t + 1]],
                   p2 = e.mesh.positions[e.mesh.indices[3 * t + 2]];
        EXPECT_LT(cross(p1 - p0, p2 - p0).y, 0.0f);
        EXPECT_NEAR(p0.y, 0.998f, 1e-6f);
    }
}

}  // namespace phos::testing
