// Small helpers for the accel tests: random transforms and directions driven by the deterministic
// phos::Sampler (shape constructors are in support/shapes.h).
#pragma once

#include <cmath>

#include "core/rng.h"
#include "scene/scene.h"
#include "support/shapes.h"

namespace phos::testing {

inline Vec3 random_unit(Sampler& rng) {
    const float z = 1 - 2 * rng.next();
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const float ph = 2 * kPi * rng.next();
    return {r * std::cos(ph), r * std::sin(ph), z};
}

inline Vec3 random_in(Sampler& rng, Vec3 lo, Vec3 hi) {
    return {lo.x + (hi.x - lo.x) * rng.next(), lo.y + (hi.y - lo.y) * rng.next(),
            lo.z + (hi.z - lo.z) * rng.next()};
}

// Rotation about a random axis, optionally with a non-uniform scale, then a translation.
inline Transform random_transform(Sampler& rng, Vec3 at, bool nonuniform) {
    Transform t = Transform::translate(at) * Transform::rotate(360 * rng.next(), random_unit(rng));
    if (nonuniform)
        t = t * Transform::scale({0.5f + 1.5f * rng.next(), 0.5f + 1.5f * rng.next(), 0.5f + rng.next()});
    return t;
}

}  // namespace phos::testing
