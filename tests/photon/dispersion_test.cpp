// Dispersion through a traced photon: parallel light crosses a 60-degree prism of SF10 glass and
// lands on a floor. A photon that refracted in and out (two specular bounces) has kept its hero
// wavelength alone, and leaves in the direction Snell's law gives at that wavelength: the
// deviation delta = theta1 + theta4 - A with sin theta2 = sin theta1 / n(lambda), theta3 = A -
// theta2, sin theta4 = n(lambda) sin theta3. Red bends least, violet most.
#include "spectrum/dispersion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "accel/embree_scene.h"
#include "photon/photon_path.h"
#include "shading/lights.h"
#include "shading/material_bsdfs.h"
#include "spectrum/distribution.h"
#include "support/shapes.h"

namespace phos::photon {
namespace {

constexpr double kApex = M_PI / 3;       // the prism's apex angle
constexpr double kIncidence = M_PI / 3;  // theta1 at the first face

// The deviation a ray of index n takes through the prism at kIncidence.
double deviation(double n) {
    const double t2 = std::asin(std::sin(kIncidence) / n);
    const double t4 = std::asin(n * std::sin(kApex - t2));
    return kIncidence + t4 - kApex;
}

// An equilateral prism (edge 1) along z over [-1, 1], its base on y = 0, closed, outward faces.
scene::Shape prism(int material) {
    const float h = float(std::sqrt(3.0) / 2);
    scene::Shape s;
    s.kind = scene::Shape::Kind::Mesh;
    s.mesh.positions = {{-0.5f, 0, -1}, {0.5f, 0, -1}, {0, h, -1}, {-0.5f, 0, 1}, {0.5f, 0, 1}, {0, h, 1}};
    // back (z = -1), front (z = 1), base, left face, right face.
    s.mesh.indices = {0, 2, 1, 3, 4, 5, 0, 1, 4, 0, 4, 3, 0, 3, 5, 0, 5, 2, 1, 2, 5, 1, 5, 4};
    s.material = material;
    return s;
}

TEST(Dispersion, APrismBendsEachPhotonAtItsHeroWavelengthBySnellsLaw) {
    scene::Scene s;
    s.materials.resize(2);
    s.materials[0].diffuse = Rgb(0.5f);  // the floor
    scene::Material& glass = s.materials[1];
    glass.transmission = Rgb(1.0f);
    const spectrum::Sellmeier sf10 = *spectrum::named_glass("glass-SF10");
    glass.ior_spectrum = spectrum::Distribution::sellmeier(sf10);
    glass.ior = float(sf10.ior(spectrum::kLineD));
    scene::Shape floor = testing::quad({-4, -3, -2}, {-4, -3, 2}, {8, -3, 2}, {8, -3, -2});
    floor.material = 0;
    s.shapes.push_back(floor);
    s.shapes.push_back(prism(1));
    // Parallel light travelling up and to the right at 30 degrees: 60 degrees from the left face's
    // normal (-sqrt(3)/2, 1/2, 0).
    const Vec3 d(float(std::cos(M_PI / 6)), float(std::sin(M_PI / 6)), 0);
    scene::Light sun;
    sun.kind = scene::Light::Kind::Directional;
    sun.direction = d;
    sun.color = Rgb(1.0f);
    s.lights.push_back(sun);

    const accel::EmbreeScene accel(s);
    const shading::LightSet lights(s, accel.bounds());
    const shading::MaterialBsdfs bsdfs(s, {});
    const PhotonScene ps{s, accel, lights, bsdfs};
    int through = 0;
    double worst = 0, shortest = 1e9, longest = 0, least = 0, most = 0;
    for (uint64_t i = 0; i < 400000; ++i) {
        trace_photon(ps, 3, 0, i, {}, [&](const PhotonHit& h) {
            if (h.bounces != 2 || !h.after_specular) return false;
            ++through;
            // Only the hero carries power, and the wavelengths say so.
            EXPECT_TRUE(h.lambda.secondary_terminated());
            for (int k = 1; k < spectrum::kSpectrumSamples; ++k) EXPECT_EQ(h.power[k], 0.0f);
            const double lambda = h.lambda[0];
            const Vec3 e = -h.wi;  // the direction the photon travelled in
            const double measured = std::atan2(d.y, d.x) - std::atan2(e.y, e.x);
            worst = std::max(worst, std::fabs(measured - deviation(sf10.ior(lambda))));
            EXPECT_NEAR(e.z, 0.0f, 1e-5f);
            if (lambda < shortest) shortest = lambda, most = measured;
            if (lambda > longest) longest = lambda, least = measured;
            return false;
        });
    }
    // About 1/30 of the emission disk's photons cross the prism.
    EXPECT_GT(through, 2000);
    EXPECT_LT(worst, 2e-5);  // float directions
    // The spread: violet (shortest) deviates more than red (longest), by about 4 degrees for SF10.
    EXPECT_LT(shortest, 420.0);
    EXPECT_GT(longest, 700.0);
    EXPECT_GT(most - least, 0.05);
    EXPECT_NEAR(most - least, deviation(sf10.ior(shortest)) - deviation(sf10.ior(longest)), 1e-4);
}

}  // namespace
}  // namespace phos::photon
