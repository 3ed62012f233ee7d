// The image as it converges, shared between the render and whoever watches it (the preview
// window, the tev stream): the render copies each finished tile (or the whole film after a pass or
// iteration) into it; watchers on their own threads read the latest pixels of any layer when the
// version has changed. Copies are per tile under a mutex, so watching costs the render little.
// Each 32 x 32 block remembers the version that last changed it, so a watcher re-reads, re-maps and
// re-sends only what changed since it last looked (changed_since / read_region).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "core/vec.h"
#include "film/film.h"
#include "film/tiles.h"

namespace phos::display {

// A rectangle of pixels [x0, x1) x [y0, y1).
struct Region {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool operator==(const Region&) const = default;
};

class LiveImage {
public:
    static constexpr int kBlock = 32;  // side of the change-tracking blocks, in pixels

    // An image of width x height; layer 0 is the film's image ("image"), the film's own layers are
    // added as they appear (update_frame).
    LiveImage(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }

    // Called by the render: copies the pixel values of `tile` (every known layer) / of the whole
    // film (adding layers the film has gained, e.g. AOVs) and bumps the version.
    void update_tile(const film::Film& film, const film::Tile& tile);
    void update_frame(const film::Film& film);
    // The render is over (watchers may show "done" and, unless held, close).
    void finish();

    // Watchers: the layer names ("image" first), the version (0: nothing yet), and a copy of one
    // layer's values (row-major, top row first). wait() returns when the version passes `seen`,
    // the render finished, or `seconds` passed.
    std::vector<std::string> layer_names() const;
    uint64_t version() const;
    bool finished() const;
    std::vector<Rgb> read(size_t layer) const;
    void wait(uint64_t seen, double seconds) const;
    // What changed after version `seen` (0: everything): per row of blocks, the span from the first
    // to the last changed block, top to bottom.
    std::vector<Region> changed_since(uint64_t seen) const;
    // One layer's values inside `region` (row-major, top row first).
    std::vector<Rgb> read_region(size_t layer, const Region& region) const;

private:
    void add_layers(const film::Film& film);    // mutex held
    void mark(int x0, int y0, int x1, int y1);  // mutex held, after ++version_
    int width_, height_;
    int blocks_x_, blocks_y_;
    std::vector<uint64_t> block_version_;  // per block, the version that last changed it
    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    std::vector<std::string> names_;        // "image", then film layer names
    std::vector<std::vector<Rgb>> values_;  // per layer, width x height
    uint64_t version_ = 0;
    bool finished_ = false;
};

}  // namespace phos::display
