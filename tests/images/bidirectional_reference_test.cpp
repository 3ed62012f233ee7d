// bdpt and vcm against the independent references of ../shared/bench and against path tracing:
//  - bdpt at 64 samples per pixel on cornell-diffuse has at most path's error at 64 (issue 16's
//    goal; its connections and light tracing only add lower-variance strategies);
//  - light tracing alone (--vcm-mode lt, no MIS) converges to the same image as path on
//    cornell-diffuse, where every path reaches the camera through a diffuse first vertex;
//  - vcm (and its bpt and ppm subsets) converges on all three bench scenes: error falling with
//    iterations, mean within a few percent of the reference, and the point-light caustic that path
//    tracing cannot render within 10 % of the reference's window;
//  - bit-identical images for 1 and 2 threads.
// Renders at 128 x 128 against the references box-filtered down from 256 x 256 (each pixel the
// mean of the four it covers, which is exactly what a 128 x 128 box-filtered pixel estimates).
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "core/stats.h"
#include "film/film.h"
#include "film/metrics.h"
#include "integrators/registry.h"
#include "io/image/image_io.h"
#include "io/load_scene.h"
#include "render/prepared.h"
#include "test_util.h"

namespace phos {
namespace {

Image render_with(const std::string& name, const std::string& integrator, int spp,
                  const integrators::ProgressiveOptions& progressive, int size = 128, uint64_t seed = 3) {
    const scene::Scene s = io::load_scene(testing::shared_path("bench/scn/" + name + ".scn"));
    render::RenderOptions opt;
    opt.width = opt.height = size;
    opt.spp = spp;
    opt.seed = seed;
    Stats stats;
    render::Prepared prepared(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    integrators::IntegratorConfig config;
    config.progressive = progressive;
    integrators::make_integrator(integrators::integrator_kind(integrator), config)
        ->render(prepared, film, progress);
    EXPECT_EQ(stats.dropped_samples(), 0u) << integrator;
    return film.image();
}

Image render(const std::string& name, const std::string& integrator, int spp, const std::string& mode = "vcm",
             int size = 128, uint64_t seed = 3, const std::string& merge = "first") {
    integrators::ProgressiveOptions o;
    const options::Table& t = integrators::progressive_options();
    t.find("vcm-mode")->set(&o, {mode});
    t.find("vcm-merge")->set(&o, {merge});
    return render_with(name, integrator, spp, o, size, seed);
}

// The 256 x 256 reference box-filtered to size x size.
Image reference(const std::string& name, int size = 128) {
    const Image full = io::read_image(testing::shared_path("bench/ref/" + name + ".pfm"));
    const int f = full.width / size;
    Image out(size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            Rgb sum(0.0f);
            for (int j = 0; j < f; ++j)
                for (int i = 0; i < f; ++i) sum += full.at(x * f + i, y * f + j);
            out.at(x, y) = sum * (1.0f / float(f * f));
        }
    return out;
}

TEST(BidirectionalReference, BdptBeatsPathAtEqualSamplesOnCornellDiffuse) {
    const Image ref = reference("cornell-diffuse");
    const Image bdpt = render("cornell-diffuse", "bdpt", 64);
    const Image path = render("cornell-diffuse", "path", 64);
    const double eb = film::rel_mse(bdpt, ref), ep = film::rel_mse(path, ref);
    std::printf("cornell-diffuse 128x128, 64 spp: bdpt relMSE %.5f, path %.5f\n", eb, ep);
    EXPECT_LE(eb, ep);
    EXPECT_NEAR(film::mean_ratio(bdpt, ref), 1.0, 0.01);
}

TEST(BidirectionalReference, LightTracingAloneConvergesToPathsImage) {
    // Light tracing splats every light vertex onto the film (the t = 1 strategy alone, weight 1),
    // so its agreement with path checks the camera's importance and the pixel each splat lands on.
    // Tolerances: the mean within 1.5 % (both unbiased; light tracing's image mean has ~0.3 %
    // noise here) and relMSE against the reference falling with samples like 1/N (4x samples:
    // at most 0.4 of the error, allowing for the reference's own noise floor).
    const Image ref = reference("cornell-diffuse");
    const Image a = render("cornell-diffuse", "vcm", 16, "lt");
    const Image b = render("cornell-diffuse", "vcm", 64, "lt");
    const Image path = render("cornell-diffuse", "path", 256);
    const double ea = film::rel_mse(a, ref), eb = film::rel_mse(b, ref);
    std::printf("light tracing relMSE: 16 spp %.5f, 64 spp %.5f; mean ratio to path %.4f\n", ea, eb,
                film::mean_ratio(b, path));
    EXPECT_LT(eb, 0.4 * ea);
    EXPECT_NEAR(film::mean_ratio(b, path), 1.0, 0.015);
    EXPECT_NEAR(film::mean_ratio(b, ref), 1.0, 0.015);
}

void expect_vcm_converges(const std::string& name, double max_final, double mean_tolerance) {
    const Image ref = reference(name);
    const double e4 = film::rel_mse(render(name, "vcm", 4), ref);
    const Image img = render(name, "vcm", 16);
    const double e16 = film::rel_mse(img, ref);
    std::printf("%s vcm relMSE: 4 it %.5f, 16 it %.5f, mean ratio %.4f\n", name.c_str(), e4, e16,
                film::mean_ratio(img, ref));
    EXPECT_LT(e16, 0.5 * e4);
    EXPECT_LT(e16, max_final);
    EXPECT_NEAR(film::mean_ratio(img, ref), 1.0, mean_tolerance);
}

// Bounds: measured at 16 iterations 0.00096, 0.00502, 0.00878 (128 x 128, seed 3), with
// room for another seed; a broken strategy or weight shows as a mean off by far more than 1-3 % (the
// caustic-point mean is dominated by the caustic: unbiased strategies measure it 3 % under the
// reference, see below).
TEST(BidirectionalReference, VcmConvergesOnCornellDiffuse) {
    expect_vcm_converges("cornell-diffuse", 0.004, 0.01);
}
TEST(BidirectionalReference, VcmConvergesOnCornellGlassMirror) {
    expect_vcm_converges("cornell-glass-mirror", 0.012, 0.02);
}
TEST(BidirectionalReference, VcmConvergesOnCausticPoint) {
    expect_vcm_converges("caustic-point", 0.02, 0.03);
}

TEST(BidirectionalReference, VcmVarianceReductionsKeepTheImage) {
    // The default vcm (per-pixel radii from the pilot light pass and edges, light subpaths per
    // pixel chosen from the pilot, first-vertex light samples weighted 8 times over, Russian
    // roulette on shadow rays of weight below 0.1, two camera samples per pixel and iteration,
    // camera subpaths ending at a Lambert first non-delta vertex) against vcm with all six off (one
    // radius, K = 2, the true sample count, every shadow ray, one camera sample, every camera
    // subpath going on): unbiased changes of the weights and of the radius's start, so both
    // converge to the reference and agree in the mean. A weight that no longer sums to 1 (say the
    // pixel's 1 / eta^2 left off the light subpath's dVM, or the continuation's probability left
    // out of merging's weight), or roulette not divided by its probability, moves the mean by far
    // more than the 1.5 % allowed.
    integrators::ProgressiveOptions off;
    off.vcm_rr_weight = 0;
    off.direct_mis_scale = 1;
    off.radius_photons = 0;
    off.edge_aware_radius = false;
    off.vcm_light_paths = 2;
    off.vcm_camera_samples = 1;
    off.vcm_continue = 1;
    for (const std::string name : {"cornell-glass-mirror", "caustic-point"}) {
        const Image ref = reference(name);
        const Image fast = render_with(name, "vcm", 16, integrators::ProgressiveOptions{});
        const Image plain = render_with(name, "vcm", 16, off);
        const double ef = film::rel_mse(fast, ref), ep = film::rel_mse(plain, ref);
        std::printf("%s vcm 16 it: default %.5f (mean %.4f), all off %.5f (mean %.4f)\n", name.c_str(), ef,
                    film::mean_ratio(fast, ref), ep, film::mean_ratio(plain, ref));
        EXPECT_LT(ef, 0.02) << name;
        EXPECT_LT(ep, 0.03) << name;
        EXPECT_NEAR(film::mean_ratio(fast, plain), 1.0, 0.015) << name;
    }
}

TEST(BidirectionalReference, VcmEndingAtLambertVerticesKeepsTheMean) {
    // --vcm-continue 0 (the default) ends camera subpaths at their first non-delta vertex x_f where
    // it is Lambert; the weights of merging, connections and light tracing of x_f must then count
    // the continuation's probability 0, or the share of the strategies that went on is lost. With
    // one camera sample and a small merging radius (0.01, 0.02 scene units: merging and the
    // strategies past x_f both carry a good share of the indirect light) the mean must stay that of
    // camera subpaths going on (q = 1). The same random numbers up to x_f make the two images
    // differ by 0.03 % in the mean; leaving q out of merging's weight moves it by 0.9 % and 3.5 %,
    // out of the connections' by 2.5 % and 1.4 %, out of light tracing's by 6.2 % and 2.7 %.
    // (Leaving it out of x_f's light samples moves it by 0.02 %: the competing BSDF sample rarely
    // finds this scene's small light. The MIS test, vcm_mis_test.cpp, checks that term.)
    for (const float radius : {0.01f, 0.02f}) {
        integrators::ProgressiveOptions stop;
        stop.radius = radius;
        stop.vcm_camera_samples = 1;
        stop.direct_mis_scale = 1;
        stop.direct_samples = 1;
        stop.vcm_continue = 0;
        integrators::ProgressiveOptions go = stop;
        go.vcm_continue = 1;
        const Image a = render_with("cornell-diffuse", "vcm", 64, stop, 64);
        const Image b = render_with("cornell-diffuse", "vcm", 64, go, 64);
        std::printf("radius %.2f: mean with q = 0 over q = 1: %.5f\n", radius, film::mean_ratio(a, b));
        EXPECT_NEAR(film::mean_ratio(a, b), 1.0, 0.005) << "radius " << radius;
    }
}

TEST(BidirectionalReference, VcmRendersThePointLightCaustic) {
    // The caustic window of sppm_convergence_test.cpp (at 256 x 256: x 104-128, y 132-156), here
    // at half resolution. vcm reaches it by merging (and light tracing); its modes: ppm merges
    // alone, bpt connects alone (light tracing through the glass: noisy but unbiased). Light
    // tracing alone at 256 x 256 x 512 measures this window 3 % under the reference (4.450 vs
    // 4.584; bdpt at 256 spp 4.443): phos's RGB glass against pbrt-v4's spectral one. Tolerance
    // 10 % (20 % for bpt's noisier light tracing at 16 iterations).
    const Image ref = reference("caustic-point");
    const double w_ref = film::window_mean(ref, 52, 64, 66, 78);
    for (const std::string mode : {"vcm", "ppm", "bpt"}) {
        const Image img = render("caustic-point", "vcm", 16, mode);
        const double w = film::window_mean(img, 52, 64, 66, 78);
        std::printf("caustic window, vcm-mode %s: %.3f (reference %.3f)\n", mode.c_str(), w, w_ref);
        EXPECT_NEAR(w / w_ref, 1.0, mode == "bpt" ? 0.2 : 0.1) << mode;
    }
}

TEST(BidirectionalReference, VcmMergingAtEveryVertexConvergesToTheSameImage) {
    // --vcm-merge every (Georgiev et al.'s merging at every camera vertex) against the default
    // (only at the first non-delta one, with the light subpaths' merging terms off): two different
    // sets of strategies and weights for the same integral. On cornell-glass-mirror, whose mirror
    // makes the first non-delta vertex a deeper one for part of the image, both converge to the
    // reference and agree with each other in the mean; a weight that no longer sums to 1 in
    // either mode moves its mean by far more than the 1.5 % allowed.
    const Image ref = reference("cornell-glass-mirror");
    const Image first = render("cornell-glass-mirror", "vcm", 16);
    const Image every = render("cornell-glass-mirror", "vcm", 16, "vcm", 128, 3, "every");
    const double ef = film::rel_mse(first, ref), ee = film::rel_mse(every, ref);
    std::printf("cornell-glass-mirror vcm 16 it: first %.5f (mean %.4f), every %.5f (mean %.4f)\n", ef,
                film::mean_ratio(first, ref), ee, film::mean_ratio(every, ref));
    EXPECT_LT(ef, 0.025);
    EXPECT_LT(ee, 0.025);
    EXPECT_NEAR(film::mean_ratio(first, ref), 1.0, 0.015);
    EXPECT_NEAR(film::mean_ratio(every, ref), 1.0, 0.015);
    EXPECT_NEAR(film::mean_ratio(first, every), 1.0, 0.015);
}

TEST(BidirectionalReference, BitIdenticalForOneAndTwoThreads) {
    for (const std::string integrator : {"bdpt", "vcm"}) {
        Image a, b;
        tbb::task_arena(1).execute([&] { a = render("cornell-glass-mirror", integrator, 2, "vcm", 48); });
        tbb::task_arena(2).execute([&] { b = render("cornell-glass-mirror", integrator, 2, "vcm", 48); });
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        size_t differ = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] == b.pixels[i] ? 0 : 1;
        EXPECT_EQ(differ, 0u) << integrator;
    }
}

}  // namespace
}  // namespace phos
