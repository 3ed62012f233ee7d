// Volume photons reach only the volume points of their own medium (sppm_core.h, PhotonAccumulator):
// where two media meet (murky glass standing in smoke), a point's ball reaches across the boundary,
// and counting the other medium's photons there read ppm 1.41 and sppm 1.23 of the reference at a
// block of the agreement matrix's smoke-murky-sky row. Here a box of scattering smoke (medium 0)
// is lit by a point light inside it, and two volume points sit at the same place with the same
// radius, one labelled smoke and one labelled medium 1 (a second medium that no photon scatters
// in): after photon passes the smoke point holds photons and flux, the other none.
#include <gtest/gtest.h>

#include <vector>

#include "core/stats.h"
#include "integrators/eye_path.h"
#include "integrators/sppm_core.h"
#include "photon/hitpoint_grid.h"
#include "render/prepared.h"
#include "support/shapes.h"

namespace phos::integrators {
namespace {

scene::Scene smoke_box() {
    scene::Scene s;
    scene::Material wall;
    wall.diffuse = Rgb(0.5f);
    s.materials.push_back(wall);
    for (const float sigma_s : {1.0f, 0.5f}) {
        scene::Medium m;
        m.sigma_a = Rgb(0.1f);
        m.sigma_s = Rgb(sigma_s);
        s.media.push_back(m);
    }
    scene::Shape box = testing::box(Vec3(-1.0f), Vec3(1.0f));
    box.material = 0;
    box.media = {0, -1};  // smoke inside
    s.shapes.push_back(box);
    scene::Light light;
    light.kind = scene::Light::Kind::Point;
    light.position = Vec3(0.0f, 0.5f, 0.0f);
    light.color = Rgb(5.0f);
    light.medium = 0;
    s.lights.push_back(light);
    scene::Camera cam;
    cam.eye = Vec3(0.0f, 0.0f, 0.9f);
    cam.forward = Vec3(0, 0, -1);
    s.camera = cam;
    s.camera_medium = 0;
    return s;
}

TEST(SppmVolumeMedia, PhotonsReachOnlyTheVolumePointsOfTheirOwnMedium) {
    const scene::Scene s = smoke_box();
    render::RenderOptions opt;
    opt.width = opt.height = 4;
    Stats stats;
    const render::Prepared P(s, opt, {}, stats);
    std::vector<VisiblePoint> vps(2);
    for (int i = 0; i < 2; ++i) {
        vps[size_t(i)].p = Vec3(0.0f, -0.2f, 0.0f);
        vps[size_t(i)].wo = Vec3(0, 0, 1);
        vps[size_t(i)].beta = Spectrum(1.0f);
        vps[size_t(i)].lambda = Wavelengths::visible(0.5f);
        vps[size_t(i)].medium = i;  // 0: the smoke it sits in; 1: the other medium
    }
    std::vector<PixelStats> px(2);
    for (PixelStats& p : px) p.r2 = 0.3 * 0.3;
    sppm::PhotonAccumulator acc(vps.size());
    photon::HitPointGrid grid;
    for (uint64_t pass = 0; pass < 4; ++pass) {
        acc.photon_pass(P, vps, px, grid, 7, pass, 20000);
        acc.update(px, vps, 0.7f, {});
    }
    EXPECT_GT(px[0].n, 50.0) << "the smoke's own point gathers the smoke's photons";
    EXPECT_GT(px[0].tau[0], 0.0);
    EXPECT_EQ(px[1].n, 0.0) << "a point of another medium gathers none of them";
    EXPECT_EQ(px[1].tau[0], 0.0);
}

}  // namespace
}  // namespace phos::integrators
