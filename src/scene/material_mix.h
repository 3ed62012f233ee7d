// pbrt-v4's mix material resolved at a surface point: which of its two materials the point has.
// The accelerator resolves it when it completes a hit (SurfaceHit::material is never a mix), so
// every consumer of a hit (BSDFs, photon storage, interface and emission tests) sees one material.
#pragma once

#include "core/vec.h"
#include "scene/scene.h"

namespace phos::scene {

// The material a hit on `material` at point p with surface coordinates uv has: `material` itself
// unless it is a mix; a mix picks mix_b where a hash of (p, the two indices) as a uniform number
// in [0, 1) is below its amount (amount <= 0: always mix_a; >= 1: always mix_b), as pbrt-v4's
// MixMaterial::ChooseMaterial does (pbrt also hashes the outgoing direction; phos hashes the point
// alone, so that camera paths and photons meeting a point agree on its material). Mixes of mixes
// are followed down to a plain material.
int resolve_material(const Scene& scene, int material, Vec3 p, Vec2 uv);

// True if any material of the scene is a mix (only then need hits be resolved).
bool has_mix_materials(const Scene& scene);

}  // namespace phos::scene
