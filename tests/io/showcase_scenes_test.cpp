// The spectral showcase scenes of scenes/ load through io::load_scene without a warning and hold
// what their comments promise: the prism's and the gem's dispersive glass (pbrt-v4's named glasses
// in the .pbrt files, the .mat `glass` key in the .scene twins, which place the camera and the
// light as their .pbrt files do), and the blackbody-lit Cornell box's lights and measured metals.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/log.h"
#include "io/load_scene.h"
#include "spectrum/blackbody.h"
#include "spectrum/dispersion.h"
#include "spectrum/named_metals.h"

namespace phos::io {
namespace {

using scene::Light;

struct Loaded {
    scene::Scene scene;
    int warnings = 0;
};

Loaded load(const std::string& name) {
    log::set_quiet(true);
    const int before = log::warning_count();
    Loaded l{load_scene(std::string(PHOS_SOURCE_DIR) + "/scenes/" + name), 0};
    l.warnings = log::warning_count() - before;
    log::set_quiet(false);
    return l;
}

double n_d(const char* glass) {
    for (const spectrum::NamedGlass& g : spectrum::named_glasses())
        if (g.name == glass) return g.n_d;
    ADD_FAILURE() << glass;
    return 0;
}

// The one material with a dispersive index; its shape's triangle count in *triangles.
const scene::Material* dispersive(const scene::Scene& s, size_t* triangles) {
    const scene::Material* found = nullptr;
    for (const scene::Shape& sh : s.shapes) {
        const scene::Material& m = s.materials[size_t(sh.material)];
        if (!m.ior_spectrum) continue;
        EXPECT_EQ(found, nullptr) << "two dispersive shapes";
        found = &m;
        *triangles = sh.mesh.indices.size() / 3;
    }
    return found;
}

void expect_near(Vec3 a, Vec3 b, float tol) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tol) << "component " << i;
}

// The two forms see the scene from the same place with the same field of view (`degrees`).
void expect_same_view(const scene::Scene& pbrt, const scene::Scene& twin, float degrees) {
    ASSERT_TRUE(pbrt.camera && twin.camera);
    expect_near(pbrt.camera->eye, twin.camera->eye, 1e-5f);
    expect_near(normalize(pbrt.camera->forward), normalize(twin.camera->forward), 1e-5f);
    EXPECT_NEAR(pbrt.camera->fov, degrees * kPi / 180, 1e-5f);
    EXPECT_NEAR(twin.camera->fov, degrees * kPi / 180, 1e-5f);
    EXPECT_EQ(pbrt.settings.width, twin.settings.width);
    EXPECT_EQ(pbrt.settings.height, twin.settings.height);
}

TEST(ShowcaseScenes, PrismOfDenseFlintGlass) {
    const Loaded p = load("prism.pbrt");
    EXPECT_EQ(p.warnings, 0);
    size_t triangles = 0;
    const scene::Material* glass = dispersive(p.scene, &triangles);
    ASSERT_NE(glass, nullptr);
    EXPECT_EQ(triangles, 8u);
    EXPECT_NEAR(glass->ior, n_d("glass-F10"), 1e-4);
    // Dense flint: blue bends clearly more than red.
    EXPECT_GT((*glass->ior_spectrum)(450) - (*glass->ior_spectrum)(650), 0.03f);
    // The spot: white (D65) of luminance 60, in a narrow cone.
    const Light* spot = nullptr;
    for (const Light& l : p.scene.lights)
        if (l.kind == Light::Kind::Spot) spot = &l;
    ASSERT_NE(spot, nullptr);
    ASSERT_TRUE(spot->spectrum.has_value());
    EXPECT_NEAR(spot->spectrum->xyz().y, 60.0f, 1e-2f);
    EXPECT_LT(spot->cutoff, 1.0f * kPi / 180);
    EXPECT_EQ(p.scene.settings.integrator, "sppm");

    const Loaded s = load("prism.scene");
    EXPECT_EQ(s.warnings, 0);
    const scene::Material* twin = dispersive(s.scene, &triangles);
    ASSERT_NE(twin, nullptr);
    EXPECT_EQ(triangles, 8u);
    EXPECT_NEAR(twin->ior, glass->ior, 1e-6);
    EXPECT_FLOAT_EQ((*twin->ior_spectrum)(450), (*glass->ior_spectrum)(450));
    // The point light in its slit box sits where the spot is.
    ASSERT_EQ(s.scene.lights.size(), 2u);  // the point light and the sky
    const Light& point = s.scene.lights[0].kind == Light::Kind::Point ? s.scene.lights[0] : s.scene.lights[1];
    EXPECT_EQ(point.kind, Light::Kind::Point);
    expect_near(point.position, spot->position, 1e-5f);
    expect_same_view(p.scene, s.scene, 48);
}

TEST(ShowcaseScenes, GemOfLanthanumFlintGlass) {
    const Loaded p = load("gem.pbrt");
    EXPECT_EQ(p.warnings, 0);
    size_t triangles = 0;
    const scene::Material* glass = dispersive(p.scene, &triangles);
    ASSERT_NE(glass, nullptr);
    EXPECT_EQ(triangles, 46u);
    EXPECT_NEAR(glass->ior, n_d("glass-LASF9"), 1e-4);
    ASSERT_EQ(p.scene.lights.size(), 1u);
    ASSERT_TRUE(p.scene.lights[0].spectrum.has_value());
    EXPECT_NEAR(p.scene.lights[0].spectrum->xyz().y, 5.0f, 1e-3f);

    const Loaded s = load("gem.scene");
    EXPECT_EQ(s.warnings, 0);
    const scene::Material* twin = dispersive(s.scene, &triangles);
    ASSERT_NE(twin, nullptr);
    EXPECT_EQ(triangles, 46u);
    EXPECT_NEAR(twin->ior, glass->ior, 1e-6);
    ASSERT_EQ(s.scene.lights.size(), 1u);
    expect_near(s.scene.lights[0].position, p.scene.lights[0].position, 1e-5f);
    // Flux 62.8 W: the .pbrt light's intensity 5 W/sr.
    EXPECT_NEAR(s.scene.lights[0].color.g, 5.0f, 1e-3f);
    expect_same_view(p.scene, s.scene, 40);
}

TEST(ShowcaseScenes, CornellBoxUnderTwoBlackbodies) {
    const Loaded p = load("cornell-blackbody.pbrt");
    EXPECT_EQ(p.warnings, 0);
    std::vector<const Light*> area;
    for (const Light& l : p.scene.lights)
        if (l.kind == Light::Kind::Area) area.push_back(&l);
    ASSERT_EQ(area.size(), 2u);
    const float kelvin[2] = {2700, 6500};
    for (size_t i = 0; i < 2; ++i) {
        ASSERT_TRUE(area[i]->spectrum.has_value());
        const spectrum::Distribution& L = *area[i]->spectrum;
        EXPECT_NEAR(L.xyz().y, 12.0f, 1e-3f);
        const spectrum::Blackbody planck(kelvin[i]);
        EXPECT_NEAR(L(450) / L(650), planck(450) / planck(650), 1e-4f);
        const Rgb c = L.srgb();
        EXPECT_NEAR(c.r, area[i]->color.r, 1e-2f);
        EXPECT_NEAR(c.b, area[i]->color.b, 1e-2f);
    }
    EXPECT_GT(area[0]->color.r, 2 * area[0]->color.b);          // 2700 K: warm
    EXPECT_NEAR(area[1]->color.r / area[1]->color.b, 1, 0.1f);  // 6500 K: nearly the sRGB white
    // The gold and the copper sphere: smooth conductors with the measured eta and k.
    int gold = 0, copper = 0;
    for (const scene::Shape& sh : p.scene.shapes) {
        const scene::Material& m = p.scene.materials[size_t(sh.material)];
        if (!m.conductor) continue;
        ASSERT_TRUE(m.conductor_eta_spectrum && m.conductor_k_spectrum);
        EXPECT_TRUE(m.microfacet);  // smooth: roughness 0
        EXPECT_EQ(m.roughness_u, 0.0f);
        EXPECT_EQ(m.roughness_v, 0.0f);
        const auto is = [&](const char* metal) {
            const auto t = spectrum::named_metal(metal);
            for (float lambda : {450.0f, 550.0f, 650.0f})
                if ((*m.conductor_eta_spectrum)(lambda) != t->eta(lambda) ||
                    (*m.conductor_k_spectrum)(lambda) != t->k(lambda))
                    return false;
            return true;
        };
        gold += is("Au");
        copper += is("Cu");
    }
    EXPECT_EQ(gold, 1);
    EXPECT_EQ(copper, 1);
}

// The material gallery: every sphere's material as pbrt-v4 defines it, without a warning.
TEST(ShowcaseScenes, MaterialGalleryHasEachMaterialAsPbrtDefinesIt) {
    const Loaded g = load("material-gallery.pbrt");
    EXPECT_EQ(g.warnings, 0);
    std::vector<const scene::Material*> spheres;
    for (const scene::Shape& sh : g.scene.shapes)
        if (sh.kind == scene::Shape::Kind::Sphere) spheres.push_back(&g.scene.materials[size_t(sh.material)]);
    ASSERT_EQ(spheres.size(), 8u);
    EXPECT_TRUE(spheres[0]->conductor && spheres[0]->microfacet);  // rough gold
    EXPECT_FLOAT_EQ(spheres[0]->roughness_u, 0.05f);
    EXPECT_NE(spheres[1]->roughness_u, spheres[1]->roughness_v);                   // anisotropic copper
    EXPECT_TRUE(spheres[2]->layered && !spheres[2]->layered_conductor_base);       // coated diffuse
    EXPECT_TRUE(spheres[3]->layered && spheres[3]->layered_conductor_base);        // coated silver
    EXPECT_TRUE(spheres[4]->microfacet && spheres[4]->transmission == Rgb(1.0f));  // rough glass
    EXPECT_TRUE(spheres[5]->is_mix());
    EXPECT_GE(spheres[6]->displacement_texture, 0);  // bump-mapped
    EXPECT_GE(spheres[7]->subsurface_medium, 0);     // ketchup
    EXPECT_EQ(g.scene.lights.size(), 2u);            // the sky and the area light
}

}  // namespace
}  // namespace phos::io
