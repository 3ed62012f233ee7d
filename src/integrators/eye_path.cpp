// The eye path of PPM and SPPM (see eye_path.h). In participating media the path samples free
// flights (delta tracking) and may instead stop at a scattering event in the medium: a volume
// visible point (multiple scattering and volume caustics from the photons); single scattering is
// integrated along the camera ray's stretches in media.
#include "integrators/eye_path.h"

#include <algorithm>

#include "core/low_discrepancy.h"
#include "integrators/direct_light.h"
#include "integrators/emission.h"
#include "render/path_radiance.h"
#include "render/path_recorder.h"
#include "shading/surface_walk.h"
#include "spectrum/color.h"

namespace phos::integrators {

using shading::Bsdf;

namespace {

// The wavelengths of estimate k of the n a visible point averages (its light samples, the single
// scattering along a stretch). A PPM hit point keeps that average for the whole render, so its
// colour noise has to average out within it: while the path's throughput `w` is the same at every
// wavelength, estimate k takes the path's wavelengths shifted by k / (4 n) in the sampling
// density's CDF (all 4 n stratified); otherwise (a coloured or dispersive chain before the point)
// every estimate takes the path's own.
Wavelengths estimate_wavelengths(const Wavelengths& lambda, const Spectrum& w, int k, int n) {
    if (!w.is_flat() || lambda.secondary_terminated()) return lambda;
    const int step = spectrum::kWavelengthCodes / (spectrum::kSpectrumSamples * n);
    return Wavelengths::from_code(uint16_t(int(lambda.code()) + k * step));
}

// The average of n light samples at a surface visible point (from the pixel's sequences with
// `sequences`, else from `sampler`), times the path's throughput `w`, as colour, each at
// estimate_wavelengths.
Rgb direct_light_colour(const Prepared& P, const accel::SurfaceHit& hit, const Bsdf& bsdf, Vec3 wo, int n,
                        const PixelSequences* sequences, Sampler& sampler, const Wavelengths& lambda,
                        const Spectrum& w, RayCounts& rays, int medium) {
    Rgb direct(0.0f);
    for (int k = 0; k < n; ++k) {
        float u_choose;
        Vec2 u;
        if (sequences) {  // sample iteration × n + k of the pixel's sequences
            const uint32_t s = sequences->iteration * uint32_t(n) + uint32_t(k);
            u_choose = padded_point1(s, hash_combine(sequences->key, 0));
            u = padded_point2(s, hash_combine(sequences->key, 1));
        } else {
            u_choose = sampler.next();
            u = sampler.next2();
        }
        const Wavelengths lk = estimate_wavelengths(lambda, w, k, n);
        direct += spectrum::to_srgb(
            w * sample_one_light(P, hit, bsdf, wo, u_choose, u, sampler, lk, rays, false, medium), lk);
    }
    return direct * (1.0f / float(n));
}

// The volume visible point where the free flight stopped. beta holds the free flight's sigma_s
// weight; the photon estimate's density already counts sigma_s (photons are stored at scattering
// events), so it is divided out once.
void stop_in_medium(const Prepared& P, const shading::SurfaceWalk& walk, const Spectrum& beta,
                    const Wavelengths& lambda, int depth, VisiblePoint& vp) {
    const Vec3 x = walk.medium_point(), wo = walk.medium_wo();
    vp.p = x;
    vp.wo = wo;
    vp.beta = beta.safe_div(P.media[walk.medium()].at(x, lambda).sigma_s);
    vp.lambda = lambda;
    vp.depth = depth;
    vp.path_length = walk.distance();
    vp.medium = walk.medium();
}

// The surface visible point (throughput w, over the choice of the non-specular part).
void stop_on_surface(const accel::SurfaceHit& hit, const Bsdf& bsdf, Vec3 wo, const Spectrum& w,
                     const Wavelengths& lambda, int depth, const shading::SurfaceWalk& walk,
                     VisiblePoint& vp) {
    vp.p = hit.p;
    vp.wo = wo;
    vp.beta = w;
    vp.lambda = lambda;
    vp.depth = depth;
    vp.path_length = walk.distance();
    vp.bsdf.emplace(bsdf);
    vp.material = hit.material;
}

// Follows the followed part of the BSDF (chosen with probability 1 - p_estimated): beta, the ray
// and the walk go on; `from` is set when the sampled lobe is not a delta one (for MIS of the
// emission the next vertex finds). False when nothing was sampled.
bool follow_lobes(const Bsdf& followed, float p_estimated, const accel::SurfaceHit& hit, Vec3 wo,
                  Sampler& sampler, Wavelengths& lambda, Spectrum& beta, Ray& ray, shading::SurfaceWalk& walk,
                  BsdfSampledFrom& from, bool& delta) {
    const float u_lobe = sampler.next();
    const auto s = followed.sample(wo, u_lobe, sampler.next2(), lambda);
    if (!s || s->weight.is_black() || !s->weight.is_finite()) return false;
    if (auto* r = recorder()) r->scattered(*s);
    beta *= s->weight * (1 / (1 - p_estimated));
    follow_dispersion(*s, lambda, beta);
    from = {hit.p, s->pdf};
    delta = s->is_specular();
    ray = accel::spawn_ray(hit, s->wi);
    walk.leave(hit, s->wi);
    return true;
}

}  // namespace

Rgb trace_eye_path(const Prepared& P, Ray ray, Sampler& sampler, int direct_samples, VisiblePoint& vp,
                   RayCounts& rays, const PixelSequences* sequences) {
    vp.bsdf.reset();
    vp.medium = -1;
    Wavelengths lambda = sequences ? camera_wavelengths(spectrum::wavelength_sequence_point(
                                         sequences->iteration, hash_combine(sequences->key, 2)))
                                   : camera_wavelengths(sampler);
    Rgb L(0.0f);
    Spectrum beta(1.0f);
    // Adds a contribution (at the path's wavelengths) to the path's radiance (and to the trace as
    // `term`), as colour.
    const auto add_colour = [&](Rgb c, TraceTerm term) {
        L += c;
        if (auto* r = recorder()) r->add(term, c);
    };
    const auto add = [&](const Spectrum& s, TraceTerm term) {
        add_colour(spectrum::to_srgb(s, lambda), term);
    };
    const shading::MediaSet* media = P.active_media();
    // Its distance() is the visible point's path length.
    shading::SurfaceWalk walk(P.accel, media, P.camera_medium());
    bool camera_chain = true;  // only delta bounces so far: the .scn glow is seen (emission.h)
    BsdfSampledFrom last{};    // the last vertex, when its bounce sampled a followed glossy lobe
    const BsdfSampledFrom* from = nullptr;
    for (int depth = 0;;) {
        accel::SurfaceHit hit;
        Spectrum emitted(0.0f);
        // Single scattering is integrated over each whole stretch in a medium (equiangular
        // sampling finds the glow around point lights), as the average of `direct_samples`
        // estimates like direct light at a surface point: near an area light the estimate is
        // heavy-tailed, and a PPM hit point keeps its value for the whole render. The free flight
        // then decides whether the path stops in the medium (a volume visible point, for multiple
        // scattering) or goes on.
        const auto stretch = [&](const shading::Medium&, Vec3 o, Vec3 d, float t_end) {
            const int n = std::max(1, direct_samples);
            Rgb sum(0.0f);
            for (int k = 0; k < n; ++k) {
                const Wavelengths lk = estimate_wavelengths(lambda, beta, k, n);
                sum += spectrum::to_srgb(
                    beta * single_scattering(P, walk.medium(), o, d, t_end, sampler, lk, rays), lk);
            }
            add_colour(sum * (1.0f / float(n)), TraceTerm::Light);
        };
        const shading::SurfaceWalk::Event event =
            media ? walk.next(ray, hit, sampler, lambda, beta, emitted, stretch) : walk.next(ray, hit);
        add(emitted, TraceTerm::Emission);
        if (auto* r = recorder()) r->vertex(P, event, ray, hit, walk, beta);
        if (event == shading::SurfaceWalk::Event::Lost || event == shading::SurfaceWalk::Event::Absorbed)
            break;
        if (event == shading::SurfaceWalk::Event::Medium) {
            if (depth == P.options.max_depth) break;
            stop_in_medium(P, walk, beta, lambda, depth, vp);
            break;
        }
        if (event == shading::SurfaceWalk::Event::Escaped) {
            // Every vertex so far was followed (mirror, glass, sharp glossy): escaped light is seen
            // directly, weighted against light sampling after a glossy bounce.
            add(escaped_emission(P, ray.origin, normalize(ray.dir), beta, lambda, from), TraceTerm::Emission);
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        const SeenEmission seen = seen_emission(P, hit, wo, beta, lambda, camera_chain, from);
        add(seen.light, TraceTerm::Emission);
        add_colour(seen.glow, TraceTerm::Emission);
        if (depth == P.options.max_depth) break;
        const Bsdf bsdf = P.bsdf(hit);

        // Split the lobes into the estimated part (a visible point) and the followed part
        // (Bsdf::split_lobes: delta and sharp glossy lobes).
        const Bsdf::LobeSplit split = bsdf.split_lobes(wo, P.options.sharp_glossy);
        const float p_est = split.p_estimated;
        const float u = p_est > 0 && p_est < 1 ? sampler.next() : 0.5f;
        if (p_est >= 1 || (p_est > 0 && u < p_est)) {
            const Bsdf est = bsdf.only(split.estimated);
            const Spectrum w = beta * (1 / p_est);
            const int n = std::max(1, direct_samples);
            add_colour(
                direct_light_colour(P, hit, est, wo, n, sequences, sampler, lambda, w, rays, walk.medium()),
                TraceTerm::Light);
            stop_on_surface(hit, est, wo, w, lambda, depth, walk, vp);
            break;
        }
        const Bsdf followed = bsdf.only(split.followed);
        // Light through the followed glossy lobes: one light sample, MIS-weighted against the
        // emission the continuation finds.
        if (followed.has_non_specular())
            add(beta * (1 / (1 - p_est)) *
                    sample_one_light(P, hit, followed, wo, sampler, lambda, rays, true, walk.medium()),
                TraceTerm::Light);
        bool delta = true;
        if (!follow_lobes(followed, p_est, hit, wo, sampler, lambda, beta, ray, walk, last, delta)) break;
        from = delta ? nullptr : &last;
        camera_chain = camera_chain && delta;
        ++rays.bounce;
        ++depth;
        if (!beta.is_finite() || beta.max() <= 0) break;
    }
    return L;
}

}  // namespace phos::integrators
