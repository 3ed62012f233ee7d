// Path tracing (Veach's estimator): at every non-specular vertex one light sample (light chosen by
// power) and one BSDF sample, combined with the power heuristic; emission found by BSDF sampling
// is weighted against the light-sampling pdf. `max_depth` counts bounces as pbrt's maxdepth does.
#include "integrators/path.h"

#include "core/warp.h"
#include "integrators/direct_light.h"
#include "integrators/emission.h"
#include "integrators/factory.h"
#include "render/path_recorder.h"
#include "render/pixel_loop.h"
#include "render/pixel_trace.h"
#include "shading/surface_walk.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

namespace {

// Where the path is, for the split into components (pixel_loop.h, RadianceParts): x is the first
// surface the camera sees directly.
enum class Stage {
    Camera,         // the camera ray
    SpecularChain,  // after one or more delta bounces from the camera
    FromX,          // the ray x's BSDF sampled from a non-delta lobe
    CausticChain,   // after x's non-delta bounce, delta bounces only
    Indirect,       // after two or more non-delta bounces
};

// The component of emission (or escaped light) found by a ray of stage s.
Rgb RadianceParts::*found_part(Stage s) {
    switch (s) {
        case Stage::Camera:
        case Stage::FromX:
            return &RadianceParts::direct;
        case Stage::SpecularChain:
            return &RadianceParts::specular;
        case Stage::CausticChain:
            return &RadianceParts::caustic;
        case Stage::Indirect:
            break;
    }
    return &RadianceParts::indirect;
}

// The component of light sampled at the vertex a ray of stage s reached.
Rgb RadianceParts::*sampled_part(Stage s) {
    if (s == Stage::Camera) return &RadianceParts::direct;
    if (s == Stage::SpecularChain) return &RadianceParts::specular;
    return &RadianceParts::indirect;
}

// Russian roulette once the path has some length; survivors are reweighted.
bool survives_roulette(int depth, Rgb& beta, Sampler& sampler) {
    if (depth > 3) {
        const float q = std::max(0.05f, 1.0f - beta.max());
        if (sampler.next() < q) return false;
        beta *= 1.0f / (1.0f - q);
    }
    return beta.is_finite();
}

Stage next_stage(Stage s, bool delta_bounce) {
    switch (s) {
        case Stage::Camera:
            return delta_bounce ? Stage::SpecularChain : Stage::FromX;
        case Stage::FromX:
        case Stage::CausticChain:
            return delta_bounce ? Stage::CausticChain : Stage::Indirect;
        case Stage::SpecularChain:
        case Stage::Indirect:
            break;
    }
    return s;
}

}  // namespace

void PathIntegrator::render(const Prepared& prepared, film::Film& film, Progress& progress) {
    const RadianceFn plain = [&](const Ray& ray, Sampler& sampler, RayCounts& rays) {
        return radiance(prepared, ray, sampler, rays);
    };
    if (prepared.options.layers)
        render_layers(prepared, film, budget_, "path", progress, integrator_layers("path"),
                      [&](const Ray& ray, Sampler& sampler, RayCounts& rays, RadianceParts& parts) {
                          return radiance(prepared, ray, sampler, rays, &parts);
                      });
    else
        render_pixels(prepared, film, budget_, "path", progress, plain);
    trace_pixel_samples(prepared, film, plain);  // --trace-pixel (pixel_trace.h)
}

Rgb PathIntegrator::radiance(const Prepared& P, Ray ray, Sampler& sampler, RayCounts& rays,
                             RadianceParts* parts) {
    const scene::Scene& scene = P.scene;
    Rgb L(0.0f), beta(1.0f);
    // Adds a contribution to the radiance and, with `parts`, to its component (and to the trace).
    const auto add = [&](Rgb c, Rgb RadianceParts::*part, TraceTerm term) {
        L += c;
        if (parts) parts->*part += c;
        if (auto* r = recorder()) r->add(term, c);
    };
    // Emission found by the path, light sampled at its vertex: the components of the path's stage.
    Stage stage = Stage::Camera;
    const auto found = [&](Rgb c) { add(c, found_part(stage), TraceTerm::Emission); };
    const auto sampled = [&](Rgb c) { add(c, sampled_part(stage), TraceTerm::Light); };
    bool specular_bounce = true;  // the camera ray counts as specular: it sees emitters directly
    BsdfSampledFrom from{};       // the last vertex, when !specular_bounce
    int depth = 0;
    const shading::MediaSet* media = P.active_media();
    shading::SurfaceWalk walk(P.accel, media, P.camera_medium());
    while (true) {
        accel::SurfaceHit hit;
        Rgb emitted(0.0f);
        const shading::SurfaceWalk::Event event =
            media ? walk.next(ray, hit, sampler, beta, emitted) : walk.next(ray, hit);
        if (!emitted.is_black()) found(emitted);
        if (auto* r = recorder()) r->vertex(P, event, ray, hit, walk, beta);
        if (event == shading::SurfaceWalk::Event::Lost || event == shading::SurfaceWalk::Event::Absorbed)
            break;
        if (event == shading::SurfaceWalk::Event::Medium) {
            // A real scattering event in a medium: light sampling and phase sampling, MIS-weighted
            // against each other like a surface vertex (the phase function is its own pdf).
            if (depth++ == P.options.max_depth) break;
            const Vec3 p = walk.medium_point(), wo = walk.medium_wo();
            sampled(beta * sample_one_light_in_medium(P, p, wo, walk.medium(), sampler, rays, true));
            Vec3 wi;
            const float pdf = P.media[walk.medium()].phase().sample(wo, sampler.next2(), wi);
            if (auto* r = recorder()) r->scattered_in_medium(wi, pdf);
            specular_bounce = false;
            stage = next_stage(stage, false);
            from = {p, pdf};
            ray = Ray{p, wi};
            ++rays.bounce;
            if (!survives_roulette(depth, beta, sampler)) break;
            continue;
        }
        if (event == shading::SurfaceWalk::Event::Escaped) {
            const Vec3 dir = normalize(ray.dir);
            if (specular_bounce || P.options.background_light) found(beta * scene.background);
            for (size_t i : P.lights.infinite_lights()) {
                const Rgb Le = P.lights[i].Le(Vec3(0.0f), dir);
                if (Le.is_black()) continue;
                float w = 1;
                if (!specular_bounce)
                    w = warp::power_heuristic(from.pdf,
                                              P.lights.pmf(i) * P.lights[i].pdf_Li(from.p, dir, {}, {}));
                found(beta * Le * w);
            }
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        const bool camera_chain = stage == Stage::Camera || stage == Stage::SpecularChain;
        found(seen_emission(P, hit, wo, beta, camera_chain, specular_bounce ? nullptr : &from));

        if (depth++ == P.options.max_depth) break;
        const shading::Bsdf bsdf = P.bsdf(hit);

        if (bsdf.has_non_specular())
            sampled(beta * sample_one_light(P, hit, bsdf, wo, sampler, rays, true, walk.medium()));

        const auto bs = bsdf.sample(wo, sampler.next(), sampler.next2());
        if (!bs || bs->weight.is_black() || !(bs->pdf > 0)) break;
        if (auto* r = recorder()) r->scattered(*bs);
        beta *= bs->weight;
        specular_bounce = bs->is_specular();
        stage = next_stage(stage, specular_bounce);
        from = {hit.p, bs->pdf};
        ray = accel::spawn_ray(hit, bs->wi);
        walk.leave(hit, bs->wi);
        ++rays.bounce;
        if (!survives_roulette(depth, beta, sampler)) break;
    }
    return L;
}

}  // namespace phos::integrators
