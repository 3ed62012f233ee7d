// Hash-grid construction by counting sort (see hitpoint_grid.h).
#include "photon/hitpoint_grid.h"

#include <algorithm>
#include <cmath>

namespace phos::photon {

void HitPointGrid::build(const std::vector<Vec3>& positions, const std::vector<float>& r2) {
    levels_.clear();
    float max_r2 = 0;
    for (size_t i = 0; i < positions.size(); ++i)
        if (r2[i] > 0) max_r2 = std::max(max_r2, r2[i]);
    if (!(max_r2 > 0)) return;
    // Class k holds r² in (R²/4^(k+1), R²/4^k]; the last class everything smaller.
    std::vector<uint32_t> members[kMaxLevels];
    for (size_t i = 0; i < positions.size(); ++i) {
        if (!(r2[i] > 0)) continue;
        int k = 0;
        for (float bound = max_r2 * 0.25f; k + 1 < max_levels_ && r2[i] <= bound; bound *= 0.25f) ++k;
        members[k].push_back(uint32_t(i));
    }
    // A level costs every photon one more cell lookup, so classes share a level unless the finer
    // ones hold at least half of the points still to place: then the level splits there and
    // those points get cells sized by their own radius (so a few large pilot discs do not
    // inflate every photon's cell). Small classes of tiny radii ride along in the level above.
    size_t left = 0;
    for (int k = 0; k < max_levels_; ++k) left += members[k].size();
    std::vector<uint32_t> level;
    for (int k = 0; k < max_levels_; ++k) {
        level.insert(level.end(), members[k].begin(), members[k].end());
        left -= members[k].size();
        if (level.empty() || (left > 0 && 2 * left < left + level.size())) continue;
        build_level(levels_.emplace_back(), positions, r2, level);
        level.clear();
    }
}

void HitPointGrid::build_level(Level& l, const std::vector<Vec3>& positions, const std::vector<float>& r2,
                               const std::vector<uint32_t>& members) const {
    float max_r2 = 0;
    Vec3 lo(kInf), hi(-kInf);
    for (uint32_t i : members) {
        max_r2 = std::max(max_r2, r2[i]);
        lo = min(lo, positions[i]);
        hi = max(hi, positions[i]);
    }
    const float r_max = std::sqrt(max_r2);
    const float cell = cell_factor_ * r_max;
    l.inv_cell = 1 / cell;
    l.lo = lo - Vec3(r_max);
    const Vec3 ext = (hi + Vec3(r_max) - l.lo) * l.inv_cell;
    l.dims = Vec3(std::floor(ext.x) + 1, std::floor(ext.y) + 1, std::floor(ext.z) + 1);
    uint32_t buckets = 1;
    while (buckets < 2 * members.size()) buckets <<= 1;
    l.mask = buckets - 1;
    l.start.assign(size_t(buckets) + 1, 0);

    std::vector<uint32_t> seen;  // a vector, not a fixed array: small cell factors give > 64 cells
    // The distinct buckets of the cells point i's sphere overlaps (cells hashing alike merge).
    auto for_each_bucket = [&](uint32_t i, auto&& f) {
        const float r = std::sqrt(r2[i]);
        const Vec3 a = (positions[i] - Vec3(r) - l.lo) * l.inv_cell;
        const Vec3 b = (positions[i] + Vec3(r) - l.lo) * l.inv_cell;
        seen.clear();
        for (int z = int(a.z); z <= int(b.z); ++z)
            for (int y = int(a.y); y <= int(b.y); ++y)
                for (int x = int(a.x); x <= int(b.x); ++x) {
                    const uint32_t h = bucket(x, y, z, l.mask);
                    if (std::find(seen.begin(), seen.end(), h) != seen.end()) continue;
                    seen.push_back(h);
                    f(h);
                }
    };
    for (uint32_t i : members) for_each_bucket(i, [&](uint32_t h) { ++l.start[h + 1]; });
    for (size_t b = 0; b < buckets; ++b) l.start[b + 1] += l.start[b];
    l.entries.resize(l.start[buckets]);
    std::vector<uint32_t> fill(l.start.begin(), l.start.end() - 1);
    for (uint32_t i : members)
        for_each_bucket(i, [&](uint32_t h) {
            l.entries[fill[h]++] = {positions[i].x, positions[i].y, positions[i].z, r2[i], i};
        });
}

}  // namespace phos::photon
