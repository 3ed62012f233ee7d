// Whitted ray tracing. The specular recursion follows one stochastically chosen branch (reflect or
// refract, by Fresnel) per sample, which is unbiased and converges with the pixel samples.
#include "integrators/whitted.h"

#include "core/log.h"
#include "integrators/direct_light.h"
#include "integrators/emission.h"
#include "integrators/factory.h"
#include "render/path_recorder.h"
#include "render/pixel_loop.h"
#include "render/pixel_trace.h"
#include "shading/surface_walk.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

void WhittedIntegrator::render(const Prepared& prepared, film::Film& film, Progress& progress) {
    if (prepared.active_media())
        log::warn(
            "whitted renders the scene as if its participating media were vacuum; path, photonmap, "
            "ppm and sppm render them");
    const RadianceFn plain = [&](const Ray& ray, Sampler& sampler, RayCounts& rays) {
        return radiance(prepared, ray, sampler, rays);
    };
    if (prepared.options.layers)
        render_layers(prepared, film, budget_, "whitted", progress, integrator_layers("whitted"),
                      [&](const Ray& ray, Sampler& sampler, RayCounts& rays, RadianceParts& parts) {
                          return radiance(prepared, ray, sampler, rays, &parts);
                      });
    else
        render_pixels(prepared, film, budget_, "whitted", progress, plain);
    trace_pixel_samples(prepared, film, plain);  // --trace-pixel (pixel_trace.h)
}

Rgb WhittedIntegrator::radiance(const Prepared& P, Ray ray, Sampler& sampler, RayCounts& rays,
                                RadianceParts* parts) {
    Rgb L(0.0f), beta(1.0f);
    shading::SurfaceWalk walk(P.accel);
    for (int depth = 0;; ++depth) {
        // Adds a contribution to the radiance and, with `parts`, to its component (and to the trace).
        const auto add = [&](Rgb c, TraceTerm term) {
            L += c;
            if (parts) (depth == 0 ? parts->direct : parts->specular) += c;
            if (auto* r = recorder()) r->add(term, c);
        };
        accel::SurfaceHit hit;
        const shading::SurfaceWalk::Event event = walk.next(ray, hit);
        if (auto* r = recorder()) r->vertex(P, event, ray, hit, walk, beta);
        if (event == shading::SurfaceWalk::Event::Lost) break;
        if (event == shading::SurfaceWalk::Event::Escaped) {
            add(beta * (P.scene.background + P.escaped(normalize(ray.dir))), TraceTerm::Emission);
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        add(seen_emission(P, hit, wo, beta), TraceTerm::Emission);

        const shading::Bsdf bsdf = P.bsdf(hit);
        if (bsdf.has_non_specular())
            add(beta * sample_all_lights(P, hit, bsdf, wo, sampler, rays), TraceTerm::Light);
        // Recurse through mirrors and glass (sample_lobes selects by kind: kSpecular = mirror,
        // kTransmission = dielectric).
        constexpr uint32_t kRecurse = shading::kSpecular | shading::kTransmission;
        if (depth >= P.options.max_depth || !(bsdf.flags() & kRecurse)) break;

        const auto bs = bsdf.sample_lobes(kRecurse, wo, sampler.next(), sampler.next2());
        if (!bs || bs->weight.is_black()) break;
        if (auto* r = recorder()) r->scattered(*bs);
        beta *= bs->weight;
        if (!beta.is_finite() || beta.max() < 1e-6f) break;
        ray = accel::spawn_ray(hit, bs->wi);
        ++rays.bounce;
    }
    return L;
}

}  // namespace phos::integrators
