// Light sampling with shadow rays (see direct_light.h).
#include "integrators/direct_light.h"

#include "core/warp.h"
#include "render/path_recorder.h"
#include "shading/medium_tracking.h"
#include "shading/surface_walk.h"
#include "spectrum/color.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

namespace {

// Records a light sample for --trace-pixel (path_recorder.h): `value` is what it adds unoccluded
// (w / pdf included, the light's selection pmf not), `T` its visibility (-1: no shadow ray).
void record_light(PathRecorder& r, size_t i, Vec3 from, const shading::LightLiSample& ls, float pmf, float w,
                  Spectrum value, int visible, Spectrum T) {
    TracedLight l;
    l.light = int(i);
    l.from = from;
    l.direction = ls.wi;
    l.distance = ls.distance;
    l.pdf = ls.pdf * pmf;
    l.mis_weight = w;
    l.visible = visible;
    l.transmittance = T;
    if (visible == 1) l.contribution = value * T * (1.0f / pmf);
    r.light(l);
}

// The same for a light sample in a medium whose contribution before 1 / pdf (transmittance and
// MIS weight included) is `c`.
void record_light_in_medium(PathRecorder& r, size_t i, Vec3 from, const shading::LightLiSample& ls, float pmf,
                            Spectrum c) {
    const bool sent = ls.pdf > 0 && !ls.L.is_black();
    record_light(r, i, from, ls, pmf, 1, sent ? c * (1.0f / ls.pdf) : Spectrum(0.0f),
                 !sent          ? -1
                 : c.is_black() ? 0
                                : 1,
                 Spectrum(1.0f));
}

// Unoccluded contribution f * L * |cos| / pdf of one sample of light `i` (pdf excludes light choice).
Spectrum light_contribution(const Prepared& P, size_t i, const accel::SurfaceHit& hit,
                            const shading::Bsdf& bsdf, Vec3 wo, Vec2 u, RayCounts& rays, bool mis,
                            float choose_pmf, int medium, Sampler& sampler, const Wavelengths& lambda) {
    const shading::Light& light = P.lights[i];
    const shading::LightLiSample ls = light.sample_Li(hit.p, u, lambda);
    PathRecorder* r = recorder();
    if (!(ls.pdf > 0) || ls.L.is_black()) {
        if (r) record_light(*r, i, hit.p, ls, choose_pmf, 1, Spectrum(0.0f), -1, Spectrum(0.0f));
        return Spectrum(0.0f);
    }
    const Spectrum f = bsdf.eval(wo, ls.wi, lambda) * std::fabs(dot(ls.wi, bsdf.frame().n));
    if (f.is_black()) {
        if (r) record_light(*r, i, hit.p, ls, choose_pmf, 1, Spectrum(0.0f), -1, Spectrum(0.0f));
        return Spectrum(0.0f);
    }
    const Ray shadow =
        ls.distance < kInf ? accel::spawn_ray_to(hit, ls.p_light) : accel::spawn_ray(hit, ls.wi);
    ++rays.shadow;
    Spectrum T(1.0f);
    if (const shading::MediaSet* media = P.active_media())
        T = shading::shadow_transmittance(
            P.accel, media, shadow, shading::SurfaceWalk::medium_after(hit, ls.wi, medium), sampler, lambda);
    else if (P.accel.occluded(shadow))
        T = Spectrum(0.0f);
    float w = 1;
    if (mis && !ls.delta && (!T.is_black() || r))
        w = warp::power_heuristic(choose_pmf * ls.pdf, bsdf.pdf(wo, ls.wi));
    if (r) record_light(*r, i, hit.p, ls, choose_pmf, w, f * ls.L * (w / ls.pdf), T.is_black() ? 0 : 1, T);
    if (T.is_black()) return Spectrum(0.0f);
    return f * ls.L * T * (w / ls.pdf);
}

}  // namespace

Spectrum sample_one_light(const Prepared& P, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf, Vec3 wo,
                          Sampler& sampler, const Wavelengths& lambda, RayCounts& rays, bool mis,
                          int medium) {
    const float u_choose = sampler.next();
    const Vec2 u = sampler.next2();
    return sample_one_light(P, hit, bsdf, wo, u_choose, u, sampler, lambda, rays, mis, medium);
}

Spectrum sample_one_light(const Prepared& P, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf, Vec3 wo,
                          float u_choose, Vec2 u, Sampler& sampler, const Wavelengths& lambda,
                          RayCounts& rays, bool mis, int medium) {
    if (P.lights.size() == 0) return Spectrum(0.0f);
    float pmf = 0;
    const size_t i = P.lights.choose(u_choose, pmf);
    if (!(pmf > 0)) return Spectrum(0.0f);
    return light_contribution(P, i, hit, bsdf, wo, u, rays, mis, pmf, medium, sampler, lambda) * (1.0f / pmf);
}

Spectrum sample_all_lights(const Prepared& P, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf,
                           Vec3 wo, Sampler& sampler, const Wavelengths& lambda, RayCounts& rays,
                           int medium) {
    Spectrum L(0.0f);
    for (size_t i = 0; i < P.lights.size(); ++i) {
        const Vec2 u = sampler.next2();
        L += light_contribution(P, i, hit, bsdf, wo, u, rays, false, 1.0f, medium, sampler, lambda);
    }
    return L;
}

Spectrum light_in_medium(const Prepared& P, const shading::LightLiSample& ls, Vec3 p, Vec3 wo, int medium,
                         Sampler& sampler, const Wavelengths& lambda, RayCounts& rays) {
    if (!(ls.pdf > 0) || ls.L.is_black()) return Spectrum(0.0f);
    const float phase = P.media[medium].phase().eval(wo, ls.wi);
    if (!(phase > 0)) return Spectrum(0.0f);
    Ray shadow;
    if (ls.distance < kInf) {
        shadow = accel::ray_to(p, ls.p_light);
    } else {
        shadow.origin = p;
        shadow.dir = ls.wi;
    }
    ++rays.shadow;
    const Spectrum T =
        shading::shadow_transmittance(P.accel, P.active_media(), shadow, medium, sampler, lambda);
    return ls.L * T * phase;
}

Spectrum sample_one_light_in_medium(const Prepared& P, Vec3 p, Vec3 wo, int medium, Sampler& sampler,
                                    const Wavelengths& lambda, RayCounts& rays, bool mis) {
    const float u_choose = sampler.next();
    const Vec2 u = sampler.next2();
    if (P.lights.size() == 0) return Spectrum(0.0f);
    float pmf = 0;
    const size_t i = P.lights.choose(u_choose, pmf);
    if (!(pmf > 0)) return Spectrum(0.0f);
    const shading::LightLiSample ls = P.lights[i].sample_Li(p, u, lambda);
    const Spectrum c = light_in_medium(P, ls, p, wo, medium, sampler, lambda, rays);
    float w = 1;
    if (mis && !ls.delta && (!c.is_black() || recorder()))
        w = warp::power_heuristic(pmf * ls.pdf, P.media[medium].phase().eval(wo, ls.wi));
    if (auto* r = recorder()) record_light_in_medium(*r, i, p, ls, pmf, c * w);
    if (c.is_black()) return c;
    return c * (w / (pmf * ls.pdf));
}

namespace {
// Where a ray from o along unit d leaves the scene's bounding sphere (0 if it never is inside).
float exit_distance(const shading::SceneSphere& s, Vec3 o, Vec3 d) {
    const Vec3 oc = o - s.center;
    const float b = dot(oc, d), c = dot(oc, oc) - s.radius * s.radius;
    const float disc = b * b - c;
    return disc > 0 ? std::max(0.0f, -b + std::sqrt(disc)) : 0.0f;
}
}  // namespace

float finite_stretch(const Prepared& P, Vec3 o, Vec3 d, float t_end) {
    return t_end < kInf ? t_end : exit_distance(shading::SceneSphere::from_bounds(P.accel.bounds()), o, d);
}

Spectrum single_scattering(const Prepared& P, int medium_index, Vec3 o, Vec3 d, float t_end, Sampler& sampler,
                           const Wavelengths& lambda, RayCounts& rays) {
    const shading::Medium& medium = P.media[medium_index];
    t_end = finite_stretch(P, o, d, t_end);
    if (!(t_end > 0)) return Spectrum(0.0f);
    const float u_light = sampler.next(), u_t = sampler.next();
    const Vec2 u = sampler.next2();
    if (P.lights.size() == 0) return Spectrum(0.0f);
    float pmf = 0;
    const size_t li = P.lights.choose(u_light, pmf);
    if (!(pmf > 0)) return Spectrum(0.0f);
    const scene::Light& light = P.scene.lights[li];
    float t, pdf_t;
    using LK = scene::Light::Kind;
    if (light.kind == LK::Point || light.kind == LK::Spot || light.kind == LK::Goniometric ||
        light.kind == LK::Projection) {
        // Equiangular: t = h + D tan(theta), theta uniform between the stretch's ends as seen from
        // the light (Kulla & Fajardo 2012, eq. 6); pdf D / ((theta_b - theta_a)(D^2 + (t - h)^2)).
        const float h = dot(light.position - o, d);
        const float D = std::max(length(light.position - (o + d * h)), 1e-6f);
        const float ta = std::atan2(-h, D), tb = std::atan2(t_end - h, D);
        if (!(tb > ta)) return Spectrum(0.0f);
        const float theta = ta + u_t * (tb - ta);
        t = std::clamp(h + D * std::tan(theta), 0.0f, t_end);
        pdf_t = D / ((tb - ta) * (D * D + (t - h) * (t - h)));
    } else {
        // Proportional to exp(-sigma t) on [0, t_end] with sigma the mean extinction (uniform for
        // grids or clear media).
        const float sigma = medium.homogeneous() ? medium.sigma_t_rgb().average() : 0.0f;
        if (sigma * t_end > 1e-3f) {
            const float norm = -std::expm1(-sigma * t_end);
            t = std::min(-std::log1p(-u_t * norm) / sigma, t_end);
            pdf_t = sigma * std::exp(-sigma * t) / norm;
        } else {
            t = u_t * t_end;
            pdf_t = 1 / t_end;
        }
    }
    if (!(pdf_t > 0)) return Spectrum(0.0f);
    const Vec3 x = o + d * t;
    const shading::MediumCoefficients c = medium.at(x, lambda);
    if (c.sigma_s.is_black()) return Spectrum(0.0f);
    const shading::LightLiSample ls = P.lights[li].sample_Li(x, u, lambda);
    if (!(ls.pdf > 0)) return Spectrum(0.0f);
    const Spectrum Li = light_in_medium(P, ls, x, -d, medium_index, sampler, lambda, rays);
    if (Li.is_black()) {
        if (auto* r = recorder()) record_light_in_medium(*r, li, x, ls, pmf, Li);
        return Li;
    }
    const Spectrum T = shading::transmittance(medium, o, d, t, sampler, lambda);
    // Recorded with the camera ray's transmittance and sigma_s / pdf_t: what the stretch adds.
    if (auto* r = recorder()) record_light_in_medium(*r, li, x, ls, pmf, T * c.sigma_s * Li * (1.0f / pdf_t));
    return T * c.sigma_s * Li * (1.0f / (pdf_t * ls.pdf * pmf));
}

}  // namespace phos::integrators
