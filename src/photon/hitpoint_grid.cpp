// Hash-grid construction by counting sort (see hitpoint_grid.h).
#include "photon/hitpoint_grid.h"

#include <algorithm>
#include <cmath>

namespace phos::photon {

void HitPointGrid::build(const std::vector<Vec3>& positions, const std::vector<float>& r2) {
    entries_.clear();
    start_.clear();
    float max_r2 = 0;
    Vec3 lo(kInf), hi(-kInf);
    size_t count = 0;
    for (size_t i = 0; i < positions.size(); ++i) {
        if (!(r2[i] > 0)) continue;
        max_r2 = std::max(max_r2, r2[i]);
        lo = min(lo, positions[i]);
        hi = max(hi, positions[i]);
        ++count;
    }
    if (count == 0) return;
    const float r_max = std::sqrt(max_r2);
    const float cell = cell_factor_ * r_max;
    inv_cell_ = 1 / cell;
    lo_ = lo - Vec3(r_max);
    const Vec3 ext = (hi + Vec3(r_max) - lo_) * inv_cell_;
    dims_ = Vec3(std::floor(ext.x) + 1, std::floor(ext.y) + 1, std::floor(ext.z) + 1);
    uint32_t buckets = 1;
    while (buckets < 2 * count) buckets <<= 1;
    mask_ = buckets - 1;
    start_.assign(size_t(buckets) + 1, 0);

    std::vector<uint32_t> seen;  // a vector, not a fixed array: small cell factors give > 64 cells
    // The distinct buckets of the cells point i's sphere overlaps (cells hashing alike merge).
    auto for_each_bucket = [&](size_t i, auto&& f) {
        const float r = std::sqrt(r2[i]);
        const Vec3 a = (positions[i] - Vec3(r) - lo_) * inv_cell_;
        const Vec3 b = (positions[i] + Vec3(r) - lo_) * inv_cell_;
        seen.clear();
        for (int z = int(a.z); z <= int(b.z); ++z)
            for (int y = int(a.y); y <= int(b.y); ++y)
                for (int x = int(a.x); x <= int(b.x); ++x) {
                    const uint32_t h = bucket(x, y, z);
                    if (std::find(seen.begin(), seen.end(), h) != seen.end()) continue;
                    seen.push_back(h);
                    f(h);
                }
    };
    for (size_t i = 0; i < positions.size(); ++i)
        if (r2[i] > 0) for_each_bucket(i, [&](uint32_t h) { ++start_[h + 1]; });
    for (size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
    entries_.resize(start_[buckets]);
    std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
    for (size_t i = 0; i < positions.size(); ++i)
        if (r2[i] > 0)
            for_each_bucket(i, [&](uint32_t h) {
                entries_[fill[h]++] = {positions[i].x, positions[i].y, positions[i].z, r2[i], uint32_t(i)};
            });
}

}  // namespace phos::photon
