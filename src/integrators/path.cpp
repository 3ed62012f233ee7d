// Path tracing (Veach's estimator): at every non-specular vertex one light sample (light chosen by
// power) and one BSDF sample, combined with the power heuristic; emission found by BSDF sampling
// is weighted against the light-sampling pdf. `max_depth` counts bounces as pbrt's maxdepth does.
// Path regularisation (Kaplanyan & Dachsbacher 2013, sec. 4): after the path's first non-delta
// bounce, every lobe sharper than a Phong lobe of exponent N (s + 1)^(1/3) (--regularize N, camera
// sample s of the pixel) is widened to it (Bsdf::regularized), so light that reaches a diffuse
// surface through mirrors, glass or sharp glossy lobes (caustics, glints behind frosted glass) is
// found by next-event estimation at the widened vertex instead of by rare hits: fewer fireflies.
// The bandwidth shrinks as samples grow (the bias with it, as in progressive photon mapping's
// radius), so the pixel's average converges to the unregularised image.
#include "integrators/path.h"

#include <cmath>

#include "integrators/direct_light.h"
#include "integrators/emission.h"
#include "render/path_recorder.h"
#include "render/pixel_loop.h"
#include "shading/surface_walk.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

namespace {

// Russian roulette once the path has some length; survivors are reweighted.
bool survives_roulette(int depth, Spectrum& beta, Sampler& sampler) {
    if (depth > 3) {
        const float q = std::max(0.05f, 1.0f - beta.max());
        if (sampler.next() < q) return false;
        beta *= 1.0f / (1.0f - q);
    }
    return beta.is_finite();
}

}  // namespace

RenderDone PathIntegrator::render(const Prepared& prepared, film::Film& film, Progress& progress) {
    return render_paths(prepared, film, budget_, "path", progress, layers_,
                        [&](const Ray& ray, Sampler& sampler, RayCounts& rays, RadianceParts* parts) {
                            return radiance(prepared, ray, sampler, rays, parts);
                        });
}

Rgb PathIntegrator::radiance(const Prepared& P, Ray ray, Sampler& sampler, RayCounts& rays,
                             RadianceParts* parts) {
    Wavelengths lambda = camera_wavelengths(sampler);
    PathRadiance L(lambda, parts);  // the estimate, split into components for --layers (path_radiance.h)
    Spectrum beta(1.0f);
    bool specular_bounce = true;  // the camera ray counts as specular: it sees emitters directly
    // Whether surfaces show the .scn glow and ambient terms (emission.h): on the camera ray and
    // after a delta first bounce.
    bool camera_chain = true;
    bool rough = false;      // the path has had a non-delta bounce: later vertices are regularised
    BsdfSampledFrom from{};  // the last vertex, when !specular_bounce
    const float widest = P.options.regularize > 0
                             ? P.options.regularize * std::cbrt(float(current_sample_index()) + 1.0f)
                             : 0.0f;
    int depth = 0;
    const shading::MediaSet* media = P.active_media();
    shading::SurfaceWalk walk(P.accel, media, P.camera_medium());
    while (true) {
        accel::SurfaceHit hit;
        Spectrum emitted(0.0f);
        const shading::SurfaceWalk::Event event =
            media ? walk.next(ray, hit, sampler, lambda, beta, emitted) : walk.next(ray, hit);
        if (!emitted.is_black()) L.emission(emitted);
        if (auto* r = recorder()) r->vertex(P, event, ray, hit, walk, beta);
        if (event == shading::SurfaceWalk::Event::Lost || event == shading::SurfaceWalk::Event::Absorbed)
            break;
        if (event == shading::SurfaceWalk::Event::Medium) {
            // A real scattering event in a medium: light sampling and phase sampling, MIS-weighted
            // against each other like a surface vertex (the phase function is its own pdf).
            if (depth++ == P.options.max_depth) break;
            const Vec3 p = walk.medium_point(), wo = walk.medium_wo();
            L.light(beta * sample_one_light_in_medium(P, p, wo, walk.medium(), sampler, lambda, rays, true));
            Vec3 wi;
            const float pdf = P.media[walk.medium()].phase().sample(wo, sampler.next2(), wi);
            if (auto* r = recorder()) r->scattered_in_medium(wi, pdf);
            if (depth == 1) camera_chain = false;
            specular_bounce = false;
            rough = true;
            L.bounce(false);
            from = {p, pdf};
            ray = Ray{p, wi};
            ++rays.bounce;
            if (!survives_roulette(depth, beta, sampler)) break;
            continue;
        }
        if (event == shading::SurfaceWalk::Event::Escaped) {
            L.emission(escaped_emission(P, ray.origin, normalize(ray.dir), beta, lambda,
                                        specular_bounce ? nullptr : &from));
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        const SeenEmission seen =
            seen_emission(P, hit, wo, beta, lambda, camera_chain, specular_bounce ? nullptr : &from);
        L.emission(seen.light);
        L.emission(seen.glow);

        if (depth++ == P.options.max_depth) break;
        // A subsurface material's boundary is not widened: the walk inside crosses it many times,
        // and each widened crossing would lose energy (7 % on a white sphere at 256 spp).
        const bool widen =
            rough && widest > 0 && P.scene.materials[size_t(hit.material)].subsurface_medium < 0;
        const shading::Bsdf bsdf = widen ? P.bsdf(hit).regularized(widest) : P.bsdf(hit);

        if (bsdf.has_non_specular())
            L.light(beta * sample_one_light(P, hit, bsdf, wo, sampler, lambda, rays, true, walk.medium()),
                    bsdf.only_widened());

        const auto bs = bsdf.sample(wo, sampler.next(), sampler.next2(), lambda);
        if (!bs || bs->weight.is_black() || !(bs->pdf > 0)) break;
        if (auto* r = recorder()) r->scattered(*bs);
        beta *= bs->weight;
        follow_dispersion(*bs, lambda, beta);
        specular_bounce = bs->is_specular();
        rough = rough || !specular_bounce;
        if (depth == 1) camera_chain = specular_bounce;
        // A lobe widened from a mirror or glass still counts as specular for the layers.
        L.bounce(specular_bounce || (bs->flags & shading::kWidened));
        from = {hit.p, bs->pdf};
        ray = accel::spawn_ray(hit, bs->wi);
        walk.leave(hit, bs->wi);
        ++rays.bounce;
        if (!survives_roulette(depth, beta, sampler)) break;
    }
    return L.total();
}

}  // namespace phos::integrators
