// A spatial hash grid over SPPM/PPM hit points with per-point radii, rebuilt every iteration:
// every point is entered in each cell its sphere's box overlaps (at most 8 with the default cell
// of one diameter), entries laid out by counting sort (SmallVCM / pbrt-v4 style), so a photon looks
// at a single cell per level. Radii differ a lot in long renders (pixels that never receive a
// photon keep their first radius while the others shrink), and one grid sized by the largest
// radius makes every photon scan many far points: so points are split into radius classes by
// powers of two (r in (R/2^(k+1), R/2^k], R the largest radius; the last class takes all smaller
// ones), and a level (a grid with cells sized by its own largest radius) starts at a class when
// the classes from there down hold at least half of the points not yet in a level; smaller
// classes share the level above. A photon visits one cell per level. The set of points a query
// reports does not depend on the levels.
// bench/hitpoint_lookup_bench.cpp compares it with a k-d tree.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace phos::photon {

class HitPointGrid {
public:
    // Builds over `positions` with squared radii `r2`; points with r2 <= 0 are left out.
    void build(const std::vector<Vec3>& positions, const std::vector<float>& r2);

    // Calls visit(index) for every point i with |p - positions[i]|² <= r2[i], each exactly once.
    template <class Visitor>
    void query(Vec3 p, Visitor&& visit) const {
        for (size_t l = 0; l < levels_.size(); ++l) {
            const uint32_t b = bucket_of(l, p);
            if (b == kNoBucket) continue;
            for (const Entry *en = bucket_begin(l, b), *end = bucket_end(l, b); en != end; ++en) {
                const float dx = p.x - en->x, dy = p.y - en->y, dz = p.z - en->z;
                if (dx * dx + dy * dy + dz * dz <= en->r2) visit(en->index);
            }
        }
    }

    // The same search for many query points at once: bin them by bucket_of(level, p) and test
    // each bin's points against that bucket's entries (what query() does per point, level by
    // level), so a bucket's entries are read once for all the points in it.
    struct Entry {
        float x, y, z, r2;
        uint32_t index;
    };
    static constexpr uint32_t kNoBucket = ~0u;
    size_t level_count() const { return levels_.size(); }
    uint32_t bucket_count(size_t level) const { return levels_[level].mask + 1; }
    // The bucket holding p's cell in `level`, or kNoBucket when p lies outside the level's cells.
    uint32_t bucket_of(size_t level, Vec3 p) const {
        const Level& l = levels_[level];
        const Vec3 c = (p - l.lo) * l.inv_cell;
        if (!(c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < l.dims.x && c.y < l.dims.y && c.z < l.dims.z))
            return kNoBucket;
        return bucket(int(c.x), int(c.y), int(c.z), l.mask);
    }
    const Entry* bucket_begin(size_t level, uint32_t b) const {
        return levels_[level].entries.data() + levels_[level].start[b];
    }
    const Entry* bucket_end(size_t level, uint32_t b) const {
        return levels_[level].entries.data() + levels_[level].start[b + 1];
    }

    // Cell edge in units of the largest radius (default 2: each point in at most 8 cells; smaller
    // cells mean fewer candidates per photon but more entries). Must be >= 0.5.
    void set_cell_factor(float f) { cell_factor_ = f; }

    // Radius classes considered (at most kMaxLevels, the default); so also the most levels.
    static constexpr int kMaxLevels = 8;
    void set_max_levels(int n) { max_levels_ = std::clamp(n, 1, kMaxLevels); }

private:
    struct Level {
        Vec3 lo{0.0f};
        float inv_cell = 0;
        Vec3 dims{0.0f};  // cells per axis (as floats, for the bounds test)
        uint32_t mask = 0;
        std::vector<uint32_t> start;  // bucket b's entries are [start[b], start[b+1])
        std::vector<Entry> entries;
    };
    static uint32_t bucket(int x, int y, int z, uint32_t mask) {
        const uint32_t h = (uint32_t(x) * 73856093u) ^ (uint32_t(y) * 19349663u) ^ (uint32_t(z) * 83492791u);
        return h & mask;
    }
    void build_level(Level& l, const std::vector<Vec3>& positions, const std::vector<float>& r2,
                     const std::vector<uint32_t>& members) const;

    float cell_factor_ = 2;
    int max_levels_ = kMaxLevels;
    std::vector<Level> levels_;
};

}  // namespace phos::photon
