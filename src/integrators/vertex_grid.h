// A hashed uniform grid over the light vertices of one VCM iteration, for vertex merging: every
// vertex within radius r of a query point, bucket by bucket and in the order the vertices were
// given within a bucket (so sums over them are the same for any thread count). Cells are 2r wide,
// so a query visits at most the 8 cells around its point (Georgiev et al. 2012's hash grid, as in
// SmallVCM), each bucket once. The points are kept sorted by bucket, so a bucket's candidates lie
// side by side in memory; callers keep their per-vertex data in the same order (order()). The
// sorted positions are kept as three coordinate arrays, so a bucket's distances are computed four
// at a time (SSE, the scalar operations' order: the same bits).
#pragma once

#include <xmmintrin.h>

#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace phos::integrators {

class VertexGrid {
public:
    // Indexes `points` for queries of radius `radius`.
    void build(const std::vector<Vec3>& points, float radius);
    // The sorted order: slot k holds points[order()[k]].
    const std::vector<uint32_t>& order() const { return order_; }

    // Calls visit(slot, distance^2) for every point within the radius of `p` (slot: its place in
    // order()), by bucket then index.
    template <class Visit>
    void query(Vec3 p, Visit&& visit) const {
        query(p, radius2_, visit);
    }
    // The same within a smaller radius, radius2 <= the grid's radius^2.
    template <class Visit>
    void query(Vec3 p, float radius2, Visit&& visit) const;

private:
    uint32_t bucket(int64_t x, int64_t y, int64_t z) const {
        const uint64_t h = uint64_t(x) * 73856093ull ^ uint64_t(y) * 19349663ull ^ uint64_t(z) * 83492791ull;
        return uint32_t(h & mask_);
    }
    int64_t cell(float v, float lo) const { return int64_t(std::floor((v - lo) * inv_cell_)); }

    std::vector<float> x_, y_, z_;  // the points' coordinates in order()
    float radius2_ = 0, inv_cell_ = 0;
    Vec3 lo_;
    uint64_t mask_ = 0;
    std::vector<uint32_t> start_;  // bucket b holds order_[start_[b] .. start_[b + 1])
    std::vector<uint32_t> order_;
};

template <class Visit>
void VertexGrid::query(Vec3 p, float radius2, Visit&& visit) const {
    if (order_.empty()) return;
    // The cell holding p and, per axis, the neighbour on the side of p's half of its cell.
    const float fx = (p.x - lo_.x) * inv_cell_, fy = (p.y - lo_.y) * inv_cell_,
                fz = (p.z - lo_.z) * inv_cell_;
    const int64_t cx = int64_t(std::floor(fx)), cy = int64_t(std::floor(fy)), cz = int64_t(std::floor(fz));
    const int64_t nx = fx - float(cx) < 0.5f ? cx - 1 : cx + 1;
    const int64_t ny = fy - float(cy) < 0.5f ? cy - 1 : cy + 1;
    const int64_t nz = fz - float(cz) < 0.5f ? cz - 1 : cz + 1;
    uint32_t buckets[8];
    int n = 0;
    for (int i = 0; i < 8; ++i) {
        const uint32_t b = bucket(i & 1 ? nx : cx, i & 2 ? ny : cy, i & 4 ? nz : cz);
        bool seen = false;
        for (int j = 0; j < n; ++j) seen |= buckets[j] == b;
        if (!seen) buckets[n++] = b;
    }
    const __m128 px = _mm_set1_ps(p.x), py = _mm_set1_ps(p.y), pz = _mm_set1_ps(p.z),
                 r2 = _mm_set1_ps(radius2);
    for (int i = 0; i < n; ++i) {
        uint32_t k = start_[buckets[i]];
        const uint32_t end = start_[buckets[i] + 1];
        for (; k + 4 <= end; k += 4) {
            const __m128 dx = _mm_sub_ps(_mm_loadu_ps(&x_[k]), px), dy = _mm_sub_ps(_mm_loadu_ps(&y_[k]), py),
                         dz = _mm_sub_ps(_mm_loadu_ps(&z_[k]), pz);
            const __m128 d2 =
                _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
            int inside = _mm_movemask_ps(_mm_cmple_ps(d2, r2));
            if (!inside) continue;
            alignas(16) float v[4];
            _mm_store_ps(v, d2);
            for (; inside; inside &= inside - 1) {
                const int j = __builtin_ctz(unsigned(inside));
                visit(k + uint32_t(j), v[j]);
            }
        }
        for (; k < end; ++k) {
            const float dx = x_[k] - p.x, dy = y_[k] - p.y, dz = z_[k] - p.z;
            const float d2 = dx * dx + dy * dy + dz * dz;
            if (d2 <= radius2) visit(k, d2);
        }
    }
}

}  // namespace phos::integrators
