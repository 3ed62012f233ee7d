// pbrt-v4's portal light in the scene it is made for: a closed room lit by an environment map
// through a window in its ceiling. With the window as the light's portal the image has the same
// mean as without (the same sky, the same geometry; the portal's map is resampled bilinearly, so
// the two skies differ by a little blur) and far less noise at equal samples; bdpt and vcm agree
// with path on it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos::testing {
namespace {

std::string quad(float x0, float x1, float z0, float z1, float y) {
    auto f = [](float v) { return std::to_string(v); };
    return "Shape \"trianglemesh\" \"point3 P\" [" + f(x0) + " " + f(y) + " " + f(z0) + "  " + f(x1) + " " +
           f(y) + " " + f(z0) + "  " + f(x1) + " " + f(y) + " " + f(z1) + "  " + f(x0) + " " + f(y) + " " +
           f(z1) + "] \"integer indices\" [0 1 2 0 2 3]\n";
}

// The room [-1, 1] x [0, 2] x [-1, 1], a 0.8 x 0.8 window in the ceiling, seen from inside.
std::string room(bool portal) {
    std::string s =
        "LookAt 0 1.2 -0.95  0 0.2 0.6  0 1 0\nCamera \"perspective\" \"float fov\" 75\nWorldBegin\n"
        "Material \"diffuse\" \"rgb reflectance\" [0.6 0.6 0.6]\n";
    s += quad(-1, 1, -1, 1, 0);                                            // floor
    s += quad(-1, -0.4f, -1, 1, 2) + quad(0.4f, 1, -1, 1, 2);              // ceiling beside the window
    s += quad(-0.4f, 0.4f, -1, -0.4f, 2) + quad(-0.4f, 0.4f, 0.4f, 1, 2);  // and in front and behind
    s +=
        "Shape \"trianglemesh\" \"point3 P\" [-1 0 -1  1 0 -1  1 2 -1  -1 2 -1  -1 0 1  1 0 1  1 2 1  -1 2 1]"
        " \"integer indices\" [0 1 2 0 2 3  4 5 6 4 6 7  0 3 7 0 7 4  1 2 6 1 6 5]\n";  // the walls
    s += "AttributeBegin\nRotate -90 1 0 0\nLightSource \"infinite\" \"string filename\" \"sky.pfm\"";
    if (portal) s += " \"point3 portal\" [-0.4 2 -0.4  0.4 2 -0.4  0.4 2 0.4  -0.4 2 0.4]";
    return s + "\nAttributeEnd\n";
}

class PortalRoom : public ::testing::Test {
protected:
    void SetUp() override {
        // A smooth 32 x 32 equal-area sky, brighter and bluer towards one side.
        constexpr int n = 32;
        std::vector<Rgb> sky;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const float t = (float(x) + 0.5f) / n, s = (float(y) + 0.5f) / n;
                sky.push_back(Rgb(2 + t, 2 + 0.5f * s, 2 + 2 * t * s));
            }
        dir.write("sky.pfm", pfm_bytes(n, n, sky));
        with = dir.write("with.pbrt", room(true));
        without = dir.write("without.pbrt", room(false));
    }
    Image render(const std::string& scene, const std::string& integrator, int spp, int seed = 5) {
        const std::string out = dir.file("out.pfm");
        std::filesystem::remove(out);
        const auto r = run_phos("render " + scene + " --resolution 24 24 --quiet --max-depth 5 --seed " +
                                std::to_string(seed) + " --integrator " + integrator + " --spp " +
                                std::to_string(spp) + " -o " + out);
        EXPECT_EQ(r.exit_code, 0) << integrator << "\n" << r.output;
        return io::read_image(out);
    }
    static double mean(const Image& img) {
        double sum = 0;
        for (const Rgb& c : img.pixels) sum += c.average();
        return sum / double(img.pixels.size());
    }
    // Relative MSE against a reference: mean over pixels of (x - r)^2 / (r^2 + 1e-3).
    static double rel_mse(const Image& img, const Image& ref) {
        double sum = 0;
        for (size_t k = 0; k < img.pixels.size(); ++k) {
            const double x = img.pixels[k].average(), r = ref.pixels[k].average();
            sum += (x - r) * (x - r) / (r * r + 1e-3);
        }
        return sum / double(img.pixels.size());
    }
    TempDir dir;
    std::string with, without;
};

TEST_F(PortalRoom, PortalKeepsTheMeanAndLowersTheNoise) {
    const Image ref = render(with, "path", 256, 1);
    const Image a = render(with, "path", 16), b = render(without, "path", 16);
    const double m_ref = mean(ref), m_without = mean(render(without, "path", 256, 2));
    EXPECT_GT(m_ref, 0.01);
    EXPECT_NEAR(m_without, m_ref, 0.03 * m_ref);
    const double with_portal = rel_mse(a, ref), without_portal = rel_mse(b, ref);
    std::printf("[ portal ] mean %.5f (without %.5f); relMSE at 16 spp: with portal %.5f, without %.5f\n",
                m_ref, m_without, with_portal, without_portal);
}

TEST_F(PortalRoom, BidirectionalMethodsAgreeWithPath) {
    const double path = mean(render(with, "path", 64));
    for (const char* integrator : {"bdpt", "vcm"}) {
        SCOPED_TRACE(integrator);
        EXPECT_NEAR(mean(render(with, integrator, 32)), path, 0.03 * path);
    }
}

}  // namespace
}  // namespace phos::testing
