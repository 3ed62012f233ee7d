// Emission seen by camera paths (see emission.h).
#include "integrators/emission.h"

#include "core/warp.h"

namespace phos::integrators {

Rgb seen_emission(const Prepared& P, const accel::SurfaceHit& hit, Vec3 wo, Rgb beta, bool camera_chain,
                  const BsdfSampledFrom* from) {
    Rgb L(0.0f);
    const Rgb Le = P.emitted(hit, wo);
    if (!Le.is_black()) {
        float w = 1;
        if (from) {
            const auto li = size_t(hit.area_light);
            const float light_pdf = P.lights.pmf(li) * P.lights[li].pdf_Li(from->p, -wo, hit.p, hit.ng);
            w = warp::power_heuristic(from->pdf, light_pdf);
        }
        L = beta * Le * w;
    }
    if (!camera_chain) return L;
    const scene::Material& mat = P.scene.materials[size_t(hit.material)];
    L += beta * mat.emission;
    if (P.options.ambient) L += beta * mat.ambient * P.scene.ambient;
    return L;
}

Rgb escaped_emission(const Prepared& P, Vec3 dir, Rgb beta, const BsdfSampledFrom* from) {
    Rgb L(0.0f);
    if (!from || P.options.background_light) L += beta * P.scene.background;
    for (size_t i : P.lights.infinite_lights()) {
        const Rgb Le = P.lights[i].Le(Vec3(0.0f), dir);
        if (Le.is_black()) continue;
        float w = 1;
        if (from)
            w = warp::power_heuristic(from->pdf, P.lights.pmf(i) * P.lights[i].pdf_Li(from->p, dir, {}, {}));
        L += beta * Le * w;
    }
    return L;
}

}  // namespace phos::integrators
