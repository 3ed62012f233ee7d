// The .pbrt, .scn and .scene versions of each bench scene describe the same scene: camera, light
// power, triangles (up to order and orientation), spheres and materials. The .scene twins live in
// bench/dissertation (written from the .scn twins in ../shared/bench/scn).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "core/log.h"
#include "io/pbrt/pbrt_loader.h"
#include "io/scene_format/scene_format_loader.h"
#include "io/scn/scn_loader.h"

namespace phos::io {
namespace {

const std::string kShared = PHOS_SHARED_DIR;

// A triangle as its sorted, rounded world-space corners (order- and orientation-free).
using TriKey = std::array<std::array<long, 3>, 3>;

TriKey key(Vec3 a, Vec3 b, Vec3 c) {
    TriKey k;
    const Vec3 v[3] = {a, b, c};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) k[size_t(i)][size_t(j)] = std::lround(double(v[i][j]) * 1e4);
    std::sort(k.begin(), k.end());
    return k;
}

// What a surface looks like, compared between formats (emitters are compared through the lights).
struct Look {
    Rgb diffuse, specular, transmission;
    float ior;
    bool mirror, sharp_glass;
};

// A delta lobe: a Phong exponent of kMirrorShininess or more (.scn), a microfacet alpha below
// 1e-3 (pbrt's materials, roughness remapped as they say).
bool smooth(const scene::Material& m, float exponent) {
    if (!m.microfacet) return exponent >= scene::Material::kMirrorShininess;
    const auto alpha = [&](float r) { return m.remap_roughness ? std::sqrt(r) : r; };
    return std::max(alpha(m.roughness_u), alpha(m.roughness_v)) < 1e-3f;
}

Look look(const scene::Material& m) {
    return {m.diffuse,
            m.specular,
            m.transmission,
            m.transmission.is_black() ? 1.0f : m.ior,
            !m.specular.is_black() && smooth(m, m.shininess),
            !m.transmission.is_black() && smooth(m, m.transmission_shininess)};
}

void expect_same_look(const Look& a, const Look& b, const std::string& what) {
    EXPECT_EQ(a.diffuse, b.diffuse) << what;
    EXPECT_EQ(a.specular, b.specular) << what;
    EXPECT_EQ(a.transmission, b.transmission) << what;
    EXPECT_FLOAT_EQ(a.ior, b.ior) << what;
    EXPECT_EQ(a.mirror, b.mirror) << what;
    EXPECT_EQ(a.sharp_glass, b.sharp_glass) << what;
}

Vec3 corner(const scene::Shape& sh, size_t t, int k) {
    return sh.to_world.point(sh.mesh.positions[sh.mesh.indices[3 * t + size_t(k)]]);
}

std::map<TriKey, int> triangles(const scene::Scene& s, bool emitters) {
    std::map<TriKey, int> out;  // triangle -> material index
    for (const scene::Shape& sh : s.shapes) {
        if (sh.kind != scene::Shape::Kind::Mesh || (sh.area_light >= 0) != emitters) continue;
        for (size_t t = 0; t < sh.mesh.triangle_count(); ++t)
            EXPECT_TRUE(
                out.emplace(key(corner(sh, t, 0), corner(sh, t, 1), corner(sh, t, 2)), sh.material).second)
                << "duplicate triangle";
    }
    return out;
}

struct Sphere {
    Vec3 c;
    float r;
    int material;
};
std::vector<Sphere> spheres(const scene::Scene& s) {
    std::vector<Sphere> out;
    for (const scene::Shape& sh : s.shapes)
        if (sh.kind == scene::Shape::Kind::Sphere) {
            const Transform& t = sh.to_world;
            out.push_back({t.point(sh.center), sh.radius * length(t.vector({1, 0, 0})), sh.material});
        }
    std::sort(out.begin(), out.end(), [](const Sphere& a, const Sphere& b) { return a.c.x < b.c.x; });
    return out;
}

// Total emitted flux per channel: pi * A * L for one-sided area lights, 4 pi I for point lights.
Rgb power(const scene::Scene& s) {
    Rgb sum(0.0f);
    for (const scene::Light& l : s.lights) {
        if (l.kind == scene::Light::Kind::Point) {
            sum += l.color * (4 * kPi);
        } else if (l.kind == scene::Light::Kind::Area) {
            const scene::Shape& sh = s.shapes[size_t(l.shape)];
            float area = 0;
            for (size_t t = 0; t < sh.mesh.triangle_count(); ++t)
                area += 0.5f * length(cross(corner(sh, t, 1) - corner(sh, t, 0),
                                            corner(sh, t, 2) - corner(sh, t, 0)));
            sum += l.color * (kPi * area * (l.two_sided ? 2.0f : 1.0f));
        } else {
            ADD_FAILURE() << "unexpected light kind in a bench scene";
        }
    }
    return sum;
}

void compare_scenes(const scene::Scene& p, const scene::Scene& s, const std::string& name) {
    // Camera
    ASSERT_TRUE(p.camera && s.camera);
    const scene::Camera &a = *p.camera, &b = *s.camera;
    const Vec3 f = normalize(a.forward);
    // up vectors compared after removing their component along forward
    const Vec3 ua = normalize(a.up - f * dot(a.up, f)), ub = normalize(b.up - f * dot(b.up, f));
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(a.eye[i], b.eye[i], 1e-4f) << name;
        EXPECT_NEAR(f[i], normalize(b.forward)[i], 1e-4f) << name;
        EXPECT_NEAR(ua[i], ub[i], 1e-4f) << name;
    }
    EXPECT_NEAR(a.fov, b.fov, 1e-4f) << name;
    EXPECT_EQ(a.flip_x, b.flip_x) << name;
    EXPECT_EQ(a.projection, b.projection) << name;

    // Lights
    ASSERT_EQ(p.lights.size(), s.lights.size()) << name;
    const Rgb pp = power(p), ps = power(s);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(pp[c], ps[c], 1e-4f * ps[c]) << name;
    for (size_t i = 0; i < p.lights.size(); ++i) {
        EXPECT_EQ(p.lights[i].kind, s.lights[i].kind) << name;
        EXPECT_EQ(p.lights[i].two_sided, s.lights[i].two_sided) << name;
        EXPECT_EQ(p.lights[i].color, s.lights[i].color) << name;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(p.lights[i].position[c], s.lights[i].position[c], 1e-5f) << name;
        if (p.lights[i].kind != scene::Light::Kind::Area) continue;
        // the emitters face the same way
        const scene::Shape &ep = p.shapes[size_t(p.lights[i].shape)],
                           &es = s.shapes[size_t(s.lights[i].shape)];
        for (size_t t = 0; t < 2; ++t) {
            const Vec3 np = cross(corner(ep, t, 1) - corner(ep, t, 0), corner(ep, t, 2) - corner(ep, t, 0));
            const Vec3 ns = cross(corner(es, t, 1) - corner(es, t, 0), corner(es, t, 2) - corner(es, t, 0));
            EXPECT_GT(dot(normalize(np), normalize(ns)), 0.999f) << name;
        }
    }

    // Triangles with their materials; emitters separately
    for (bool emitters : {false, true}) {
        const auto tp = triangles(p, emitters), ts = triangles(s, emitters);
        ASSERT_EQ(tp.size(), ts.size()) << name << (emitters ? " emitters" : " surfaces");
        if (!emitters) {
            EXPECT_GE(tp.size(), 2u) << name;
        }
        for (const auto& [k, m] : tp) {
            const auto it = ts.find(k);
            ASSERT_NE(it, ts.end()) << name << ": a pbrt triangle has no .scn twin";
            if (!emitters)
                expect_same_look(look(p.materials[size_t(m)]), look(s.materials[size_t(it->second)]), name);
        }
    }

    // Spheres
    const auto sp = spheres(p), ss = spheres(s);
    ASSERT_EQ(sp.size(), ss.size()) << name;
    for (size_t i = 0; i < sp.size(); ++i) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sp[i].c[c], ss[i].c[c], 1e-5f) << name;
        EXPECT_NEAR(sp[i].r, ss[i].r, 1e-6f) << name;
        expect_same_look(look(p.materials[size_t(sp[i].material)]), look(s.materials[size_t(ss[i].material)]),
                         name + " sphere");
    }
}

void compare(const std::string& name) {
    log::set_quiet(true);
    const scene::Scene p = load_pbrt(kShared + "/bench/scenes/" + name + ".pbrt");
    const scene::Scene s = load_scn(kShared + "/bench/scn/" + name + ".scn");
    log::set_quiet(false);
    compare_scenes(p, s, name);
}

// The .scene twin against the .scn twin (and so, through the test above, against pbrt).
void compare_scene_format(const std::string& name) {
    log::set_quiet(true);
    const scene::Scene d =
        load_scene_format(std::string(PHOS_SOURCE_DIR) + "/bench/dissertation/" + name + ".scene");
    const scene::Scene s = load_scn(kShared + "/bench/scn/" + name + ".scn");
    log::set_quiet(false);
    compare_scenes(d, s, name + " (.scene vs .scn)");
    EXPECT_TRUE(d.camera->fov_vertical);
    ASSERT_TRUE(d.settings.width && d.settings.height);
    EXPECT_EQ(*d.settings.width, 256);
    EXPECT_EQ(*d.settings.height, 256);
    // Shared .mat files are one material each (plus the area light's black emitter).
    EXPECT_EQ(d.materials.size(), s.materials.size()) << name;
}

TEST(SceneScnEquivalence, CornellDiffuse) { compare_scene_format("cornell-diffuse"); }
TEST(SceneScnEquivalence, CornellGlassMirror) { compare_scene_format("cornell-glass-mirror"); }
TEST(SceneScnEquivalence, CausticPoint) { compare_scene_format("caustic-point"); }

TEST(PbrtScnEquivalence, CornellDiffuse) { compare("cornell-diffuse"); }
TEST(PbrtScnEquivalence, CornellGlassMirror) { compare("cornell-glass-mirror"); }
TEST(PbrtScnEquivalence, CausticPoint) { compare("caustic-point"); }

}  // namespace
}  // namespace phos::io
