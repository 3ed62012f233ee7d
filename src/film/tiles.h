// Fixed tiling of the image for deterministic parallel rendering: the same tiles in the same order
// for a given size, whatever the thread count, so per-tile work and its reduction are reproducible.
#pragma once

#include <vector>

namespace phos::film {

// Pixels [x0, x1) x [y0, y1); `index` is the tile's position in make_tiles' order.
struct Tile {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int index = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    int pixel_count() const { return width() * height(); }
};

inline constexpr int kDefaultTileSize = 16;

// Tiles of tile_size x tile_size (smaller at the right and bottom edges), row by row from the
// top-left. Empty for an empty image; std::invalid_argument for tile_size < 1 or negative sizes.
std::vector<Tile> make_tiles(int width, int height, int tile_size = kDefaultTileSize);

}  // namespace phos::film
