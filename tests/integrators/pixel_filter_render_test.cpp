// The pixel filter in rendered images: a camera looks at a large emitter whose edge falls exactly
// on a pixel boundary, so each pixel's value is the share of its filter on the lit side,
// ∫_{edge - c}^{r} f1 / ∫ f1, a closed form of the filter's 1D profile (integrated here by
// quadrature of pbrt-v4's formula). Path tracing (camera samples placed by filter importance
// sampling) and bdpt (where light tracing's splats are shared out by the filter too) must both
// draw that profile, Mitchell's negative lobe included.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/stats.h"
#include "film/film.h"
#include "integrators/registry.h"
#include "render/prepared.h"

namespace phos::integrators {
namespace {

constexpr int kWidth = 16, kHeight = 8;

scene::Scene half_lit(const scene::PixelFilter& filter) {
    scene::Scene s;
    s.materials.emplace_back();
    scene::Shape quad;
    quad.kind = scene::Shape::Kind::Mesh;
    // x >= 0 on the plane z = -1, facing the camera: its left edge is the image's middle column
    // boundary; the others are far outside the view.
    quad.mesh.positions = {{0, -20, -1}, {20, -20, -1}, {20, 20, -1}, {0, 20, -1}};
    quad.mesh.indices = {0, 1, 2, 0, 2, 3};
    s.add_area_light(quad, Rgb(1.0f));
    scene::Camera cam;
    cam.forward = Vec3(0, 0, -1);
    cam.fov = 0.5f;
    s.camera = cam;
    s.pixel_filter = filter;
    return s;
}

Image render(IntegratorKind kind, const scene::Scene& s, int spp, const IntegratorConfig& config = {}) {
    RenderOptions opt;
    opt.width = kWidth;
    opt.height = kHeight;
    opt.spp = spp;
    opt.seed = 5;
    Stats stats;
    Prepared prepared(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    make_integrator(kind, config)->render(prepared, film, progress);
    return film.image();
}

// The lit share of pixel x's filter: ∫ f1(t) over t >= kWidth/2 - (x + 1/2), over ∫ f1.
double lit_share(const std::function<double(double)>& f1, double radius, int x) {
    const int n = 20000;
    const double h = 2 * radius / n, edge = kWidth / 2.0 - (x + 0.5);
    double lit = 0, all = 0;
    for (int i = 0; i < n; ++i) {
        const double t = -radius + (i + 0.5) * h;
        all += f1(t);
        if (t >= edge) lit += f1(t);
    }
    return lit / all;
}

void expect_profile(IntegratorKind kind, const scene::PixelFilter& filter,
                    const std::function<double(double)>& f1, int spp, double tolerance,
                    const IntegratorConfig& config = {}) {
    const Image img = render(kind, half_lit(filter), spp, config);
    const auto column = [&](int x) {
        double mean = 0;
        for (int y = 0; y < kHeight; ++y) mean += img.at(x, y).average() / kHeight;
        return mean;
    };
    const double white = column(kWidth - 1);  // entirely lit: the emitter's white as rendered
    EXPECT_NEAR(white, 1.0, 0.01);
    for (int x = 0; x < kWidth; ++x)
        EXPECT_NEAR(column(x) / white, lit_share(f1, filter.radius.x, x), tolerance) << "column " << x;
}

scene::PixelFilter gaussian() {
    scene::PixelFilter f;
    f.kind = scene::PixelFilter::Kind::Gaussian;
    f.radius = {1.5f, 1.5f};
    return f;
}

double gaussian_1d(double t) {  // pbrt-v4's Gaussian, sigma 0.5 and radius 1.5, up to a constant
    return std::max(0.0, std::exp(-t * t / 0.5) - std::exp(-1.5 * 1.5 / 0.5));
}

scene::PixelFilter mitchell() {
    scene::PixelFilter f;
    f.kind = scene::PixelFilter::Kind::Mitchell;
    f.radius = {2.0f, 2.0f};
    return f;
}

double mitchell_1d(double t) {  // Mitchell & Netravali's cubic, B = C = 1/3, radius 2
    const double x = std::fabs(t), B = 1.0 / 3, C = 1.0 / 3;
    if (x <= 1) return (12 - 9 * B - 6 * C) * x * x * x + (-18 + 12 * B + 6 * C) * x * x + (6 - 2 * B);
    if (x <= 2)
        return (-B - 6 * C) * x * x * x + (6 * B + 30 * C) * x * x + (-12 * B - 48 * C) * x +
               (8 * B + 24 * C);
    return 0;
}

TEST(PixelFilterRender, PathTracingDrawsTheGaussiansEdgeProfile) {
    expect_profile(IntegratorKind::Path, gaussian(), gaussian_1d, 1024, 0.01);
}

TEST(PixelFilterRender, PathTracingDrawsMitchellsRinging) {
    const scene::PixelFilter f = mitchell();
    // The negative lobe makes the last dark pixel before the edge negative.
    EXPECT_LT(lit_share(mitchell_1d, 2.0, kWidth / 2 - 2), -0.005);
    expect_profile(IntegratorKind::Path, f, mitchell_1d, 4096, 0.005);
}

TEST(PixelFilterRender, BdptSplatsFollowTheFilter) {
    expect_profile(IntegratorKind::Bdpt, gaussian(), gaussian_1d, 256, 0.015);
    // Light tracing alone (vcm's "lt" mode): every pixel's value comes from splats.
    IntegratorConfig lt;
    lt.progressive.vcm_mode = VcmMode::Lt;
    expect_profile(IntegratorKind::Vcm, gaussian(), gaussian_1d, 256, 0.03, lt);
}

TEST(PixelFilterRender, TheBoxKeepsTheEdgeSharp) {
    scene::PixelFilter box;
    // Dark pixels exactly dark; lit ones white up to the spectral sampling's colour noise.
    expect_profile(
        IntegratorKind::Path, box, [](double t) { return std::fabs(t) <= 0.5 ? 1.0 : 0.0; }, 64, 1e-3);
    const Image img = render(IntegratorKind::Path, half_lit(box), 16);
    for (int y = 0; y < kHeight; ++y) EXPECT_EQ(img.at(kWidth / 2 - 1, y), Rgb(0.0f));
}

}  // namespace
}  // namespace phos::integrators
