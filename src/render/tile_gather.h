// A sample-based render split over MPI ranks (dist/ranks.h, docs/distributed.md): each rank renders
// the tiles it owns (dist::owns(tile index)), every pixel's samples exactly as one process takes
// them; gather() brings the other ranks' tiles, every film layer, into rank 0's film, so that rank
// 0 holds the whole image whenever it writes one (a preview, a checkpoint, the end). With one rank
// it does nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "film/film.h"
#include "film/tiles.h"

namespace phos::render {

class TileGather {
public:
    explicit TileGather(const std::vector<film::Tile>& tiles) : tiles_(tiles) {}
    // The film as the render starts (a resumed one holds the checkpoint's rejected count, which
    // rank 0 already has).
    void start(const film::Film& film) { rejected_sent_ = film.main().rejected(); }
    // Collective: every rank calls it at the same point. Rank 0's film receives each other rank's
    // tiles (their current sums, overwriting rank 0's stale copies) and the samples those ranks
    // rejected (NaN / infinite) since the last call.
    void gather(film::Film& film);

private:
    const std::vector<film::Tile>& tiles_;
    uint64_t rejected_sent_ = 0;  // this rank's rejected count at the last gather
};

}  // namespace phos::render
