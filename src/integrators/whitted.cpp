// Whitted ray tracing. The specular recursion follows one stochastically chosen branch (reflect or
// refract, by Fresnel) per sample, which is unbiased and converges with the pixel samples.
#include "integrators/whitted.h"

#include "core/log.h"
#include "integrators/direct_light.h"
#include "integrators/emission.h"
#include "render/path_recorder.h"
#include "render/pixel_loop.h"
#include "shading/surface_walk.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

RenderDone WhittedIntegrator::render(const Prepared& prepared, film::Film& film, Progress& progress) {
    if (prepared.active_media())
        log::warn(
            "whitted renders the scene as if its participating media were vacuum; path, photonmap, "
            "ppm and sppm render them");
    return render_paths(prepared, film, budget_, "whitted", progress, layers_,
                        [&](const Ray& ray, Sampler& sampler, RayCounts& rays, RadianceParts* parts) {
                            return radiance(prepared, ray, sampler, rays, parts);
                        });
}

Rgb WhittedIntegrator::radiance(const Prepared& P, Ray ray, Sampler& sampler, RayCounts& rays,
                                RadianceParts* parts) {
    Wavelengths lambda = camera_wavelengths(sampler);
    PathRadiance L(lambda, parts);  // the estimate, split into components for --layers (path_radiance.h)
    Spectrum beta(1.0f);
    shading::SurfaceWalk walk(P.accel);
    for (int depth = 0;; ++depth) {
        accel::SurfaceHit hit;
        const shading::SurfaceWalk::Event event = walk.next(ray, hit);
        if (auto* r = recorder()) r->vertex(P, event, ray, hit, walk, beta);
        if (event == shading::SurfaceWalk::Event::Lost) break;
        if (event == shading::SurfaceWalk::Event::Escaped) {
            L.emission(beta * (P.background(lambda) + P.escaped(ray.origin, normalize(ray.dir), lambda)));
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        const SeenEmission seen = seen_emission(P, hit, wo, beta, lambda);
        L.emission(seen.light);
        L.emission(seen.glow);

        const shading::Bsdf bsdf = P.bsdf(hit);
        if (bsdf.has_non_specular())
            L.light(beta * sample_all_lights(P, hit, bsdf, wo, sampler, lambda, rays));
        // Recurse through mirrors and glass (sample_lobes selects by kind: kSpecular = mirror,
        // kTransmission = dielectric).
        constexpr uint32_t kRecurse = shading::kSpecular | shading::kTransmission;
        if (depth >= P.options.max_depth || !(bsdf.flags() & kRecurse)) break;

        const auto bs = bsdf.sample_lobes(kRecurse, wo, sampler.next(), sampler.next2(), lambda);
        if (!bs || bs->weight.is_black()) break;
        if (auto* r = recorder()) r->scattered(*bs);
        beta *= bs->weight;
        follow_dispersion(*bs, lambda, beta);
        if (!beta.is_finite() || beta.max() < 1e-6f) break;
        L.bounce(true);  // the recursion counts as delta: all it finds is specular
        ray = accel::spawn_ray(hit, bs->wi);
        ++rays.bounce;
    }
    return L.total();
}

}  // namespace phos::integrators
