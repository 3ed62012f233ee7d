// Path tracing (Veach's estimator): at every non-specular vertex one light sample (light chosen by
// power) and one BSDF sample, combined with the power heuristic; emission found by BSDF sampling
// is weighted against the light-sampling pdf. `max_depth` counts bounces as pbrt's maxdepth does.
#include "integrators/path.h"

#include "core/warp.h"
#include "integrators/direct_light.h"
#include "integrators/emission.h"
#include "integrators/pixel_loop.h"
#include "shading/surface_walk.h"

namespace phos::integrators {

void PathIntegrator::render(const Prepared& prepared, film::Film& film, Progress& progress) {
    render_pixels(prepared, film, progress, [&](const accel::Ray& ray, Sampler& sampler, RayCounts& rays) {
        return radiance(prepared, ray, sampler, rays);
    });
}

Rgb PathIntegrator::radiance(const Prepared& P, accel::Ray ray, Sampler& sampler, RayCounts& rays) {
    const scene::Scene& scene = P.scene;
    Rgb L(0.0f), beta(1.0f);
    bool specular_bounce = true;  // the camera ray counts as specular: it sees emitters directly
    BsdfSampledFrom from{};       // the last vertex, when !specular_bounce
    int depth = 0;
    shading::SurfaceWalk walk(P.accel);
    while (true) {
        accel::SurfaceHit hit;
        const shading::SurfaceWalk::Event event = walk.next(ray, hit);
        if (event == shading::SurfaceWalk::Event::Lost) break;
        if (event == shading::SurfaceWalk::Event::Escaped) {
            const Vec3 dir = normalize(ray.dir);
            if (specular_bounce || P.options.background_light) L += beta * scene.background;
            for (size_t i : P.lights.infinite_lights()) {
                const Rgb Le = P.lights[i].Le(Vec3(0.0f), dir);
                if (Le.is_black()) continue;
                float w = 1;
                if (!specular_bounce)
                    w = warp::power_heuristic(from.pdf,
                                              P.lights.pmf(i) * P.lights[i].pdf_Li(from.p, dir, {}, {}));
                L += beta * Le * w;
            }
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        L += seen_emission(P, hit, wo, beta, specular_bounce ? nullptr : &from);

        if (depth++ == P.options.max_depth) break;
        const shading::Bsdf bsdf = P.bsdf(hit);

        if (bsdf.has_non_specular()) L += beta * sample_one_light(P, hit, bsdf, wo, sampler, rays, true);

        const auto bs = bsdf.sample(wo, sampler.next(), sampler.next2());
        if (!bs || bs->weight.is_black() || !(bs->pdf > 0)) break;
        beta *= bs->weight;
        specular_bounce = bs->is_specular();
        from = {hit.p, bs->pdf};
        ray = accel::spawn_ray(hit, bs->wi);
        ++rays.bounce;

        // Russian roulette once the path has some length; survivors are reweighted.
        if (depth > 3) {
            const float q = std::max(0.05f, 1.0f - beta.max());
            if (sampler.next() < q) break;
            beta *= 1.0f / (1.0f - q);
        }
        if (!beta.is_finite()) break;
    }
    return L;
}

}  // namespace phos::integrators
