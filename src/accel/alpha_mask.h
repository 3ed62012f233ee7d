// Alpha cut-outs (pbrt-v4's "alpha" shape parameter): whether a ray keeps a hit on a masked shape.
// pbrt-v4 (GeometricPrimitive::Intersect, PBR 4th ed. sec. 7.1.1) keeps a hit where alpha is 1,
// drops it where alpha is 0 and, in between, keeps it when a hash of the ray is at most alpha, so
// that the same ray always decides the same way. The accelerator asks this for every candidate hit
// of a masked shape (Embree filter functions for triangles and curves, the intersect callbacks of
// the analytic shapes and bilinear patches), so camera rays, shadow rays and photons all see it.
#pragma once

#include <cstdint>

#include "core/vec.h"
#include "scene/scene.h"

namespace phos::accel {

// Whether the shape has a mask at all; shapes without one never call the functions below.
inline bool has_alpha(const scene::Shape& shape) { return shape.alpha_texture >= 0 || shape.alpha < 1; }

// The shape's alpha at surface parameters `uv` (its constant, or the average of its float texture
// there), clamped to [0, 1].
float alpha_at(const scene::Scene& scene, const scene::Shape& shape, Vec2 uv);

// A number in [0, 1) that is a pure function of the ray's origin and direction bits and of `salt`
// (which candidate hit along the ray: geometry, primitive, instance, root), in the role of pbrt-v4's
// HashFloat(r.o, r.d). The salt makes overlapping masked surfaces along one ray decide
// independently, as pbrt-v4's re-spawned rays do.
float alpha_hash(Vec3 origin, Vec3 dir, uint64_t salt);

// pbrt-v4's rule: keep the hit when alpha >= 1; drop it when alpha <= 0; otherwise keep it when
// alpha_hash(origin, dir, salt) < alpha (probability alpha over distinct rays).
bool alpha_keeps(const scene::Scene& scene, const scene::Shape& shape, Vec2 uv, Vec3 origin, Vec3 dir,
                 uint64_t salt);

}  // namespace phos::accel
