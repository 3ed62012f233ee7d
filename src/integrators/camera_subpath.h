// The engine bdpt and vcm share (Veach 1997, ch. 10; Georgiev, Křivánek, Davidovič & Slusallek
// 2012): a pixel's camera subpath and every strategy that completes it with light — the emitters
// it hits (s = 0), light samples at its vertices (s = 1), connections to the pixel's light subpath
// (s, t >= 2), merging with the iteration's light vertices, and light tracing of the pixel's light
// subpath onto the film (t = 1) — each weighted by the power heuristic (vcm_mis.h). Which of them
// take part is the iteration's Strategies: bdpt's are the connections, vcm's what --vcm-mode names.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "film/tiles.h"
#include "integrators/bidirectional_path.h"
#include "integrators/fixed_film.h"
#include "integrators/progressive_options.h"
#include "integrators/vertex_grid.h"
#include "spectrum/color.h"

namespace phos::integrators::vcm {

// The random-number stream of light subpath j of an iteration (keyed by j and the iteration).
constexpr uint64_t kLightSubpathStream = 0x6c69676874ULL;

// The strategies that make an iteration's paths (Georgiev et al. 2012: vertex connection
// is bidirectional path tracing's, vertex merging photon mapping's).
struct Strategies {
    // Vertex connection: light samples, connections and light tracing, MIS-weighted (bdpt; --vcm-mode
    // bpt and vcm).
    bool connect = false;
    bool merge = false;  // vertex merging (--vcm-mode vcm and ppm)
    // --vcm-mode lt: light tracing alone, unweighted (with the emitters the camera sees directly).
    bool light_tracing_only = false;
    // --vcm-mode ppm: merging alone, unweighted, at the camera subpath's first non-delta vertex
    // only, and next to the light too (which nothing else finds there; vcm leaves direct light to
    // light sampling, emitter hits and light tracing, vcm_mis.h).
    bool ppm = false;
    // Merging at every camera vertex (Georgiev et al.; --vcm-merge every) or only at the camera
    // subpath's first non-delta vertex (as SPPM gathers): vcm_mis.h.
    bool merge_everywhere = false;

    bool light_tracing() const { return connect || light_tracing_only; }
    bool merge_next_to_light() const { return ppm; }
    bool merge_first_vertex_only() const { return merge && !merge_everywhere; }
};

// bdpt: every connection strategy, no merging.
constexpr Strategies kBdptStrategies{.connect = true};

// What merging needs of a light vertex on a surface, packed (the grid visits many per query).
// Plain data, so that ranks can exchange them (under MPI each traces its own pixels' subpaths).
struct MergeVertex {
    Vec3 p, wo;
    // Its throughput at its subpath's wavelengths, as the colour each wavelength adds
    // (spectrum::colour_weights): merging weighs them by the camera vertex's BSDF there.
    spectrum::ColourWeights beta;
    SubpathMis mis;
    int length;
    Part part;      // part_at_first_vertex
    uint32_t path;  // the light subpath it belongs to: the order every rank count agrees on
    // Its subpath's wavelengths, the values only: merging evaluates the camera vertex's BSDF there
    // (the densities are in beta's colours already).
    std::array<float, spectrum::kSpectrumSamples> lambda{};
    Wavelengths wavelengths() const { return Wavelengths::at_values(lambda); }
};

// Light arriving at light vertex `l`, seen at the camera's first vertex x1 = l.
inline Part part_at_first_vertex(const VertexCore& l) {
    return l.length == 1 ? kDirect : l.delta_chain ? kCaustic : kIndirect;
}

// The iteration's light vertices merging reads (vcm): in the grid's order, a bucket's vertices side
// by side.
struct LightVertexGrid {
    std::vector<MergeVertex> vertices;
    VertexGrid grid;
};

// The strategies of one iteration and their constants.
struct Iteration {
    Strategies strategies;
    // Light samples at the camera subpath's first non-delta vertex x_f (--direct-samples; deeper
    // vertices take one): the light-sampling strategy of paths whose vertex next to the light is
    // x_f has n times the density in every weight (direct_light_sample, the emitter hit right
    // after x_f, light tracing of a light subpath's first vertex).
    int direct_samples = 1;
    // The count the weights give those samples: direct_samples x --direct-mis-scale x
    // camera_samples. Any positive count used alike in all three weights keeps them a partition of
    // unity (the estimate unbiased); a larger one hands more of the direct light to the stratified
    // light samples, which converge faster than the BSDF samples and light-tracing splats they
    // compete with (on the Cornell boxes' walls, 8 cut the variance 3.4x at no cost;
    // docs/bidirectional.md).
    float direct_mis = 1;
    // Camera samples per pixel (--vcm-camera-samples M, merging at the first non-delta vertex only):
    // the first camera subpath takes every strategy; the other M - 1 stop after their first
    // non-delta vertex x_f. So the strategies that end at x_f on the camera side (its light samples,
    // merging there, emission found up to it) are M samples per iteration and every other strategy
    // one: multi-sample MIS (Veach 1997 sec. 9.2.2) counts those M times in every weight (M x eta in
    // the pixel's merging factors, M x direct_mis) and each of the M samples' estimates of them is
    // divided by M. Merging at x_f being a path's only merging strategy, eta is already per pixel.
    int camera_samples = 1;
    // The probability that the first camera sample goes on past its first non-delta vertex x_f
    // where x_f is a lone Lambert lobe (--vcm-continue, first-vertex merging; 1 elsewhere):
    // go_on_from.
    float go_on = 1;
    // Merging radii: pixel i's camera subpaths merge within pixel_radius[i] * shrink (first-vertex
    // merging; null: every pixel `radius`), and the grid is built for the largest, `radius`.
    float radius = 0, shrink = 1, light_paths = 0;
    const std::vector<float>* pixel_radius = nullptr;
    // Strategies whose MIS weight is below this cast their shadow ray by Russian roulette
    // (weight_roulette; 0: always).
    float rr_weight = 0;
    MisFactors factors;        // bdpt; vcm merging at every vertex (one radius for all)
    MisFactors light_factors;  // what the light subpaths use (begin_merging_iteration)
    float uniform_norm = 0;    // 1 / (pi r^2 N_light) of `radius`

    // What merging needs at the first non-delta vertex of pixel i's camera subpaths. With merging
    // there only, the merging area eta enters a path's weights at that vertex alone, so each pixel
    // may have its own: its camera subpaths, and the light-tracing splats that land on it, use
    // that pixel's factors; the light subpaths carry dVM without 1 / eta^2 (light_factors: vc = 1)
    // and merging multiplies it in.
    struct PixelMerge {
        MisFactors factors;
        float merge_norm = 0, radius2 = 0;  // 1 / (pi r^2 N_light M), r^2
    };
    PixelMerge pixel(size_t i) const;
};

// The constants of an iteration with `strategies` from the options (their light samples, camera
// samples, roulette); without merging also its MIS factors, which then stay the same.
Iteration iteration_for(const Strategies& strategies, const ProgressiveOptions& o);

// Merging iteration `iteration`'s radius and MIS factors: the radius reduction of Knaus & Zwicker
// 2011, r_i = r_1 i^((alpha - 1) / 2), of the largest first radius r1, and eta_VCM = pi r_i^2
// N_light (Georgiev 2012, "Implementing vertex connection and merging", eq. 20).
void begin_merging_iteration(Iteration& it, uint64_t iteration, float r1, float alpha);

// The camera pass of iteration `iteration`, tile by tile (this rank's tiles): each pixel's light
// subpath from `light_path(pixel, out, rays)` (which appends it to the cleared `out`), then its
// light tracing and camera samples with every strategy (`merging`: the light vertices to merge
// with; null without merging), added to `sums`.
using LightPathSource = std::function<void(size_t pixel, std::vector<Vertex>& out, RayCounts& rays)>;
void camera_pass(const Prepared& P, const Iteration& it, const LightVertexGrid* merging,
                 const std::vector<film::Tile>& tiles, uint64_t iteration, FixedFilm& sums,
                 const LightPathSource& light_path);

}  // namespace phos::integrators::vcm
