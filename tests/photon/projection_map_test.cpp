// Projection maps (photon/projection_map.h): the caustic map they produce carries the same power,
// in the same place, as the one from full emission, for a point light and a rectangular area light,
// while far fewer photons are emitted; the marked fraction bounds the specular object's solid angle.
#include "photon/projection_map.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "accel/embree_scene.h"
#include "photon/tracer.h"
#include "scene/scene.h"
#include "shading/lights.h"

namespace phos::photon {
namespace {

// A glass sphere (radius 0.5, centre (0, 0.5, 0)) on a large white floor, lit by a point light of
// 100 W/sr at (0, 2.5, 0) or by a 0.4 x 0.4 area light facing down at the same height.
struct CausticScene {
    scene::Scene s;
    std::unique_ptr<accel::EmbreeScene> accel;
    std::unique_ptr<shading::LightSet> lights;
    std::unique_ptr<shading::MaterialBsdfs> bsdfs;
    explicit CausticScene(bool area) {
        scene::Material floor;
        floor.diffuse = Rgb(0.8f);
        s.materials.push_back(floor);
        scene::Material glass;
        glass.transmission = Rgb(1.0f);
        glass.ior = 1.5f;
        glass.transmission_shininess = 1e6f;
        s.materials.push_back(glass);
        scene::Shape f;
        f.kind = scene::Shape::Kind::Mesh;
        f.mesh.positions = {{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}};
        f.mesh.indices = {0, 1, 2, 0, 2, 3};
        f.material = 0;
        s.shapes.push_back(f);
        scene::Shape sp;
        sp.kind = scene::Shape::Kind::Sphere;
        sp.center = Vec3(0.0f, 0.5f, 0.0f);
        sp.radius = 0.5f;
        sp.material = 1;
        s.shapes.push_back(sp);
        if (area) {
            scene::Shape q;
            q.kind = scene::Shape::Kind::Mesh;
            // Counter-clockwise seen from below: the emitting normal faces -y.
            q.mesh.positions = {
                {-0.2f, 2.5f, -0.2f}, {0.2f, 2.5f, -0.2f}, {0.2f, 2.5f, 0.2f}, {-0.2f, 2.5f, 0.2f}};
            q.mesh.indices = {0, 1, 2, 0, 2, 3};
            q.material = 0;
            s.add_area_light(q, Rgb(100.0f), true);
        } else {
            scene::Light l;
            l.kind = scene::Light::Kind::Point;
            l.color = Rgb(100.0f);
            l.position = Vec3(0.0f, 2.5f, 0.0f);
            s.lights.push_back(l);
        }
        accel = std::make_unique<accel::EmbreeScene>(s);
        lights = std::make_unique<shading::LightSet>(s, accel->bounds());
        bsdfs = std::make_unique<shading::MaterialBsdfs>(s, shading::BsdfOptions{});
    }
    PhotonScene ps() const { return {s, *accel, *lights, *bsdfs}; }
};

// Total caustic power and the part within 0.15 of the caustic's centre (below the sphere).
struct CausticPower {
    double total = 0, core = 0;
    size_t photons = 0;
    uint64_t emitted = 0;
    double seconds = 0;
};

CausticPower caustic(const CausticScene& cs, bool projection, uint64_t target, uint64_t emit) {
    TraceOptions o;
    o.wanted[kGlobalMap] = false;
    o.wanted[kCausticMap] = true;
    o.target[kCausticMap] = target;
    o.emit = emit;
    o.seed = 7;
    o.caustic_projection = projection;
    const auto t0 = std::chrono::steady_clock::now();
    const TracedPhotons t = trace_photons(cs.ps(), o);
    CausticPower c;
    c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (const Photon& p : t.photons[kCausticMap]) {
        // Each photon's power as colour at its own wavelengths (a Monte Carlo estimate of the
        // light's RGB: relative variance ~0.034 per photon for this white light, next to the
        // emission counts' ~1 % noise on each total over > 10000 photons, negligible).
        const double v = p.colour().average();
        c.total += v;
        if (p.position.x * p.position.x + p.position.z * p.position.z < 0.15 * 0.15) c.core += v;
    }
    c.photons = t.photons[kCausticMap].size();
    c.emitted = t.emitted[kCausticMap];
    return c;
}

TEST(ProjectionMap, MarksAtLeastTheSpheresSolidAngleAndNotMuchMore) {
    const CausticScene cs(false);
    const ProjectionMap pm(cs.ps(), 128);
    // Sphere of radius 0.5 seen from 2 away: (1 - cos(asin(0.25))) / 2 of the sphere of directions.
    const double solid = (1 - std::cos(std::asin(0.25))) / 2;
    EXPECT_GE(pm.fraction(), solid);
    EXPECT_LE(pm.fraction(), 3 * solid);
    // Nothing specular: nothing marked.
    CausticScene plain(false);
    plain.s.materials[1] = plain.s.materials[0];
    EXPECT_TRUE(ProjectionMap(plain.ps()).empty());
}

void expect_same_caustic(bool area) {
    const CausticScene cs(area);
    const CausticPower full = caustic(cs, false, 0, 3000000);
    const CausticPower proj = caustic(cs, true, full.photons, 0);
    std::printf(
        "%s light: caustic power %.7f (full emission, %zu photons from %llu emitted, %.0f stored/s) vs "
        "%.7f (projection, %zu from %llu, %.0f stored/s); core %.4f vs %.4f\n",
        area ? "area" : "point", full.total, full.photons, (unsigned long long)full.emitted,
        double(full.photons) / full.seconds, proj.total, proj.photons, (unsigned long long)proj.emitted,
        double(proj.photons) / proj.seconds, full.core, proj.core);
    ASSERT_GT(full.photons, 10000u);
    // ~1 % relative noise on each total: 4 % is a > 3 sigma band.
    EXPECT_NEAR(proj.total / full.total, 1.0, 0.04);
    EXPECT_NEAR(proj.core / full.core, 1.0, 0.06);
    // The same photons from far fewer emissions.
    EXPECT_LT(double(proj.emitted), 0.25 * double(full.emitted));
}

TEST(ProjectionMap, PointLightCausticMatchesFullEmission) { expect_same_caustic(false); }
TEST(ProjectionMap, AreaLightCausticMatchesFullEmission) { expect_same_caustic(true); }

}  // namespace
}  // namespace phos::photon
