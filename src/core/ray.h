// A ray: origin, direction and the parametric interval searched. Every layer that traces,
// spawns or records rays uses it (the accelerator's hits and spawning are in accel/ray.h).
#pragma once

#include "core/vec.h"

namespace phos {

struct Ray {
    Vec3 origin;
    Vec3 dir;  // need not be normalised; t is measured in units of |dir|
    float tmin = 0.0f;
    float tmax = kInf;
};

}  // namespace phos
