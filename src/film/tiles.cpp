// Image tiling (see tiles.h).
#include "film/tiles.h"

#include <algorithm>
#include <stdexcept>

namespace phos::film {

std::vector<Tile> make_tiles(int width, int height, int tile_size) {
    if (tile_size < 1) throw std::invalid_argument("tile size must be at least 1");
    if (width < 0 || height < 0) throw std::invalid_argument("image size must not be negative");
    std::vector<Tile> tiles;
    for (int y = 0; y < height; y += tile_size)
        for (int x = 0; x < width; x += tile_size) {
            Tile t;
            t.x0 = x;
            t.y0 = y;
            t.x1 = std::min(x + tile_size, width);
            t.y1 = std::min(y + tile_size, height);
            t.index = int(tiles.size());
            tiles.push_back(t);
        }
    return tiles;
}

}  // namespace phos::film
