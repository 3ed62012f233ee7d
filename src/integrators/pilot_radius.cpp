// Edge-aware bounds of the pilot's radii (see pilot_radius.h).
#include "integrators/pilot_radius.h"

#include <tbb/parallel_for.h>

#include "photon/hitpoint_grid.h"

namespace phos::integrators {

void bound_radii_at_edges(const std::vector<Vec3>& p, const std::vector<Vec3>& n, std::vector<double>& r2,
                          const std::vector<double>& r2_min) {
    const size_t count = p.size();
    std::vector<float> r2f(count);
    for (size_t i = 0; i < count; ++i) r2f[i] = float(std::max(r2[i], 0.0));
    photon::HitPointGrid grid;  // the points j whose disc holds point i: its neighbours
    grid.build(p, r2f);
    std::vector<double> bounded(r2);
    tbb::parallel_for(size_t(0), count, [&](size_t i) {
        if (!(r2[i] > 0)) return;
        double nearest = r2[i];  // squared distance to the nearest edge point found so far
        grid.query(p[i], [&](uint32_t j) {
            const Vec3 d = p[j] - p[i];
            const float d2 = dot(d, d);
            if (j == i || !(double(d2) < nearest)) return;
            if (std::fabs(dot(n[i], n[j])) < kEdgeNormalCos ||
                std::fabs(dot(d, n[i])) > kEdgePlaneSlope * std::sqrt(d2))
                nearest = d2;
        });
        const double floor = std::max(kEdgeMinShrink * kEdgeMinShrink * r2[i], r2_min[i]);
        bounded[i] = std::min(r2[i], std::max(nearest, floor));
    });
    r2.swap(bounded);
}

}  // namespace phos::integrators
