// Light sampling with shadow rays (see direct_light.h).
#include "integrators/direct_light.h"

#include "core/warp.h"
#include "shading/surface_walk.h"

namespace phos::integrators {
namespace {

// Unoccluded contribution f * L * |cos| / pdf of one sample of light `i` (pdf excludes light choice).
Rgb light_contribution(const Prepared& P, size_t i, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf,
                       Vec3 wo, Vec2 u, RayCounts& rays, bool mis, float choose_pmf, int medium,
                       Sampler& sampler) {
    const shading::Light& light = P.lights[i];
    const shading::LightLiSample ls = light.sample_Li(hit.p, u);
    if (!(ls.pdf > 0) || ls.L.is_black()) return Rgb(0.0f);
    const Rgb f = bsdf.eval(wo, ls.wi) * std::fabs(dot(ls.wi, hit.ns));
    if (f.is_black()) return Rgb(0.0f);
    const accel::Ray shadow =
        ls.distance < kInf ? accel::spawn_ray_to(hit, ls.p_light) : accel::spawn_ray(hit, ls.wi);
    ++rays.shadow;
    Rgb T(1.0f);
    if (const shading::MediaSet* media = P.active_media()) {
        T = shading::shadow_transmittance(P.accel, media, shadow,
                                          shading::SurfaceWalk::medium_after(hit, ls.wi, medium), sampler);
        if (T.is_black()) return Rgb(0.0f);
    } else if (P.accel.occluded(shadow)) {
        return Rgb(0.0f);
    }
    float w = 1;
    if (mis && !ls.delta) w = warp::power_heuristic(choose_pmf * ls.pdf, bsdf.pdf(wo, ls.wi));
    return f * ls.L * T * (w / ls.pdf);
}

}  // namespace

Rgb sample_one_light(const Prepared& P, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf, Vec3 wo,
                     Sampler& sampler, RayCounts& rays, bool mis, int medium) {
    const float u_choose = sampler.next();
    const Vec2 u = sampler.next2();
    if (P.lights.size() == 0) return Rgb(0.0f);
    float pmf = 0;
    const size_t i = P.lights.choose(u_choose, pmf);
    if (!(pmf > 0)) return Rgb(0.0f);
    return light_contribution(P, i, hit, bsdf, wo, u, rays, mis, pmf, medium, sampler) * (1.0f / pmf);
}

Rgb sample_all_lights(const Prepared& P, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf, Vec3 wo,
                      Sampler& sampler, RayCounts& rays, int medium) {
    Rgb L(0.0f);
    for (size_t i = 0; i < P.lights.size(); ++i) {
        const Vec2 u = sampler.next2();
        L += light_contribution(P, i, hit, bsdf, wo, u, rays, false, 1.0f, medium, sampler);
    }
    return L;
}

Rgb light_in_medium(const Prepared& P, const shading::LightLiSample& ls, Vec3 p, Vec3 wo, int medium,
                    Sampler& sampler, RayCounts& rays) {
    if (!(ls.pdf > 0) || ls.L.is_black()) return Rgb(0.0f);
    const float phase = P.media[medium].phase().eval(wo, ls.wi);
    if (!(phase > 0)) return Rgb(0.0f);
    accel::Ray shadow;
    if (ls.distance < kInf) {
        shadow = accel::ray_to(p, ls.p_light);
    } else {
        shadow.origin = p;
        shadow.dir = ls.wi;
    }
    ++rays.shadow;
    const Rgb T = shading::shadow_transmittance(P.accel, P.active_media(), shadow, medium, sampler);
    return ls.L * T * phase;
}

Rgb sample_one_light_in_medium(const Prepared& P, Vec3 p, Vec3 wo, int medium, Sampler& sampler,
                               RayCounts& rays, bool mis) {
    const float u_choose = sampler.next();
    const Vec2 u = sampler.next2();
    if (P.lights.size() == 0) return Rgb(0.0f);
    float pmf = 0;
    const size_t i = P.lights.choose(u_choose, pmf);
    if (!(pmf > 0)) return Rgb(0.0f);
    const shading::LightLiSample ls = P.lights[i].sample_Li(p, u);
    const Rgb c = light_in_medium(P, ls, p, wo, medium, sampler, rays);
    if (c.is_black()) return c;
    float w = 1;
    if (mis && !ls.delta) w = warp::power_heuristic(pmf * ls.pdf, P.media[medium].phase().eval(wo, ls.wi));
    return c * (w / (pmf * ls.pdf));
}

}  // namespace phos::integrators
