// Path tracing (Veach's estimator): at every non-specular vertex one light sample (light chosen by
// power) and one BSDF sample, combined with the power heuristic; emission found by BSDF sampling
// is weighted against the light-sampling pdf. `max_depth` counts bounces as pbrt's maxdepth does.
#include "integrators/path.h"

#include "core/warp.h"
#include "integrators/direct_light.h"
#include "integrators/pixel_loop.h"

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
    float prev_pdf = 0;
    Vec3 prev_p;
    int depth = 0;
    int crossings = 0;
    while (true) {
        accel::SurfaceHit hit;
        if (!P.accel.intersect(ray, hit)) {
            const Vec3 dir = normalize(ray.dir);
            if (specular_bounce || P.options.background_light) L += beta * scene.background;
            for (size_t i : P.lights.infinite_lights()) {
                const Rgb Le = P.lights[i].Le(Vec3(0.0f), dir);
                if (Le.is_black()) continue;
                float w = 1;
                if (!specular_bounce)
                    w = warp::power_heuristic(prev_pdf,
                                              P.lights.pmf(i) * P.lights[i].pdf_Li(prev_p, dir, {}, {}));
                L += beta * Le * w;
            }
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        if (P.passes_through(hit)) {
            if (++crossings > 256) break;
            ray = accel::spawn_ray(hit, ray.dir);
            continue;
        }
        const scene::Material& mat = scene.materials[size_t(hit.material)];

        // Light emitted by the surface we hit.
        const Rgb Le = P.emitted(hit, wo);
        if (!Le.is_black()) {
            float w = 1;
            if (!specular_bounce) {
                const auto li = size_t(hit.area_light);
                const float light_pdf = P.lights.pmf(li) * P.lights[li].pdf_Li(prev_p, -wo, hit.p, hit.ng);
                w = warp::power_heuristic(prev_pdf, light_pdf);
            }
            L += beta * Le * w;
        }
        // The .scn glow is seen only by camera and specular rays (see docs/formats/scn.md).
        if (specular_bounce) L += beta * mat.emission;
        if (depth == 0 && P.options.ambient) L += beta * mat.ambient * scene.ambient;

        if (depth++ == P.options.max_depth) break;
        const shading::Bsdf bsdf = P.bsdf(hit);

        if (bsdf.has_non_specular()) L += beta * sample_one_light(P, hit, bsdf, wo, sampler, rays, true);

        const auto bs = bsdf.sample(wo, sampler.next(), sampler.next2());
        if (!bs || bs->weight.is_black() || !(bs->pdf > 0)) break;
        beta *= bs->weight;
        specular_bounce = bs->is_specular();
        prev_pdf = bs->pdf;
        prev_p = hit.p;
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
