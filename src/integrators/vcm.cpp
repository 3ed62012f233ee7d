// vcm's render loop, one screen: the pilot (vcm_pilot.h), then per iteration the merging radius,
// the light pass (every light subpath of the iteration, stored), the grid over their mergeable
// vertices, the camera pass (camera_subpath.h), the sums over the ranks, and the budget's previews
// and checkpoints. Each pixel's value is the mean over iterations of its camera subpaths' estimate
// plus the light-tracing splats that landed on it (fixed_film.h).
#include "integrators/vcm.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <span>

#include "core/format.h"
#include "dist/ranks.h"
#include "film/tiles.h"
#include "integrators/camera_subpath.h"
#include "integrators/fixed_film.h"
#include "integrators/vcm_pilot.h"
#include "render/progressive_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

namespace {

using namespace vcm;

// The strategies --vcm-mode and --vcm-merge name (the one reader of those options).
Strategies strategies_for(const ProgressiveOptions& o) {
    Strategies s;
    s.light_tracing_only = o.vcm_mode == VcmMode::Lt;
    s.connect = o.vcm_mode == VcmMode::Bpt || o.vcm_mode == VcmMode::Vcm;
    s.merge = o.vcm_mode == VcmMode::Ppm || o.vcm_mode == VcmMode::Vcm;
    s.ppm = o.vcm_mode == VcmMode::Ppm;
    s.merge_everywhere = o.vcm_merge == VcmMerge::Every;
    return s;
}

// The iteration's light subpaths, kept from one iteration to the next (no allocation per
// iteration). Batch b holds subpaths [b kBatch, (b + 1) kBatch): the vertices of those below
// `pixels` (subpath i's are kept[i / kBatch][begin[i] .. end[i])) and the mergeable vertices of all.
class LightPaths {
public:
    static constexpr size_t kBatch = 4096;
    LightPaths(const RenderOptions& ro, const std::vector<film::Tile>& tiles, size_t count)
        : pixels_(size_t(ro.width) * size_t(ro.height)),
          count_(count),
          owned_pixel_(pixels_, 0),
          kept_((count + kBatch - 1) / kBatch),
          mergeable_(kept_.size()),
          begin_(pixels_),
          end_(pixels_) {
        for (size_t t = 0; t < tiles.size(); ++t)
            if (dist::owns(t))
                for (int y = tiles[t].y0; y < tiles[t].y1; ++y)
                    for (int x = tiles[t].x0; x < tiles[t].x1; ++x)
                        owned_pixel_[size_t(y) * size_t(ro.width) + size_t(x)] = 1;
    }

    // The light pass of iteration `iteration`, in batches of consecutive subpaths; each rank traces
    // those of its own pixels (light subpath j belongs to pixel j mod pixels). Subpaths j < pixels
    // keep their vertices for the connections and light tracing of pixel j; every subpath adds its
    // mergeable vertices to the batch's merge list, in order.
    void trace(const Prepared& P, const LightSubpathRules& rules, uint64_t iteration) {
        tbb::parallel_for(size_t(0), kept_.size(), [&](size_t b) {
            RayCounts rays;
            std::vector<Vertex> traced;
            std::vector<VertexCore>& kept = kept_[b];
            std::vector<MergeVertex>& mergeable = mergeable_[b];
            kept.clear();
            mergeable.clear();
            for (size_t i = b * kBatch; i < std::min(count_, (b + 1) * kBatch); ++i) {
                if (i < pixels_) begin_[i] = uint32_t(kept.size());
                if (owned_pixel_[i % pixels_]) {
                    Sampler sampler(P.options.seed, kLightSubpathStream, i, iteration);
                    traced.clear();
                    trace_light_path(P, rules, sampler, subpath_wavelengths(P.options.seed, i, iteration),
                                     traced, rays);
                    for (const Vertex& v : traced) {
                        if (i < pixels_) kept.push_back(v);  // without the BSDF
                        if (v.mergeable)
                            mergeable.push_back({v.p, v.wo, spectrum::colour_weights(v.beta, v.lambda), v.mis,
                                                 v.length, part_at_first_vertex(v), uint32_t(i),
                                                 v.lambda.lambdas()});
                    }
                }
                if (i < pixels_) end_[i] = uint32_t(kept.size());
            }
            P.stats.add_rays(rays);
        });
    }

    // Pixel i's light subpath, its BSDFs built again, appended to `out`.
    void of_pixel(const Prepared& P, size_t i, std::vector<Vertex>& out) const {
        const std::vector<VertexCore>& batch = kept_[i / kBatch];
        for (uint32_t k = begin_[i]; k < end_[i]; ++k) out.push_back(with_bsdf(P, batch[k]));
    }

    // The grid over the mergeable vertices (surfaces only) of every rank, in light subpath order,
    // for merging within `radius`; the vertices stored in its order (a bucket's side by side).
    void build_vertex_grid(float radius, LightVertexGrid& out) {
        std::vector<size_t> offset(mergeable_.size() + 1, 0);
        for (size_t b = 0; b < mergeable_.size(); ++b) offset[b + 1] = offset[b] + mergeable_[b].size();
        if (dist::distributed()) {
            all_mergeable_.resize(offset.back());
            tbb::parallel_for(size_t(0), mergeable_.size(), [&](size_t b) {
                std::copy(mergeable_[b].begin(), mergeable_[b].end(),
                          all_mergeable_.begin() + std::ptrdiff_t(offset[b]));
            });
            all_mergeable_ = dist::all_gather(std::span<const MergeVertex>(all_mergeable_));
            std::stable_sort(all_mergeable_.begin(), all_mergeable_.end(),
                             [](const MergeVertex& a, const MergeVertex& b) { return a.path < b.path; });
        }
        // Mergeable vertex k of the iteration: from the gathered list, or (one process) in place
        // in its batch.
        const size_t count = dist::distributed() ? all_mergeable_.size() : offset.back();
        const auto mergeable_vertex = [&](size_t k) -> const MergeVertex& {
            if (dist::distributed()) return all_mergeable_[k];
            const size_t b = size_t(std::upper_bound(offset.begin(), offset.end(), k) - offset.begin()) - 1;
            return mergeable_[b][k - offset[b]];
        };
        merge_points_.resize(count);
        tbb::parallel_for(size_t(0), count, [&](size_t k) { merge_points_[k] = mergeable_vertex(k).p; });
        out.grid.build(merge_points_, radius);
        out.vertices.resize(count);
        const std::vector<uint32_t>& order = out.grid.order();
        tbb::parallel_for(size_t(0), order.size(),
                          [&](size_t k) { out.vertices[k] = mergeable_vertex(order[k]); });
    }

private:
    size_t pixels_, count_;
    std::vector<uint8_t> owned_pixel_;  // under MPI: the pixels of this rank's tiles
    std::vector<std::vector<VertexCore>> kept_;
    std::vector<std::vector<MergeVertex>> mergeable_;
    std::vector<uint32_t> begin_, end_;
    std::vector<MergeVertex> all_mergeable_;  // under MPI: every rank's, in light subpath order
    std::vector<Vec3> merge_points_;          // their positions, for the grid
};

// The -v line's account of merging: light subpaths per pixel (and the pilot's count behind an
// automatic choice), camera samples, and the last iteration's largest radius.
std::string merging_summary(const ProgressiveOptions& o, const MergingPlan& plan, const Iteration& it) {
    if (!it.strategies.merge) return "";
    std::string s = ", " + std::to_string(plan.light_paths_per_pixel) + " light subpaths per pixel";
    if (o.vcm_light_paths == 0)
        s +=
            " (pilot: " + printf_string("%.2f", plan.mergeable_per_path) + " mergeable vertices per subpath)";
    if (it.camera_samples > 1) s += ", " + std::to_string(it.camera_samples) + " camera samples";
    return s + ", largest radius " + std::to_string(it.radius);
}

}  // namespace

RenderDone VcmIntegrator::render(const Prepared& P, film::Film& film, Progress& progress) {
    const RenderOptions& ro = P.options;
    const size_t pixels = size_t(ro.width) * size_t(ro.height);
    ProgressiveState state = start_state(ro, budget_, "vcm", 0, "iterations", uint64_t(std::max(1, ro.spp)));
    FixedFilm sums(ro.width, ro.height, ro.layers);  // this rank's image sums (all of them without MPI)
    sums.resume(state, "checkpoint '" + budget_.settings.resume_path + "': vcm sums");

    // Prepare: the strategies, and from the pilot the light subpaths per pixel and the radii.
    Iteration it = iteration_for(strategies_for(opt_), opt_);
    const MergingPlan plan = plan_merging(P, opt_, it.strategies);
    const size_t light_paths = pixels * size_t(plan.light_paths_per_pixel);
    it.light_paths = float(light_paths);
    if (!plan.pixel_radius.empty()) it.pixel_radius = &plan.pixel_radius;
    const auto tiles = film::make_tiles(ro.width, ro.height);
    LightPaths light(ro, tiles, light_paths);
    LightVertexGrid merging;
    const RenderBudget budget = sums.saving_sums(budget_);
    const auto resolve_film = [&] { sums.resolve(film, state.iterations); };

    ProgressiveBudget loop(ro, budget, state, film, progress);
    while (loop.next()) {
        const uint64_t iteration = state.iterations;
        if (it.strategies.merge) begin_merging_iteration(it, iteration, plan.base_radius, opt_.alpha);
        light.trace(
            P, {std::max(1, ro.max_depth), it.light_factors, plan.merge_from, it.strategies.merge_everywhere},
            iteration);
        if (it.strategies.merge) light.build_vertex_grid(it.radius, merging);
        // Each pixel's camera subpath with its light subpath (connections and light tracing).
        camera_pass(P, it, &merging, tiles, iteration, sums,
                    [&](size_t i, std::vector<Vertex>& out, RayCounts&) {
                        if (it.strategies.light_tracing()) light.of_pixel(P, i, out);
                    });
        sums.sum_over_ranks();
        loop.after_iteration(resolve_film);
    }
    resolve_film();
    const RenderDone done = loop.finish();
    P.stats.add_dropped_samples(sums.rejected());
    P.stats.add_value("vcm",
                      std::to_string(state.iterations) + " iterations" + merging_summary(opt_, plan, it));
    return done;
}

}  // namespace phos::integrators
