// The budget of a sample-based render (whitted, path, photonmap's second pass), so that the pixel
// loop stays visible:
//
//     SamplePasses passes(P, film, budget, "path", progress);
//     while (passes.next())
//         parallel over tiles t: if (!passes.stopped()) render samples passes.range(t), passes.tile_done(t,
//         rays) passes.after_pass();
//     passes.finish();
//
// Samples are taken in passes over the whole image: each pass gives every tile its next few
// samples per pixel (as many as keep a pass near half a second; the count never changes the image,
// since every pixel takes its samples in index order). Between passes it checks the time budget
// (--time), writes previews (--write-every) and checkpoints (--checkpoint, every
// --checkpoint-every samples per pixel, at the end and when interrupted); an interrupt stops the
// tiles not yet started, and the film then holds each pixel's own samples, correctly normalised.
// A checkpoint holds the film's sums and each tile's sample count, so resuming continues each tile
// where it stopped: bit-identical to an uninterrupted render.
//
// Under MPI (dist/ranks.h) each rank takes the samples of the tiles it owns; between passes the
// ranks agree on the tiles' counts, rank 0's clock and options decide (time budget, previews,
// checkpoints, the pass size) for all, an interrupt on any rank stops all, and rank 0 gathers the
// other ranks' tiles whenever it writes or shows the image (tile_gather.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/progress.h"
#include "core/stats.h"
#include "film/film.h"
#include "film/tiles.h"
#include "render/prepared.h"
#include "render/progressive_checkpoint.h"
#include "render/render_budget.h"
#include "render/tile_gather.h"

namespace phos::render {

class SamplePasses {
public:
    // Starts the render (fresh, or from budget.observers.resume after checking it is the same render and
    // film) and its progress display: the target is options.spp x options.dof_samples samples per
    // pixel and budget.time seconds.
    // `payload` (optional) fills the integrator's own data into each checkpoint (the photon maps).
    SamplePasses(const Prepared& prepared, film::Film& film, const RenderBudget& budget,
                 const std::string& integrator, Progress& progress,
                 std::function<void(std::string& payload)> payload = {});

    const std::vector<film::Tile>& tiles() const { return tiles_; }
    // Whether to run another pass: some tile is short of the target, the time budget was not
    // crossed and no interrupt came.
    bool next();
    // The samples [first, last) tile t takes in this pass (empty when it is done).
    std::pair<uint32_t, uint32_t> range(size_t t) const;
    // Whether tiles not yet started should be skipped (an interrupt came). Thread-safe.
    bool stopped() const;
    // Records that tile t took its range of this pass (call from the tile's task).
    void tile_done(size_t t, const RayCounts& rays);
    // Ends a pass: the time budget, previews, checkpoints, the next pass's size.
    void after_pass();
    // Ends the render: the progress line, the final checkpoint (also when interrupted); returns
    // what the render completed.
    RenderDone finish();

private:
    uint32_t min_done() const;
    uint64_t taken() const;  // pixel samples taken in all
    void save_checkpoint();

    const Prepared& P_;
    film::Film& film_;
    const BudgetSettings& settings_;
    const RenderObservers& watch_;
    Progress& progress_;
    std::function<void(std::string&)> payload_;
    std::vector<film::Tile> tiles_;
    TileGather gather_{tiles_};
    ProgressiveState state_;           // identity, tile_samples (the film's sums are taken when saving)
    uint64_t target_ = 0;              // samples per pixel asked
    uint32_t pass_ = 1;                // samples per pixel of the next pass
    uint32_t pass_end_ = 0;            // this pass: tiles take samples up to here
    uint64_t last_checkpoint_ = 0;     // samples per pixel at the last checkpoint
    uint64_t checkpoint_samples_ = 0;  // pixel samples the last checkpoint (or the resumed one) held
    RenderDone done_;
    bool time_up_ = false, timed_ = false, progress_started_ = false;
    std::chrono::steady_clock::time_point t0_, pass_start_, last_preview_;
};

}  // namespace phos::render
