// Emission seen by camera paths (see emission.h).
#include "integrators/emission.h"

#include "core/warp.h"
#include "spectrum/color.h"

namespace phos::integrators {

SeenEmission seen_emission(const Prepared& P, const accel::SurfaceHit& hit, Vec3 wo, const Spectrum& beta,
                           const Wavelengths& lambda, bool camera_chain, const BsdfSampledFrom* from) {
    SeenEmission seen{Spectrum(0.0f), Rgb(0.0f)};
    const Spectrum Le = P.emitted(hit, wo, lambda);
    if (!Le.is_black()) {
        float w = 1;
        if (from) {
            const auto li = size_t(hit.area_light);
            const float light_pdf = P.lights.pmf(li) * P.lights[li].pdf_Li(from->p, -wo, hit.p, hit.ng);
            w = warp::power_heuristic(from->pdf, light_pdf);
        }
        seen.light = beta * Le * w;
    }
    if (camera_chain) seen.glow = spectrum::colour_through(beta, lambda, P.glow(hit.material));
    return seen;
}

Spectrum escaped_emission(const Prepared& P, Vec3 origin, Vec3 dir, const Spectrum& beta,
                          const Wavelengths& lambda, const BsdfSampledFrom* from) {
    Spectrum L(0.0f);
    if (!from || P.options.background_light) L += beta * P.background(lambda);
    for (size_t i : P.lights.infinite_lights()) {
        const Spectrum Le = P.lights[i].escaped_Le(origin, dir, lambda);
        if (Le.is_black()) continue;
        float w = 1;
        if (from)
            w = warp::power_heuristic(from->pdf, P.lights.pmf(i) * P.lights[i].pdf_Li(from->p, dir, {}, {}));
        L += beta * Le * w;
    }
    return L;
}

}  // namespace phos::integrators
