// The light-vertex hash grid (see vertex_grid.h): a counting sort of the points by bucket (the
// buckets and the sorted copy computed in parallel, the count and placement in order).
#include "integrators/vertex_grid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace phos::integrators {

void VertexGrid::build(const std::vector<Vec3>& points, float radius) {
    radius2_ = radius * radius;
    inv_cell_ = 1 / (2 * radius);
    order_.clear();
    start_.clear();
    x_.clear();
    y_.clear();
    z_.clear();
    if (points.empty() || !(radius > 0)) return;
    lo_ = points[0];
    for (const Vec3& p : points) lo_ = Vec3(std::min(lo_.x, p.x), std::min(lo_.y, p.y), std::min(lo_.z, p.z));
    uint64_t size = 1;
    while (size < points.size()) size <<= 1;
    mask_ = size - 1;
    start_.assign(size + 1, 0);
    std::vector<uint32_t> key(points.size());
    tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
        const Vec3& p = points[i];
        key[i] = bucket(cell(p.x, lo_.x), cell(p.y, lo_.y), cell(p.z, lo_.z));
    });
    for (uint32_t k : key) ++start_[k + 1];
    for (size_t b = 0; b < size; ++b) start_[b + 1] += start_[b];
    order_.resize(points.size());
    std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
    for (size_t i = 0; i < points.size(); ++i) order_[fill[key[i]]++] = uint32_t(i);
    x_.resize(points.size());
    y_.resize(points.size());
    z_.resize(points.size());
    tbb::parallel_for(size_t(0), points.size(), [&](size_t k) {
        const Vec3& p = points[order_[k]];
        x_[k] = p.x;
        y_[k] = p.y;
        z_[k] = p.z;
    });
}

}  // namespace phos::integrators
