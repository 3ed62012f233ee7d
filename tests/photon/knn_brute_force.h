// Reference k-nearest-neighbour query for the photon tests: the same query as PhotonKdTree::knn by
// examining every photon, with the tree's own squared distance so the answers compare exactly.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "photon/kdtree.h"

namespace phos::testing {

using photon::KnnResult;
using photon::Neighbour;
using photon::Photon;

// The neighbours sorted by (dist2, index); index is the position in `photons`. `out` must hold k
// entries.
inline KnnResult knn_brute_force(std::span<const Photon> photons, Vec3 q, uint32_t k, float max_dist2,
                                 Neighbour* out) {
    KnnResult r;
    if (k == 0 || !(max_dist2 >= 0)) return r;
    std::vector<Neighbour> all;
    for (uint32_t i = 0; i < photons.size(); ++i) {
        const float d2 = photon::detail::dist2(photons[i].position, q);
        if (d2 <= max_dist2) all.push_back({i, d2});
    }
    const auto less = [](const Neighbour& a, const Neighbour& b) {
        return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.index < b.index);
    };
    const size_t m = std::min<size_t>(k, all.size());
    std::partial_sort(all.begin(), all.begin() + m, all.end(), less);
    std::copy(all.begin(), all.begin() + m, out);
    r.count = uint32_t(m);
    r.max_dist2 = m > 0 ? all[m - 1].dist2 : 0.0f;
    return r;
}

}  // namespace phos::testing
