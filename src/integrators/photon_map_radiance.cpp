// Pass 2 of the photon mapper (see photon_map_radiance.h). Each BSDF is split as in Jensen 2001,
// sec. 9.1 (f_r = f_r,S + f_r,D, Bsdf::split_lobes): the followed part (mirrors, smooth glass and
// glossy lobes at least as sharp as --sharp-glossy) is ray traced, the estimated part (diffuse and
// wider glossy lobes) reads the photon maps. The radiance leaving the first vertex x with an
// estimated part, seen by the camera directly or through followed bounces, is split so that every
// light path is counted exactly once (S: a followed bounce, D: an estimated one):
//   direct    L -> x             shadow rays towards every light through x's estimated part; the
//                                followed glossy lobes sample one light, weighted by the power
//                                heuristic against the continuation finding the emitter
//   caustic   L S+ -> x          the caustic map's estimate at x (its photons took S bounces only)
//   indirect  L ... D S* -> x    final gathering: rays sampled from x's estimated lobes, followed
//                                through S bounces to their first vertex y with an estimated part,
//                                where the global map's estimate (all light leaving y except
//                                emission) is taken; with --fast-global, the indirect map's estimate
//   specular  x's followed part  the camera path goes on through it (one sampled lobe) and adds
//                                what the next vertex shows.
// A photon estimate of a sharp lobe reads the few photons arriving inside it: behind frosted glass
// in front of the lights those are rare, bright and isolated, so the sharp lobes are traced instead.
// In participating media the camera ray gains, along every stretch in a medium (Jensen &
// Christensen 1998, eq. 12), the same three parts: single scattering L V (light sampling), volume
// caustics L S+ V and multiple scattering L ... {D|V} V (the volume maps' estimates: one beam
// radiance estimate per stretch, Jarosz, Zwicker & Jensen 2008, or ray marching), while what lies
// behind is attenuated by the stretch's transmittance.
#include "integrators/photon_map_radiance.h"

#include <algorithm>
#include <cmath>

#include "integrators/direct_light.h"
#include "integrators/emission.h"
#include "render/path_recorder.h"
#include "render/pixel_loop.h"
#include "shading/medium_tracking.h"
#include "shading/surface_walk.h"
#include "spectrum/color.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

using photon::kCausticMap;
using photon::kGlobalMap;
using photon::kIndirectMap;

namespace {

// Russian roulette where a vertex has both parts: the estimated part is evaluated there, so going
// on through the followed part (a plastic's sharp highlight, a coated surface's mirror) is kept
// with the probability of its weight (at most 1) and reweighted. Chains of such vertices then
// cost a geometric series instead of a gather at every one of max_depth bounces; chains of glass
// and mirrors alone (weight ~1) are not played.
bool survives_followed(const shading::BsdfSample& s, Sampler& sampler, Spectrum& beta) {
    const float q = std::min(1.0f, s.weight.max());
    if (q >= 1) return true;
    if (!(sampler.next() < q)) return false;
    beta *= 1.0f / q;
    return true;
}

}  // namespace

PhotonMapRadiance::PhotonMapRadiance(const Prepared& P, const PhotonMapOptions& o, const PhotonMaps& maps)
    : P_(P), o_(o), maps_(maps) {
    volume_est_ = {o.volume.samples, o.volume.radius, &P.accel};
    volume_caustic_est_ = {o.volume_caustic.samples, o.volume_caustic.radius, &P.accel};
    const PhotonMapSettings* s[3] = {&o.global, &o.caustic, &o.indirect};
    for (int m = 0; m < 3; ++m) {
        est_[m].k = s[m]->samples;
        est_[m].max_radius = s[m]->radius;
        est_[m].filter.kind = s[m]->filter;
        est_[m].filter.cone_k = s[m]->cone_k;
        est_[m].normal_cos = o.normal_cos;
        est_[m].flatness = o.flatness;
    }
    // The caustic estimate's minimum radius in pixel footprints, widened at low sample counts:
    // the film averages a pixel's samples over its area, so with n samples per pixel a kernel of
    // about 3 / sqrt(n) pixels is what keeps a sub-pixel focus from hitting or missing them
    // (caustic-point's window at 1 spp: +/- 12 % over seeds with 1 pixel, +/- 4 % with 3).
    const int n = std::max(1, P.options.spp) * std::max(1, P.options.dof_samples);
    const float pixels = o.caustic_min_pixels * std::max(1.0f, 3.0f / std::sqrt(float(n)));
    const CameraModel::Footprint f = P.camera.pixel_footprint();
    footprint_offset_ = pixels * f.offset;
    footprint_slope_ = pixels * f.slope;
}

Rgb PhotonMapRadiance::estimate(int m, const photon::SurfaceQuery& q, Vec3 wo,
                                const shading::Bsdf& bsdf) const {
    PathRecorder* r = recorder();
    if (!r) return photon::radiance_estimate(maps_.map[m], est_[m], q, wo, bsdf);
    TracedLookup l{photon::map_name(m), q.p};
    l.estimate = photon::radiance_estimate(maps_.map[m], est_[m], q, wo, bsdf, &l.found, &l.radius);
    r->lookup(l);
    return l.estimate;
}

RadianceParts PhotonMapRadiance::camera_ray(Ray ray, Sampler& sampler, RayCounts& rays) const {
    RadianceParts out;
    Wavelengths lambda = camera_wavelengths(sampler);
    Spectrum beta(1.0f);
    bool via_followed = false;  // the path went through a followed bounce: all it adds is "specular"
    bool camera_chain = true;   // only delta bounces so far: the .scn glow is seen (emission.h)
    BsdfSampledFrom last{};     // the last vertex, when its bounce sampled a followed glossy lobe
    const BsdfSampledFrom* from = nullptr;
    // Adds colour c to component `part` (and to the trace as `term`); a spectrum at the path's
    // wavelengths goes to colour first, a photon estimate (a colour) meets the throughput.
    const auto add = [](Rgb& part, Rgb c, TraceTerm term) {
        part += c;
        if (auto* r = recorder()) r->add(term, c);
    };
    const auto add_spectrum = [&](Rgb& part, const Spectrum& c, TraceTerm term) {
        add(part, spectrum::to_srgb(c, lambda), term);
    };
    const auto add_estimate = [&](Rgb& part, Rgb estimate, TraceTerm term) {
        add(part, spectrum::colour_through(beta, lambda, estimate), term);
    };
    // Its distance() scales the pixel footprint.
    shading::SurfaceWalk walk(P_.accel, P_.active_media(), P_.camera_medium());
    for (int depth = 0;;) {
        Rgb& seen = via_followed ? out.specular : out.direct;
        accel::SurfaceHit hit;
        const shading::SurfaceWalk::Event event =
            walk.next_segments(ray, hit, [&](const shading::Medium& m, Vec3 o, Vec3 d, float t_end) {
                const MediumStretch s = march(m, walk.medium(), o, d, t_end, lambda, sampler, rays);
                if (auto* r = recorder()) {  // the volume maps' estimates over the stretch from o
                    r->lookup({"volume caustic (stretch)", o, 0, 0, s.caustic});
                    r->lookup({"volume (stretch)", o, 0, 0, s.multiple});
                }
                add_spectrum(via_followed ? out.specular : out.direct, beta * s.single, TraceTerm::Light);
                add_estimate(via_followed ? out.specular : out.caustic, s.caustic, TraceTerm::Caustic);
                add_estimate(via_followed ? out.specular : out.indirect, s.multiple, TraceTerm::Indirect);
                beta *= s.T;
            });
        if (auto* r = recorder()) r->vertex(P_, event, ray, hit, walk, beta);
        if (event == shading::SurfaceWalk::Event::Lost) break;
        if (event == shading::SurfaceWalk::Event::Escaped) {
            add_spectrum(seen, escaped_emission(P_, ray.origin, normalize(ray.dir), beta, lambda, from),
                         TraceTerm::Emission);
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        const SeenEmission emitted = seen_emission(P_, hit, wo, beta, lambda, camera_chain, from);
        add_spectrum(seen, emitted.light, TraceTerm::Emission);
        add(seen, emitted.glow, TraceTerm::Emission);

        const shading::Bsdf bsdf = P_.bsdf(hit);
        const shading::Bsdf::LobeSplit split = bsdf.split_lobes(wo, P_.options.sharp_glossy);
        Rgb& d = via_followed ? out.specular : out.direct;
        if (o_.photon_viz && bsdf.has_non_specular()) {
            add_estimate(seen, estimate(kGlobalMap, photon::make_query(hit.p, hit.ng, wo, bsdf), wo, bsdf),
                         TraceTerm::Indirect);
        } else if (split.estimated) {
            const shading::Bsdf est = bsdf.only(split.estimated);
            const photon::SurfaceQuery q = photon::make_query(hit.p, hit.ng, wo, est);
            Rgb& c = via_followed ? out.specular : out.caustic;
            Rgb& i = via_followed ? out.specular : out.indirect;
            if (o_.direct)
                add_spectrum(d,
                             beta * sample_all_lights(P_, hit, est, wo, sampler, lambda, rays, walk.medium()),
                             TraceTerm::Light);
            if (o_.caustics) {
                photon::SurfaceQuery qc = q;
                qc.min_radius = footprint_offset_ + footprint_slope_ * walk.distance();
                add_estimate(c, estimate(kCausticMap, qc, wo, est), TraceTerm::Caustic);
            }
            if (o_.indirect_light) {
                if (o_.fast_global)
                    add_estimate(i, estimate(kIndirectMap, q, wo, est), TraceTerm::Indirect);
                else
                    add(i, final_gather(hit, est, wo, walk.medium(), beta, lambda, sampler, rays),
                        TraceTerm::Indirect);
            }
        }
        // The followed part: one sampled lobe per sample (unbiased), as a path tracer would.
        if (depth >= P_.options.max_depth || !split.followed) break;
        const shading::Bsdf followed = bsdf.only(split.followed);
        // Light through its glossy lobes: one light sample, MIS-weighted against the continuation.
        if (o_.direct && followed.has_non_specular())
            add_spectrum(
                d, beta * sample_one_light(P_, hit, followed, wo, sampler, lambda, rays, true, walk.medium()),
                TraceTerm::Light);
        const auto s = followed.sample(wo, sampler.next(), sampler.next2(), lambda);
        if (!s || s->weight.is_black()) break;
        if ((s->flags & shading::kTransmission) ? !o_.transmissive : !o_.specular) break;
        if (auto* r = recorder()) r->scattered(*s);
        if (split.estimated && !survives_followed(*s, sampler, beta)) break;
        beta *= s->weight;
        follow_dispersion(*s, lambda, beta);
        if (!beta.is_finite() || beta.max() < 1e-6f) break;
        via_followed = true;
        camera_chain = camera_chain && s->is_specular();
        last = {hit.p, s->pdf};
        from = s->is_specular() ? nullptr : &last;
        ray = accel::spawn_ray(hit, s->wi);
        walk.leave(hit, s->wi);
        ++rays.bounce;
        ++depth;
    }
    return out;
}

Rgb PhotonMapRadiance::final_gather(const accel::SurfaceHit& hit, const shading::Bsdf& bsdf, Vec3 wo,
                                    int medium, const Spectrum& beta, const Wavelengths& lambda,
                                    Sampler& sampler, RayCounts& rays) const {
    // `bsdf` is the estimated part of the vertex's BSDF: every non-delta lobe of it is gathered.
    const uint32_t lobes = bsdf.split_lobes(wo).estimated;
    const int n = std::max(o_.gather_rays, 1);
    if (!lobes) return Rgb(0.0f);
    Rgb sum(0.0f);
    for (int i = 0; i < n; ++i) {
        // Stratified over the hemisphere (sqrt(n) x sqrt(n) cells of the lobe's sample square).
        const Vec2 u = stratified_sample(i, n, sampler.next2());
        const float u_lobe = sampler.next();
        const auto s = bsdf.sample_lobes(lobes, wo, u_lobe, u, lambda);
        if (!s || s->is_specular() || s->weight.is_black()) continue;
        ++rays.bounce;
        sum +=
            gather_ray(accel::spawn_ray(hit, s->wi), shading::SurfaceWalk::medium_after(hit, s->wi, medium),
                       beta * s->weight, lambda, sampler, rays);
    }
    return sum * (1.0f / float(n));
}

Rgb PhotonMapRadiance::gather_ray(Ray ray, int medium, Spectrum beta, Wavelengths lambda, Sampler& sampler,
                                  RayCounts& rays) const {
    Rgb L(0.0f);
    const shading::MediaSet* media = P_.active_media();
    shading::SurfaceWalk walk(P_.accel, media, medium);
    for (int depth = 0; depth <= P_.options.max_depth;) {
        accel::SurfaceHit hit;
        Spectrum emitted(0.0f);
        const shading::SurfaceWalk::Event event =
            media ? walk.next(ray, hit, sampler, lambda, beta, emitted) : walk.next(ray, hit);
        L += spectrum::to_srgb(emitted, lambda);
        if (event == shading::SurfaceWalk::Event::Medium) {
            // The free flight's weight carries sigma_s / sigma_maj...: what remains is the radiance
            // in-scattered at x, int p L_i = direct (light sampling) + volume estimates / sigma_s.
            const Vec3 x = walk.medium_point(), wo = walk.medium_wo();
            const shading::Medium& m = P_.media[walk.medium()];
            const Spectrum Ls =
                sample_one_light_in_medium(P_, x, wo, walk.medium(), sampler, lambda, rays, false);
            // The volume cache's first-order estimate (photon/volume_cache.h) where it has a point
            // nearby, else the two maps' k-nearest estimates.
            Rgb est;
            const bool cached = maps_.volume_cache.lookup(x, volume_est_.max_radius, wo, m.phase().g, est);
            if (!cached)
                est = photon::volume_radiance_estimate(maps_.volume(), volume_est_, x, wo, m.phase()) +
                      photon::volume_radiance_estimate(maps_.volume_caustic(), volume_caustic_est_, x, wo,
                                                       m.phase());
            if (auto* r = recorder())
                r->lookup({cached ? "volume cache" : "volume + volume caustic", x, 0, 0, est});
            // The estimates hold sigma_s, which the free flight's weight in beta holds too.
            L += spectrum::to_srgb(beta * Ls, lambda) +
                 spectrum::colour_through(beta.safe_div(m.at(x, lambda).sigma_s), lambda, est);
            break;
        }
        // Sky light arriving this way is direct light: an escaped ray adds nothing.
        if (event != shading::SurfaceWalk::Event::Surface) break;
        const Vec3 wo = -normalize(ray.dir);
        const shading::Bsdf bsdf = P_.bsdf(hit);
        const shading::Bsdf::LobeSplit split = bsdf.split_lobes(wo, P_.options.sharp_glossy);
        if (split.estimated) {
            const shading::Bsdf est = bsdf.only(split.estimated);
            const photon::SurfaceQuery q = photon::make_query(hit.p, hit.ng, wo, est);
            Rgb E;
            if (est.is_lambertian() && !maps_.cache.empty() &&
                maps_.cache.lookup(q, est_[kGlobalMap].max_radius, o_.normal_cos, E)) {
                // The cache holds irradiance colours: their product with the albedo's colour.
                const Rgb Lo = est.diffuse_colour() * kInvPi * E;
                L += spectrum::colour_through(beta, lambda, Lo);
                if (auto* r = recorder()) r->lookup({"irradiance cache", q.p, 0, 0, Lo});
            } else {
                L += spectrum::colour_through(beta, lambda, estimate(kGlobalMap, q, wo, est));
            }
        }
        // Through the followed part (mirrors, glass, sharp glossy lobes) to the next vertex with an
        // estimated part; emitters found this way are direct light or caustics of the gather's
        // origin, counted there.
        if (!split.followed) break;
        const shading::Bsdf followed = bsdf.only(split.followed);
        const auto s = followed.sample(wo, sampler.next(), sampler.next2(), lambda);
        if (!s || s->weight.is_black()) break;
        if (split.estimated && !survives_followed(*s, sampler, beta)) break;
        beta *= s->weight;
        if (s->dispersive) spectrum::terminate_secondary(lambda, beta);
        if (!beta.is_finite() || beta.max() < 1e-6f) break;
        ray = accel::spawn_ray(hit, s->wi);
        walk.leave(hit, s->wi);
        ++rays.bounce;
        ++depth;
    }
    return L;
}

namespace {

// A stretch's transmittance T and emission int_0^t_end T sigma_a Le dt at `lambda`: in closed form in
// homogeneous media; in grids with sigma_t and the emission taken constant over steps of at most
// `step`, at a jittered point in each (as photon::StretchTransmittance does), each step integrated
// exactly.
void stretch_spectra(const shading::Medium& medium, Vec3 o, Vec3 d, float t_end, float step, float jitter,
                     const Wavelengths& lambda, Spectrum& T, Spectrum& emitted) {
    // int_0^L exp(-sigma t) dt per wavelength (L where sigma = 0).
    const auto chord = [](const Spectrum& sigma, float L) {
        Spectrum c;
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i)
            c[i] = sigma[i] * L > 1e-4f ? -std::expm1(-sigma[i] * L) / sigma[i] : L;
        return c;
    };
    emitted = Spectrum(0.0f);
    if (medium.homogeneous()) {
        const shading::MediumCoefficients c = medium.at(o, lambda);
        T = spectrum::exp(c.sigma_t() * -t_end);
        if (medium.emissive()) emitted = c.sigma_a * c.Le * chord(c.sigma_t(), t_end);
        return;
    }
    const int n = std::clamp(int(std::ceil(t_end / step)), 1, 4096);
    const float dt = t_end / float(n);
    T = Spectrum(1.0f);
    for (int k = 0; k < n; ++k) {
        const shading::MediumCoefficients c = medium.at(o + d * ((float(k) + jitter) * dt), lambda);
        if (medium.emissive()) emitted += T * c.sigma_a * c.Le * chord(c.sigma_t(), dt);
        T *= spectrum::exp(c.sigma_t() * -dt);
        if (T.max() < 1e-4f) break;
    }
}

}  // namespace

PhotonMapRadiance::MediumStretch PhotonMapRadiance::march(const shading::Medium& medium, int medium_index,
                                                          Vec3 o, Vec3 d, float t_end,
                                                          const Wavelengths& lambda, Sampler& sampler,
                                                          RayCounts& rays) const {
    MediumStretch s;
    if (o_.direct) s.single = single_scattering(P_, medium_index, o, d, t_end, sampler, lambda, rays);
    t_end = finite_stretch(P_, o, d, t_end);
    if (!(t_end > 0)) return s;
    // The stretch's transmittance at the path's wavelengths, and the medium's emission along it.
    const float jitter = sampler.next();
    Spectrum emitted;
    stretch_spectra(medium, o, d, t_end, o_.volume_step, jitter, lambda, s.T, emitted);
    s.single += emitted;
    if (o_.volume_estimate == VolumeEstimate::Beam) {
        // The beam radiance estimate (photon/beam_estimate.h): one query of each volume map's photon
        // spheres for the whole stretch, each photon weighted by T integrated over its chord (exact
        // in homogeneous media, a table over the --volume-step steps in grids).
        const photon::StretchTransmittance T(medium, o, d, t_end, o_.volume_step, jitter);
        if (o_.caustics)
            s.caustic += photon::beam_radiance_estimate(maps_.volume_caustic_beams, o, d, T, medium.phase());
        if (o_.indirect_light)
            s.multiple += photon::beam_radiance_estimate(maps_.volume_beams, o, d, T, medium.phase());
        return s;
    }
    // Ray marching with a jittered start: every step adds T(t) dt times the volume estimates; T
    // (the colour of sigma_t's) is exact in homogeneous media and marched in grids.
    const int n = std::clamp(int(std::ceil(t_end / o_.volume_step)), 1, 4096);
    const float dt = t_end / float(n);
    const Vec3 wo = -d;
    Rgb T(1.0f);
    float t_prev = 0;
    for (int k = 0; k < n; ++k) {
        const float t = (float(k) + jitter) * dt;
        const Vec3 x = o + d * t;
        T = medium.homogeneous() ? exp(medium.sigma_t_rgb() * -t)
                                 : T * exp(medium.sigma_t_rgb(x) * -(t - t_prev));
        t_prev = t;
        if (T.max() < 1e-4f) break;
        const Rgb w = T * dt;
        if (o_.caustics)
            s.caustic += w * photon::volume_radiance_estimate(maps_.volume_caustic(), volume_caustic_est_, x,
                                                              wo, medium.phase());
        if (o_.indirect_light)
            s.multiple +=
                w * photon::volume_radiance_estimate(maps_.volume(), volume_est_, x, wo, medium.phase());
    }
    return s;
}

}  // namespace phos::integrators
