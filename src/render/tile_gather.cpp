// Gathering the ranks' tiles on rank 0 (see tile_gather.h). A rank's message: its rejected-sample
// increment (one uint64), then for each tile it owns, in tile order, each layer's region sums (the
// main image, then the layers by name), 4 doubles per pixel.
#include "render/tile_gather.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "dist/ranks.h"

namespace phos::render {

void TileGather::gather(film::Film& film) {
    if (!dist::distributed()) return;
    std::vector<film::Layer*> layers{&film.main()};
    for (const std::string& name : film.layer_names()) layers.push_back(&film.layer(name));
    std::string mine;
    if (!dist::root()) {
        const uint64_t rejected = film.main().rejected();
        const uint64_t increment = rejected - rejected_sent_;
        rejected_sent_ = rejected;
        std::vector<double> sums;
        for (size_t t = 0; t < tiles_.size(); ++t) {
            if (!dist::owns(t)) continue;
            const film::Tile& tile = tiles_[t];
            for (const film::Layer* layer : layers)
                layer->append_region_sums(tile.x0, tile.y0, tile.x1, tile.y1, sums);
        }
        mine.resize(sizeof increment + sums.size() * sizeof(double));
        std::memcpy(mine.data(), &increment, sizeof increment);
        if (!sums.empty())
            std::memcpy(mine.data() + sizeof increment, sums.data(), sums.size() * sizeof(double));
    }
    const std::vector<std::string> all = dist::gather(mine);
    if (!dist::root()) return;
    const size_t n = size_t(dist::ranks());
    for (size_t r = 1; r < all.size(); ++r) {
        const std::string& bytes = all[r];
        size_t expected = sizeof(uint64_t);
        for (size_t t = r; t < tiles_.size(); t += n)
            expected += size_t(tiles_[t].pixel_count()) * 4 * sizeof(double) * layers.size();
        if (bytes.size() != expected)
            throw std::runtime_error("rank " + std::to_string(r) + " sent " + std::to_string(bytes.size()) +
                                     " bytes of tiles, not " + std::to_string(expected));
        uint64_t increment = 0;
        std::memcpy(&increment, bytes.data(), sizeof increment);
        film.main().add_rejected(increment);
        std::vector<double> sums((bytes.size() - sizeof increment) / sizeof(double));
        if (!sums.empty())
            std::memcpy(sums.data(), bytes.data() + sizeof increment, sums.size() * sizeof(double));
        const double* at = sums.data();
        for (size_t t = r; t < tiles_.size(); t += n) {
            const film::Tile& tile = tiles_[t];
            for (film::Layer* layer : layers) {
                layer->set_region_sums(tile.x0, tile.y0, tile.x1, tile.y1, at);
                at += size_t(tile.pixel_count()) * 4;
            }
        }
    }
}

}  // namespace phos::render
