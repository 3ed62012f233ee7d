// Tests of shading/light_media.h: a light without a declared medium sits where tracking from the
// camera reaches it (the smoke box whose only boundary is an interface quad across its open front),
// a declaration wins and is reported when tracking disagrees, points in different media are
// reported with the majority chosen, a transition emitter emits into the medium on each side, and
// medium_reached applies transitions only.
#include "shading/light_media.h"

#include <gtest/gtest.h>

#include "core/log.h"
#include "support/shapes.h"

namespace phos::shading {
namespace {

// A unit box x, y in [-1, 1], z in [-1, 1] of ordinary walls (no medium interface) whose open front
// z = +1 is closed by an interface quad: inside (-z side) fog (medium 0), outside vacuum. The
// camera is outside in front, in vacuum.
scene::Scene smoke_box() {
    scene::Scene s;
    scene::Material wall;
    wall.diffuse = Rgb(0.5f);
    scene::Material boundary;
    boundary.interface_only = true;
    s.materials = {wall, boundary};
    s.media.push_back(scene::Medium{});
    s.media[0].name = "smoke";
    s.media[0].sigma_s = Rgb(1.0f);
    const float a = 1;
    const auto wall_quad = [&](Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3) {
        scene::Shape q = testing::quad(p0, p1, p2, p3);
        q.material = 0;
        s.shapes.push_back(q);
    };
    wall_quad({-a, -a, -a}, {a, -a, -a}, {a, a, -a}, {-a, a, -a});                       // back
    wall_quad({-a, -a, -a}, {-a, -a, a}, {a, -a, a}, {a, -a, -a});                       // floor
    wall_quad({-a, a, -a}, {a, a, -a}, {a, a, a}, {-a, a, a});                           // ceiling
    wall_quad({-a, -a, -a}, {-a, a, -a}, {-a, a, a}, {-a, -a, a});                       // left
    wall_quad({a, -a, -a}, {a, -a, a}, {a, a, a}, {a, a, -a});                           // right
    scene::Shape front = testing::quad({-a, -a, a}, {a, -a, a}, {a, a, a}, {-a, a, a});  // normal +z
    front.material = 1;
    front.media = {0, -1};
    s.shapes.push_back(front);
    scene::Camera cam;
    cam.eye = Vec3(0, 0, 4);
    cam.forward = Vec3(0, 0, -1);
    s.camera = cam;
    return s;
}

// A ceiling light quad facing down over x in [x0, x1], z in [z0, z1] at height y.
int add_ceiling_light(scene::Scene& s, float x0, float x1, float z0, float z1, float y = 0.99f) {
    scene::Shape q = testing::quad({x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1});
    q.material = 0;
    return s.add_area_light(q, Rgb(1.0f));
}

int add_point_light(scene::Scene& s, Vec3 p) {
    scene::Light l;
    l.kind = scene::Light::Kind::Point;
    l.position = p;
    l.color = Rgb(1.0f);
    s.lights.push_back(l);
    return int(s.lights.size()) - 1;
}

struct Placed {
    std::vector<LightMedia> media;
    int warnings;
};

Placed place(const scene::Scene& s) {
    const accel::EmbreeScene accel(s);
    const LightSet lights(s, accel.bounds());
    log::set_quiet(true);
    const int before = log::warning_count();
    Placed p{place_lights_in_media(accel, lights, s.camera->eye, s.camera_medium), 0};
    p.warnings = log::warning_count() - before;
    log::set_quiet(false);
    return p;
}

TEST(LightMedia, MediumReachedAppliesTransitionsOnly) {
    const scene::Scene s = smoke_box();
    const accel::EmbreeScene accel(s);
    // Through the interface quad into the box (crossing no wall): smoke.
    EXPECT_EQ(medium_reached(accel, {0, 0, 4}, -1, {0, 0, 0}), 0);
    // Through a wall only (the box's side, from outside): walls are no transition, vacuum stays.
    EXPECT_EQ(medium_reached(accel, {3, 0, 0}, -1, {0, 0, 0}), -1);
    // In and out again through the front: vacuum.
    EXPECT_EQ(medium_reached(accel, {0, 0, 4}, -1, {0.5f, 0, 5}), -1);
    // Nothing crossed: the starting medium.
    EXPECT_EQ(medium_reached(accel, {0, 0, 0}, 0, {0.2f, 0.3f, 0.1f}), 0);
}

TEST(LightMedia, UndeclaredLightsSitWhereCameraTrackingReachesThem) {
    scene::Scene s = smoke_box();
    const int area = add_ceiling_light(s, -0.25f, 0.25f, -0.2f, 0.2f);
    const int point = add_point_light(s, {0.3f, 0.5f, -0.2f});
    const int outside = add_point_light(s, {0, 3, 3});
    const Placed p = place(s);
    EXPECT_EQ(p.media[size_t(area)].front, 0);
    EXPECT_EQ(p.media[size_t(area)].back, 0);
    EXPECT_EQ(p.media[size_t(point)].front, 0);
    EXPECT_EQ(p.media[size_t(outside)].front, -1);
    EXPECT_EQ(p.warnings, 0);
}

TEST(LightMedia, ADeclarationWinsAndADisagreementIsReported) {
    scene::Scene s = smoke_box();
    const int agrees = add_point_light(s, {0.3f, 0.5f, -0.2f});
    s.lights[size_t(agrees)].medium = 0;
    s.lights[size_t(agrees)].medium_declared = true;
    Placed p = place(s);
    EXPECT_EQ(p.media[size_t(agrees)].front, 0);
    EXPECT_EQ(p.warnings, 0);

    const int vacuum = add_point_light(s, {-0.3f, 0.5f, -0.2f});
    s.lights[size_t(vacuum)].medium_declared = true;  // declared in vacuum, inside the smoke
    p = place(s);
    EXPECT_EQ(p.media[size_t(vacuum)].front, -1);
    EXPECT_EQ(p.warnings, 1);
}

TEST(LightMedia, PointsInDifferentMediaAreReportedAndTheMajorityChosen) {
    scene::Scene s = smoke_box();
    // Three quarters of the light (z in [-1, 1]) inside the box, a quarter (z in [1, 1.667]) outside.
    const int light = add_ceiling_light(s, -0.25f, 0.25f, -1.0f + 1e-3f, 1.6667f, 0.5f);
    const Placed p = place(s);
    EXPECT_EQ(p.media[size_t(light)].front, 0);
    EXPECT_EQ(p.warnings, 1);
}

TEST(LightMedia, ATransitionEmitterEmitsIntoTheMediumOnEachSide) {
    scene::Scene s = smoke_box();
    s.media.push_back(s.media[0]);
    s.media[1].name = "milk";
    scene::Shape q = testing::quad({-0.2f, 0, -0.2f}, {0.2f, 0, -0.2f}, {0.2f, 0, 0.2f}, {-0.2f, 0, 0.2f});
    q.material = 0;
    q.media = {1, 0};  // inside (against the normal) milk, outside smoke
    const int light = s.add_area_light(q, Rgb(1.0f), /*two_sided=*/true);
    const accel::EmbreeScene accel(s);
    LightSet lights(s, accel.bounds());
    lights.set_media(place_lights_in_media(accel, lights, s.camera->eye, -1));
    int front = 0, back = 0;
    for (int i = 0; i < 64; ++i) {
        const LightLeSample e = lights[size_t(light)].sample_Le({0.5f, 0.5f}, {(i + 0.5f) / 64, 0.3f},
                                                                Wavelengths::visible(0.5f));
        const int m = lights.emission_medium(size_t(light), e);
        const bool along_normal = dot(e.ray.dir, Vec3(0, -1, 0)) > 0;  // the quad's normal is -y
        EXPECT_EQ(m, along_normal ? 0 : 1) << i;
        ++(along_normal ? front : back);
    }
    EXPECT_GT(front, 0);
    EXPECT_GT(back, 0);
    // The same sides as a ray crossing the quad sees them: along the normal into the outside.
    EXPECT_EQ(medium_reached(accel, {0, 0.5f, 0}, 1, {0, -0.5f, 0}), 0);
    EXPECT_EQ(medium_reached(accel, {0, -0.5f, 0}, 0, {0, 0.5f, 0}), 1);
}

TEST(LightMedia, LightsAreInVacuumUntilPlaced) {
    scene::Scene s = smoke_box();
    const int light = add_point_light(s, {0, 0, 0});
    const accel::EmbreeScene accel(s);
    const LightSet lights(s, accel.bounds());
    const LightLeSample e =
        lights[size_t(light)].sample_Le({0.5f, 0.5f}, {0.5f, 0.5f}, Wavelengths::visible(0.5f));
    EXPECT_EQ(lights.emission_medium(size_t(light), e), -1);
}

}  // namespace
}  // namespace phos::shading
