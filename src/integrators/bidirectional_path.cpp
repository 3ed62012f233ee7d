// Light subpaths and vertex evaluation for the bidirectional integrators (see bidirectional_path.h).
#include "integrators/bidirectional_path.h"

#include <cmath>

#include "shading/surface_walk.h"

namespace phos::integrators::vcm {

Wavelengths subpath_wavelengths(uint64_t seed, uint64_t j, uint64_t iteration) {
    return Wavelengths::visible(spectrum::wavelength_sequence_point(
        uint32_t(iteration), Sampler(seed, 0x7761766573ULL, j).next_bits()));
}

Scattering evaluate(const Prepared& P, const Vertex& v, Vec3 wi, shading::TransportMode mode,
                    const Wavelengths& lambda) {
    Scattering s;
    if (v.in_medium) {
        const shading::PhaseFunction& phase = P.media[v.medium].phase();
        const float p = phase.eval(v.wo, wi);
        s.f = Spectrum(p);
        s.pdf_dir = p;
        s.pdf_rev = phase.eval(wi, v.wo);
        return s;
    }
    const shading::Bsdf& b = *v.bsdf;
    const shading::Bsdf::Evaluation e = b.evaluate(v.wo, wi, lambda, mode);
    s.f = e.f;
    s.cos = std::fabs(dot(b.frame().n, wi));
    s.pdf_dir = e.pdf;
    s.pdf_rev = e.pdf_rev;
    return s;
}

namespace {

// The medium a ray from vertex `v` towards `dir` starts in.
int medium_towards(const Vertex& v, Vec3 dir) {
    return v.in_medium ? v.medium : shading::SurfaceWalk::medium_after(v.hit, dir, v.medium);
}

}  // namespace

Spectrum transmittance_between(const Prepared& P, const Vertex& a, const Vertex& b, Sampler& sampler,
                               const Wavelengths& lambda) {
    if (!a.in_medium && !b.in_medium) {
        const Ray ray = accel::spawn_ray_between(a.hit, b.hit);
        return shading::shadow_transmittance(P.accel, P.active_media(), ray, medium_towards(a, ray.dir),
                                             sampler, lambda);
    }
    if (a.in_medium && !b.in_medium) return transmittance_to(P, b, a.p, sampler, lambda);
    return transmittance_to(P, a, b.p, sampler, lambda);
}

Spectrum transmittance_to(const Prepared& P, const Vertex& a, Vec3 target, Sampler& sampler,
                          const Wavelengths& lambda) {
    Ray ray;
    if (a.in_medium) {
        ray = Ray{a.p, target - a.p, 0.0f, 1 - 1e-4f};
    } else {
        ray = accel::spawn_ray_to(a.hit, target);
    }
    return shading::shadow_transmittance(P.accel, P.active_media(), ray, medium_towards(a, ray.dir), sampler,
                                         lambda);
}

Vertex reach_vertex(const Prepared& P, shading::SurfaceWalk::Event event, const shading::SurfaceWalk& walk,
                    const Ray& ray, const accel::SurfaceHit& hit, int length, const Spectrum& beta,
                    const Wavelengths& lambda) {
    Vertex v;
    v.length = length;
    v.beta = beta;
    v.lambda = lambda;
    v.medium = walk.medium();
    if (event == shading::SurfaceWalk::Event::Medium) {
        v.p = walk.medium_point();
        v.wo = walk.medium_wo();
        v.in_medium = true;
    } else {
        v.p = hit.p;
        v.wo = -normalize(ray.dir);
        v.hit = hit;
        v.bsdf.emplace(P.bsdf(hit));
    }
    return v;
}

std::optional<Direction> continue_from(const Prepared& P, const Vertex& v, shading::TransportMode mode,
                                       const ScatterTerms& terms, Sampler& sampler, SubpathState& path) {
    float pdf = 0, pdf_rev = 0;
    Direction d;
    if (v.in_medium) {
        const shading::PhaseFunction& phase = P.media[v.medium].phase();
        pdf = phase.sample(v.wo, sampler.next2(), d.wi);
        pdf_rev = phase.eval(d.wi, v.wo);
    } else {
        const float u_lobe = sampler.next();
        const auto bs = v.bsdf->sample(v.wo, u_lobe, sampler.next2(), path.lambda, mode);
        if (!bs || bs->weight.is_black() || !(bs->pdf > 0)) return std::nullopt;
        d.wi = bs->wi;
        path.beta *= bs->weight;
        if (bs->dispersive) spectrum::terminate_secondary(path.lambda, path.beta);
        d.delta = bs->is_specular();
        pdf = bs->pdf;
        if (!d.delta) pdf_rev = v.bsdf->pdf(d.wi, v.wo);
    }
    if (d.delta)
        scatter_delta(path.mis, cos_at(v, d.wi));
    else
        scatter(path.mis, cos_at(v, d.wi), pdf * terms.go_on, pdf_rev, terms.merge_here, terms.factors);
    return d;
}

Ray leave_vertex(const Vertex& v, Vec3 wi, shading::SurfaceWalk& walk) {
    if (v.in_medium) return Ray{v.p, wi};
    walk.leave(v.hit, wi);
    return accel::spawn_ray(v.hit, wi);
}

bool survives(int length, Spectrum& beta, const Spectrum& beta0, Sampler& sampler) {
    if (length > 3) {
        const float start = beta0.max();
        const float p = std::clamp(start > 0 ? beta.max() / start : 0.0f, 0.05f, 1.0f);
        if (sampler.next() >= p) return false;
        beta *= 1.0f / p;
    }
    return beta.is_finite() && !beta.is_black();
}

bool trace_light_path(const Prepared& P, const LightSubpathRules& rules, Sampler& sampler,
                      const Wavelengths& lambda, std::vector<Vertex>& out, RayCounts& rays) {
    if (P.lights.size() == 0) return false;
    float pmf = 0;
    const size_t li = P.lights.choose(sampler.next(), pmf);
    const Vec2 u_pos = sampler.next2(), u_dir = sampler.next2();
    if (!(pmf > 0)) return false;
    const shading::Light& light = P.lights[li];
    const shading::LightLeSample e = light.sample_Le(u_pos, u_dir, lambda);
    if (e.weight.is_black() || !e.weight.is_finite() || !(e.pdf_pos > 0) || !(e.pdf_dir > 0)) return false;
    const scene::Light::Kind kind = P.scene.lights[li].kind;
    const bool at_infinity = light.is_infinite() || kind == scene::Light::Kind::Directional;
    const bool area = kind == scene::Light::Kind::Area;
    const float direct_pdf = direct_density(pmf, e.pdf_pos, e.pdf_dir, at_infinity);
    const float emit_pdf = pmf * e.pdf_pos * e.pdf_dir;
    const float cos_light = area ? std::fabs(dot(e.n, e.ray.dir)) : 1.0f;
    SubpathState path{
        e.weight * (1.0f / pmf),
        start_light(direct_pdf, emit_pdf, cos_light, light.is_delta(), at_infinity, rules.factors), lambda};
    const Spectrum beta0 = path.beta;
    Ray ray = e.ray;
    const shading::MediaSet* media = P.active_media();
    shading::SurfaceWalk walk(P.accel, media, P.lights.emission_medium(li, e));
    Vec3 from = e.ray.origin;
    bool delta_chain = true;
    for (int segments = 1;; ++segments) {
        accel::SurfaceHit hit;
        Spectrum emitted(0.0f);  // light paths ignore media's own emission (only camera paths see it)
        const auto event =
            media ? walk.next(ray, hit, sampler, path.lambda, path.beta, emitted) : walk.next(ray, hit);
        ++rays.photon;
        if (event != shading::SurfaceWalk::Event::Surface && event != shading::SurfaceWalk::Event::Medium)
            break;
        Vertex v = reach_vertex(P, event, walk, ray, hit, segments, path.beta, path.lambda);
        v.delta_chain = delta_chain;
        // An infinite light's direct density is that of sampling it from this first vertex (a
        // portal's depends on the point).
        if (segments == 1 && light.is_infinite())
            path.mis.dVCM =
                mis(direct_density(pmf, e.pdf_pos, light.pdf_Li(v.p, -ray.dir, {}, {}), true) / emit_pdf);
        // The first segment from a light at infinity has no distance to convert (its start is a
        // direction).
        arrive(path.mis, length(v.p - from), cos_at(v, v.wo), !(segments == 1 && at_infinity));
        v.mis = path.mis;
        const bool scatters_smoothly = v.in_medium || v.bsdf->has_non_specular();
        v.mergeable =
            rules.merge_from > 0 && segments >= rules.merge_from && !v.in_medium && scatters_smoothly;
        if (scatters_smoothly) out.push_back(v);
        if (segments >= rules.max_segments) break;

        // Scatter: the phase function or the BSDF (importance transport).
        const std::optional<Direction> d =
            continue_from(P, v, shading::TransportMode::Importance,
                          {rules.factors, v.mergeable && rules.merge_terms}, sampler, path);
        if (!d) break;
        delta_chain = delta_chain && d->delta;
        if (!survives(segments, path.beta, beta0, sampler)) break;
        from = v.p;
        ray = leave_vertex(v, d->wi, walk);
    }
    return true;
}

}  // namespace phos::integrators::vcm
