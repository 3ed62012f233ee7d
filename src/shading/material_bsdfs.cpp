// Per-material BSDFs built once (see material_bsdfs.h).
#include "shading/material_bsdfs.h"

namespace phos::shading {

MaterialBsdfs::MaterialBsdfs(const scene::Scene& scene, const BsdfOptions& options) : scene_(scene) {
    of_material_.reserve(scene.materials.size());
    for (const scene::Material& m : scene.materials) of_material_.push_back(Bsdf::of_material(m, options));
}

}  // namespace phos::shading
