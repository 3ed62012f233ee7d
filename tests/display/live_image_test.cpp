// LiveImage's change tracking: a watcher that re-reads only changed_since() regions ends up with
// exactly the image, and the regions cover what changed and nothing far from it.
#include "display/live_image.h"

#include <gtest/gtest.h>

#include "film/film.h"

namespace phos::display {
namespace {

void fill(film::Film& film, const film::Tile& t, float v) {
    for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) film.add_sample(x, y, Rgb(v + float(x) + 1000.0f * float(y)), 1.0f);
}

TEST(LiveImage, EverythingIsChangedForAFreshWatcher) {
    LiveImage live(70, 40);
    const std::vector<Region> all = live.changed_since(0);
    ASSERT_EQ(all.size(), 2u);  // two rows of 32-pixel blocks
    EXPECT_EQ(all[0], (Region{0, 0, 70, 32}));
    EXPECT_EQ(all[1], (Region{0, 32, 70, 40}));
}

TEST(LiveImage, OnlyChangedBlocksAreReportedAndTheyHoldTheNewValues) {
    film::Film film(100, 80);
    LiveImage live(100, 80);
    live.update_frame(film);  // a watcher has seen this (version 0 would mean "show me everything")
    const uint64_t seen = live.version();
    const film::Tile tile{40, 33, 56, 49};  // inside block row 1, block columns 1
    fill(film, tile, 0.5f);
    live.update_tile(film, tile);
    const std::vector<Region> changed = live.changed_since(seen);
    ASSERT_EQ(changed.size(), 1u);
    EXPECT_EQ(changed[0], (Region{32, 32, 64, 64}));
    const std::vector<Rgb> values = live.read_region(0, changed[0]);
    ASSERT_EQ(values.size(), 32u * 32u);
    for (int y = 32; y < 64; ++y)
        for (int x = 32; x < 64; ++x)
            EXPECT_EQ(values[size_t(y - 32) * 32 + size_t(x - 32)], film.main().value(x, y)) << x << "," << y;
    EXPECT_TRUE(live.changed_since(live.version()).empty());
}

TEST(LiveImage, AWatcherFollowingRegionsReconstructsTheWholeImage) {
    film::Film film(90, 70);
    LiveImage live(90, 70);
    std::vector<Rgb> mirror(90 * 70, Rgb(-1.0f));
    uint64_t shown = 0;
    const std::vector<film::Tile> tiles = {
        {0, 0, 45, 35}, {45, 0, 90, 35}, {0, 35, 45, 70}, {45, 35, 90, 70}};
    for (size_t i = 0; i < tiles.size(); ++i) {
        fill(film, tiles[i], float(i));
        live.update_tile(film, tiles[i]);
        const uint64_t now = live.version();
        for (const Region& r : live.changed_since(shown)) {
            const std::vector<Rgb> v = live.read_region(0, r);
            for (int y = r.y0; y < r.y1; ++y)
                for (int x = r.x0; x < r.x1; ++x)
                    mirror[size_t(y) * 90 + size_t(x)] =
                        v[size_t(y - r.y0) * size_t(r.width()) + size_t(x - r.x0)];
        }
        shown = now;
    }
    EXPECT_EQ(mirror, live.read(0));
    for (int y = 0; y < 70; ++y)
        for (int x = 0; x < 90; ++x) ASSERT_EQ(mirror[size_t(y) * 90 + size_t(x)], film.main().value(x, y));
}

}  // namespace
}  // namespace phos::display
