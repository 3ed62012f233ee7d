// Every material's BSDF built once per scene (Bsdf::of_material), so that a BSDF at a hit is a
// copy placed there (Bsdf::placed: shading frame and textures) instead of a construction from the
// material: the same object, bit for bit, in a fraction of the work. Integrators and the photon
// tracer build one BSDF per surface event.
#pragma once

#include <vector>

#include "accel/embree_scene.h"
#include "scene/scene.h"
#include "shading/bsdf.h"

namespace phos::shading {

class MaterialBsdfs {
public:
    // Keeps a reference to `scene`, which must outlive this object.
    MaterialBsdfs(const scene::Scene& scene, const BsdfOptions& options);

    // The BSDF at `hit`: Bsdf(scene.materials[hit.material], hit, scene, options).
    Bsdf at(const accel::SurfaceHit& hit) const {
        const size_t m = size_t(hit.material);
        return of_material_[m].placed(scene_.materials[m], hit, scene_);
    }

    // The BSDF at `hit` when it is a lone Lambert lobe (Bsdf::is_lambertian): its lobe as at(hit)
    // would hold it, without building the whole BSDF (most photon bounces). False otherwise.
    bool lambert_at(const accel::SurfaceHit& hit, LambertLobe& lobe) const {
        const size_t m = size_t(hit.material);
        if (!of_material_[m].is_lambertian()) return false;
        of_material_[m].place_lambert(scene_.materials[m], hit, scene_, lobe);
        return true;
    }

private:
    const scene::Scene& scene_;
    std::vector<Bsdf> of_material_;
};

}  // namespace phos::shading
