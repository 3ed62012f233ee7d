// The option table of the progressive photon mappers (see progressive_options.h).
#include "integrators/progressive_options.h"

#include "integrators/registry.h"

namespace phos::integrators {

using options::at_least;
using options::between;
using options::Effect;
using options::positive;
using K = IntegratorKind;

namespace {

using Builder = options::TableBuilder<ProgressiveOptions>;

// Marks `o` as an option of the integrators `to`.
options::Option& applies(options::Option& o, std::initializer_list<K> to = {K::Ppm, K::Sppm}) {
    o.applies_to = integrator_set(to);
    return o;
}

// The bidirectional integrators' entries (bdpt, vcm): their strategies and weights.
void add_bidirectional_options(Builder& b) {
    applies(
        b.choice("vcm-mode", &ProgressiveOptions::vcm_mode,
                 {{VcmMode::Bpt, "bpt"}, {VcmMode::Ppm, "ppm"}, {VcmMode::Vcm, "vcm"}, {VcmMode::Lt, "lt"}},
                 "the strategies vcm uses: connections only (bpt), merging only (ppm), both (vcm), "
                 "light tracing alone (lt)"),
        {K::Vcm});
    auto& lp = applies(b.number("vcm-light-paths", &ProgressiveOptions::vcm_light_paths, "K", between(0, 64),
                                "light subpaths per pixel per iteration for merging (connections and light "
                                "tracing use one; 0 = automatic: 2 to 8, enough for about 3 mergeable "
                                "vertices per pixel in a pilot light pass)"),
                       {K::Vcm});
    lp.default_text = "automatic";
    applies(b.number("vcm-camera-samples", &ProgressiveOptions::vcm_camera_samples, "M", between(1, 64),
                     "camera samples per pixel per iteration with merging at the first non-delta vertex: "
                     "one camera subpath goes on with every strategy, the other M - 1 stop after their "
                     "first non-delta vertex's light samples and merging (as SPPM's visible points)"),
            {K::Vcm});
    applies(b.number("vcm-continue", &ProgressiveOptions::vcm_continue, "Q", between(0, 1),
                     "with merging at the first non-delta vertex: the probability that the first camera "
                     "sample goes on past that vertex where it is a lone Lambert lobe (the deeper "
                     "strategies weighted by it; 0: merging, light samples, connections and light tracing "
                     "of that vertex make every path; glossy vertices and media always go on)"),
            {K::Vcm});
    applies(b.choice("vcm-merge", &ProgressiveOptions::vcm_merge,
                     {{VcmMerge::First, "first"}, {VcmMerge::Every, "every"}},
                     "where camera subpaths merge: at their first non-delta vertex only, as SPPM gathers "
                     "(first), or at every vertex (every, Georgiev et al.'s VCM)"),
            {K::Vcm});
    applies(b.number("vcm-rr-weight", &ProgressiveOptions::vcm_rr_weight, "W", between(0, 1),
                     "Russian roulette on the shadow rays of connections, light-tracing splats and light "
                     "samples whose MIS weight w is below W: cast with probability w / W and counted W / w "
                     "times (unbiased; 0 = every shadow ray)"),
            {K::Bdpt, K::Vcm});
    applies(b.number("direct-mis-scale", &ProgressiveOptions::direct_mis_scale, "S", between(1, 1e6),
                     "the MIS weights count the light samples at the camera subpath's first non-delta "
                     "vertex S times over "
                     "(stratified, they converge faster than the BSDF samples and light-tracing splats "
                     "they compete with; any S keeps the estimate unbiased)"),
            {K::Bdpt, K::Vcm});
}

}  // namespace

const options::Table& progressive_options() {
    static const options::Table table = [] {
        options::TableBuilder<ProgressiveOptions> b(
            "Progressive photon mapping",
            "ppm and sppm: radius reduction, photons, iterations (docs/progressive.md)");
        const auto prog = [](options::Option& o,
                             std::initializer_list<K> to = {K::Ppm, K::Sppm}) -> options::Option& {
            return applies(o, to);
        };
        prog(b.number("alpha", &ProgressiveOptions::alpha, "A", options::Range{0, 1, true, false},
                      "fraction of new photons kept per iteration (radius reduction)"),
             {K::Ppm, K::Sppm, K::Vcm});
        prog(b.number("photons-per-iter", &ProgressiveOptions::photons_per_iter, "N",
                      between(1, 4294967296.0), "photons traced per iteration"))
            .pbrt = "photonsperiteration";
        b.last().pbrt_unset = "-1";
        auto& r = prog(b.number("radius", &ProgressiveOptions::radius, "R", at_least(0),
                                "initial gather radius in scene units (0 = automatic)"),
                       {K::Ppm, K::Sppm, K::Vcm});
        r.pbrt = "radius";
        r.default_text = "automatic (--radius-pixels, --radius-photons)";
        prog(b.number("radius-pixels", &ProgressiveOptions::radius_pixels, "P", positive(),
                      "automatic initial radius in pixel footprints at the hit distance (vcm: at the "
                      "distance from the camera to the scene's centre)"),
             {K::Ppm, K::Sppm, K::Vcm});
        add_bidirectional_options(b);
        prog(b.number("radius-photons", &ProgressiveOptions::radius_photons, "K", between(0, 1e9),
                      "the first iteration's photons (a pilot, not used in the estimate) set each pixel's "
                      "automatic radius so its disc holds about K photons, within 1-8 pixel footprints (vcm: "
                      "light vertices of a pilot light pass, the radius at most --radius-pixels; 0 = off)"),
             {K::Sppm, K::Vcm});
        prog(b.flag("edge-aware-radius", &ProgressiveOptions::edge_aware_radius,
                    "after the pilot, bound each pixel's radius by its distance to the nearest visible point "
                    "on another surface or off its plane (an edge, corner or contact), at most halving it",
                    true, "no-edge-aware-radius"),
             {K::Sppm, K::Vcm});
        auto& ds = prog(
            b.number(
                "direct-samples", &ProgressiveOptions::direct_samples, "N", between(0, 65536),
                "light samples per visible point (bdpt, vcm: at the camera subpath's first non-delta vertex; "
                "0 = the integrator's default)"),
            {K::Ppm, K::Sppm, K::Bdpt, K::Vcm});
        ds.aliases = {"ppm-direct-samples"};
        ds.default_text = "sppm, bdpt and vcm 2 per iteration, ppm 16 once";
        prog(b.number("ppm-eye-samples", &ProgressiveOptions::eye_samples, "N", between(1, 4096),
                      "hit points per pixel"),
             {K::Ppm});
        auto& it = prog(b.number("iterations", &ProgressiveOptions::iterations, "N", between(0, 1 << 30),
                                 "number of iterations (the same as --spp; 0 = not given)"),
                        {K::Ppm, K::Sppm, K::Bdpt, K::Vcm});
        it.effect = Effect::Budget;
        it.pbrt = "iterations";
        it.default_text = "--spp";
        return b.build();
    }();
    return table;
}

}  // namespace phos::integrators
