// Tests of film/tiles: tiles cover every pixel exactly once, in a fixed row-major order.
#include "film/tiles.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace phos::film {
namespace {

TEST(Tiles, CoverEveryPixelExactlyOnce) {
    for (auto [w, h, size] : {std::tuple{256, 256, 16}, {37, 21, 8}, {1, 1, 16}, {17, 3, 16}, {5, 40, 1}}) {
        const std::vector<Tile> tiles = make_tiles(w, h, size);
        std::vector<int> hits(size_t(w) * size_t(h), 0);
        for (size_t i = 0; i < tiles.size(); ++i) {
            const Tile& t = tiles[i];
            EXPECT_EQ(t.index, int(i));
            EXPECT_GT(t.width(), 0);
            EXPECT_GT(t.height(), 0);
            EXPECT_LE(t.width(), size);
            EXPECT_LE(t.height(), size);
            for (int y = t.y0; y < t.y1; ++y)
                for (int x = t.x0; x < t.x1; ++x) {
                    ASSERT_TRUE(x >= 0 && x < w && y >= 0 && y < h);
                    ++hits[size_t(y) * size_t(w) + size_t(x)];
                }
        }
        for (int n : hits) ASSERT_EQ(n, 1) << w << "x" << h << " tile " << size;
        const size_t expected = size_t((w + size - 1) / size) * size_t((h + size - 1) / size);
        EXPECT_EQ(tiles.size(), expected);
    }
}

TEST(Tiles, FixedRowMajorOrderAndEdgeTiles) {
    const std::vector<Tile> tiles = make_tiles(40, 20, 16);  // 3 columns x 2 rows
    ASSERT_EQ(tiles.size(), 6u);
    EXPECT_EQ(tiles[0].x0, 0);
    EXPECT_EQ(tiles[0].y0, 0);
    EXPECT_EQ(tiles[1].x0, 16);
    EXPECT_EQ(tiles[2].x0, 32);
    EXPECT_EQ(tiles[2].x1, 40);  // right edge tile is 8 wide
    EXPECT_EQ(tiles[3].x0, 0);
    EXPECT_EQ(tiles[3].y0, 16);
    EXPECT_EQ(tiles[5].y1, 20);  // bottom edge tile is 4 high
    EXPECT_EQ(tiles[5].pixel_count(), 8 * 4);
}

TEST(Tiles, EmptyImageAndBadTileSize) {
    EXPECT_TRUE(make_tiles(0, 10).empty());
    EXPECT_TRUE(make_tiles(10, 0).empty());
    EXPECT_THROW(make_tiles(10, 10, 0), std::invalid_argument);
}

}  // namespace
}  // namespace phos::film
