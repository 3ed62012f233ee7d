// An axis-aligned bounding box of points: what the accelerator reports for a scene and what the
// photon, camera and integrator code size their searches and radii by.
#pragma once

#include "core/vec.h"

namespace phos {

struct Bounds {
    Vec3 lo{kInf}, hi{-kInf};
    bool empty() const { return lo.x > hi.x; }
    Vec3 center() const { return (lo + hi) * 0.5f; }
    Vec3 extent() const { return hi - lo; }
    void extend(Vec3 p) {
        lo = min(lo, p);
        hi = max(hi, p);
    }
};

}  // namespace phos
