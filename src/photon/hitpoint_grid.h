// A spatial hash grid over SPPM/PPM hit points with per-point radii, rebuilt every iteration:
// cell size = the largest diameter, every point entered in each cell its sphere's box overlaps
// (at most 8), entries laid out by counting sort (SmallVCM / pbrt-v4 style), so a photon looks at
// a single cell. bench/hitpoint_lookup_bench.cpp compares it with a k-d tree.
#pragma once

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
        if (entries_.empty()) return;
        const Vec3 c = (p - lo_) * inv_cell_;
        if (!(c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < dims_.x && c.y < dims_.y && c.z < dims_.z)) return;
        const uint32_t h = bucket(int(c.x), int(c.y), int(c.z));
        for (uint32_t e = start_[h], end = start_[h + 1]; e < end; ++e) {
            const Entry& en = entries_[e];
            const float dx = p.x - en.x, dy = p.y - en.y, dz = p.z - en.z;
            if (dx * dx + dy * dy + dz * dz <= en.r2) visit(en.index);
        }
    }

    // Cell edge in units of the largest radius (default 2: each point in at most 8 cells; smaller
    // cells mean fewer candidates per photon but more entries). Must be >= 0.5.
    void set_cell_factor(float f) { cell_factor_ = f; }

    size_t entry_count() const { return entries_.size(); }
    float cell_size() const { return inv_cell_ > 0 ? 1 / inv_cell_ : 0; }

private:
    struct Entry {
        float x, y, z, r2;
        uint32_t index;
    };
    uint32_t bucket(int x, int y, int z) const {
        const uint32_t h = (uint32_t(x) * 73856093u) ^ (uint32_t(y) * 19349663u) ^ (uint32_t(z) * 83492791u);
        return h & mask_;
    }

    Vec3 lo_{0.0f};
    float inv_cell_ = 0;
    float cell_factor_ = 2;
    Vec3 dims_{0.0f};  // cells per axis (as floats, for the bounds test)
    uint32_t mask_ = 0;
    std::vector<uint32_t> start_;  // bucket b's entries are [start_[b], start_[b+1])
    std::vector<Entry> entries_;
};

}  // namespace phos::photon
