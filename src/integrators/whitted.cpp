// Whitted ray tracing. The specular recursion follows one stochastically chosen branch (reflect or
// refract, by Fresnel) per sample, which is unbiased and converges with the pixel samples.
#include "integrators/whitted.h"

#include "integrators/direct_light.h"
#include "integrators/pixel_loop.h"

namespace phos::integrators {

void WhittedIntegrator::render(const Prepared& prepared, film::Film& film, Progress& progress) {
    render_pixels(prepared, film, progress, [&](const accel::Ray& ray, Sampler& sampler, RayCounts& rays) {
        return radiance(prepared, ray, sampler, rays);
    });
}

Rgb WhittedIntegrator::radiance(const Prepared& P, accel::Ray ray, Sampler& sampler, RayCounts& rays) {
    const scene::Scene& scene = P.scene;
    Rgb L(0.0f), beta(1.0f);
    int crossings = 0;
    for (int depth = 0;; ++depth) {
        accel::SurfaceHit hit;
        if (!P.accel.intersect(ray, hit)) {
            L += beta * (scene.background + P.escaped(normalize(ray.dir)));
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        if (P.passes_through(hit)) {
            if (++crossings > 256) break;
            ray = accel::spawn_ray(hit, ray.dir);
            --depth;
            continue;
        }
        const scene::Material& mat = scene.materials[size_t(hit.material)];
        L += beta * (P.emitted(hit, wo) + mat.emission);
        if (P.options.ambient) L += beta * mat.ambient * scene.ambient;

        const shading::Bsdf bsdf = P.bsdf(hit);
        if (bsdf.has_non_specular()) L += beta * sample_all_lights(P, hit, bsdf, wo, sampler, rays);
        // Recurse through mirrors and glass (sample_lobes selects by kind: kSpecular = mirror,
        // kTransmission = dielectric).
        constexpr uint32_t kRecurse = shading::kSpecular | shading::kTransmission;
        if (depth >= P.options.max_depth || !(bsdf.flags() & kRecurse)) break;

        const auto bs = bsdf.sample_lobes(kRecurse, wo, sampler.next(), sampler.next2());
        if (!bs || bs->weight.is_black()) break;
        beta *= bs->weight;
        if (!beta.is_finite() || beta.max() < 1e-6f) break;
        ray = accel::spawn_ray(hit, bs->wi);
        ++rays.bounce;
    }
    return L;
}

}  // namespace phos::integrators
