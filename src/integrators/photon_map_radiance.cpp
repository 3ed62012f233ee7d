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
bool survives_followed(const shading::BsdfSample& s, Sampler& sampler, Rgb& beta) {
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
    Rgb beta(1.0f);
    bool via_followed = false;  // the path went through a followed bounce: all it adds is "specular"
    bool camera_chain = true;   // only delta bounces so far: the .scn glow is seen (emission.h)
    BsdfSampledFrom last{};     // the last vertex, when its bounce sampled a followed glossy lobe
    const BsdfSampledFrom* from = nullptr;
    // Adds c to component `part` (and to the trace as `term`).
    const auto add = [](Rgb& part, Rgb c, TraceTerm term) {
        part += c;
        if (auto* r = recorder()) r->add(term, c);
    };
    // Its distance() scales the pixel footprint.
    shading::SurfaceWalk walk(P_.accel, P_.active_media(), P_.camera_medium());
    for (int depth = 0;;) {
        Rgb& seen = via_followed ? out.specular : out.direct;
        accel::SurfaceHit hit;
        const shading::SurfaceWalk::Event event =
            walk.next_segments(ray, hit, [&](const shading::Medium& m, Vec3 o, Vec3 d, float t_end) {
                const MediumStretch s = march(m, walk.medium(), o, d, t_end, sampler, rays);
                if (auto* r = recorder()) {  // the volume maps' estimates over the stretch from o
                    r->lookup({"volume caustic (stretch)", o, 0, 0, s.caustic});
                    r->lookup({"volume (stretch)", o, 0, 0, s.multiple});
                }
                add(via_followed ? out.specular : out.direct, beta * s.single, TraceTerm::Light);
                add(via_followed ? out.specular : out.caustic, beta * s.caustic, TraceTerm::Caustic);
                add(via_followed ? out.specular : out.indirect, beta * s.multiple, TraceTerm::Indirect);
                beta *= s.T;
            });
        if (auto* r = recorder()) r->vertex(P_, event, ray, hit, walk, beta);
        if (event == shading::SurfaceWalk::Event::Lost) break;
        if (event == shading::SurfaceWalk::Event::Escaped) {
            add(seen, escaped_emission(P_, normalize(ray.dir), beta, from), TraceTerm::Emission);
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        add(seen, seen_emission(P_, hit, wo, beta, camera_chain, from), TraceTerm::Emission);

        const shading::Bsdf bsdf = P_.bsdf(hit);
        const shading::Bsdf::LobeSplit split = bsdf.split_lobes(wo, P_.options.sharp_glossy);
        Rgb& d = via_followed ? out.specular : out.direct;
        if (o_.photon_viz && bsdf.has_non_specular()) {
            add(seen, beta * estimate(kGlobalMap, photon::make_query(hit.p, hit.ng, wo, bsdf), wo, bsdf),
                TraceTerm::Indirect);
        } else if (split.estimated) {
            const shading::Bsdf est = bsdf.only(split.estimated);
            const photon::SurfaceQuery q = photon::make_query(hit.p, hit.ng, wo, est);
            Rgb& c = via_followed ? out.specular : out.caustic;
            Rgb& i = via_followed ? out.specular : out.indirect;
            if (o_.direct)
                add(d, beta * sample_all_lights(P_, hit, est, wo, sampler, rays, walk.medium()),
                    TraceTerm::Light);
            if (o_.caustics) {
                photon::SurfaceQuery qc = q;
                qc.min_radius = footprint_offset_ + footprint_slope_ * walk.distance();
                add(c, beta * estimate(kCausticMap, qc, wo, est), TraceTerm::Caustic);
            }
            if (o_.indirect_light) {
                if (o_.fast_global)
                    add(i, beta * estimate(kIndirectMap, q, wo, est), TraceTerm::Indirect);
                else
                    add(i, beta * final_gather(hit, est, wo, walk.medium(), sampler, rays),
                        TraceTerm::Indirect);
            }
        }
        // The followed part: one sampled lobe per sample (unbiased), as a path tracer would.
        if (depth >= P_.options.max_depth || !split.followed) break;
        const shading::Bsdf followed = bsdf.only(split.followed);
        // Light through its glossy lobes: one light sample, MIS-weighted against the continuation.
        if (o_.direct && followed.has_non_specular())
            add(d, beta * sample_one_light(P_, hit, followed, wo, sampler, rays, true, walk.medium()),
                TraceTerm::Light);
        const auto s = followed.sample(wo, sampler.next(), sampler.next2());
        if (!s || s->weight.is_black()) break;
        if ((s->flags & shading::kTransmission) ? !o_.transmissive : !o_.specular) break;
        if (auto* r = recorder()) r->scattered(*s);
        if (split.estimated && !survives_followed(*s, sampler, beta)) break;
        beta *= s->weight;
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
                                    int medium, Sampler& sampler, RayCounts& rays) const {
    // `bsdf` is the estimated part of the vertex's BSDF: every non-delta lobe of it is gathered.
    const uint32_t lobes = bsdf.split_lobes(wo).estimated;
    const int n = std::max(o_.gather_rays, 1);
    if (!lobes) return Rgb(0.0f);
    Rgb sum(0.0f);
    for (int i = 0; i < n; ++i) {
        // Stratified over the hemisphere (sqrt(n) x sqrt(n) cells of the lobe's sample square).
        const Vec2 u = stratified_sample(i, n, sampler.next2());
        const float u_lobe = sampler.next();
        const auto s = bsdf.sample_lobes(lobes, wo, u_lobe, u);
        if (!s || s->is_specular() || s->weight.is_black()) continue;
        ++rays.bounce;
        sum += s->weight * gather_ray(accel::spawn_ray(hit, s->wi),
                                      shading::SurfaceWalk::medium_after(hit, s->wi, medium), sampler, rays);
    }
    return sum * (1.0f / float(n));
}

Rgb PhotonMapRadiance::gather_ray(Ray ray, int medium, Sampler& sampler, RayCounts& rays) const {
    Rgb L(0.0f), beta(1.0f);
    const shading::MediaSet* media = P_.active_media();
    shading::SurfaceWalk walk(P_.accel, media, medium);
    for (int depth = 0; depth <= P_.options.max_depth;) {
        accel::SurfaceHit hit;
        Rgb emitted(0.0f);
        const shading::SurfaceWalk::Event event =
            media ? walk.next(ray, hit, sampler, beta, emitted) : walk.next(ray, hit);
        L += emitted;
        if (event == shading::SurfaceWalk::Event::Medium) {
            // The free flight's weight carries sigma_s / sigma_maj...: what remains is the radiance
            // in-scattered at x, int p L_i = direct (light sampling) + volume estimates / sigma_s.
            const Vec3 x = walk.medium_point(), wo = walk.medium_wo();
            const shading::Medium& m = P_.media[walk.medium()];
            Rgb Ls = sample_one_light_in_medium(P_, x, wo, walk.medium(), sampler, rays, false);
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
            const Rgb sigma_s = m.at(x).sigma_s;
            for (int c = 0; c < 3; ++c) Ls[c] += sigma_s[c] > 0 ? est[c] / sigma_s[c] : 0.0f;
            L += beta * Ls;
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
                L += beta * est.diffuse_albedo() * kInvPi * E;
                if (auto* r = recorder())
                    r->lookup({"irradiance cache", q.p, 0, 0, est.diffuse_albedo() * kInvPi * E});
            } else {
                L += beta * estimate(kGlobalMap, q, wo, est);
            }
        }
        // Through the followed part (mirrors, glass, sharp glossy lobes) to the next vertex with an
        // estimated part; emitters found this way are direct light or caustics of the gather's
        // origin, counted there.
        if (!split.followed) break;
        const shading::Bsdf followed = bsdf.only(split.followed);
        const auto s = followed.sample(wo, sampler.next(), sampler.next2());
        if (!s || s->weight.is_black()) break;
        if (split.estimated && !survives_followed(*s, sampler, beta)) break;
        beta *= s->weight;
        if (!beta.is_finite() || beta.max() < 1e-6f) break;
        ray = accel::spawn_ray(hit, s->wi);
        walk.leave(hit, s->wi);
        ++rays.bounce;
        ++depth;
    }
    return L;
}

PhotonMapRadiance::MediumStretch PhotonMapRadiance::march(const shading::Medium& medium, int medium_index,
                                                          Vec3 o, Vec3 d, float t_end, Sampler& sampler,
                                                          RayCounts& rays) const {
    MediumStretch s;
    if (o_.direct) s.single = single_scattering(P_, medium_index, o, d, t_end, sampler, rays);
    t_end = finite_stretch(P_, o, d, t_end);
    if (!(t_end > 0)) return s;
    if (o_.volume_estimate == VolumeEstimate::Beam) {
        // The beam radiance estimate (photon/beam_estimate.h): one query of each volume map's photon
        // spheres for the whole stretch, each photon weighted by T integrated over its chord (exact
        // in homogeneous media, a table over the --volume-step steps in grids).
        const photon::StretchTransmittance T(medium, o, d, t_end, o_.volume_step, sampler.next());
        if (o_.caustics)
            s.caustic += photon::beam_radiance_estimate(maps_.volume_caustic_beams, o, d, T, medium.phase());
        if (o_.indirect_light)
            s.multiple += photon::beam_radiance_estimate(maps_.volume_beams, o, d, T, medium.phase());
        // Emission, int T sigma_a Le dt: in closed form in homogeneous media, by jittered steps of
        // --volume-step in grids.
        if (medium.emissive() && medium.homogeneous()) {
            const shading::MediumCoefficients c = medium.at(o);
            s.single += c.sigma_a * c.Le * T.integral(0.0f, T.end());
        } else if (medium.emissive()) {
            const int n = std::clamp(int(std::ceil(T.end() / o_.volume_step)), 1, 4096);
            const float dt = T.end() / float(n), jitter = sampler.next();
            for (int k = 0; k < n; ++k) {
                const float t = (float(k) + jitter) * dt;
                const shading::MediumCoefficients c = medium.at(o + d * t);
                s.single += c.sigma_a * c.Le * T.at(t) * dt;
            }
        }
        s.T = T.total();
        return s;
    }
    // Ray marching with a jittered start: every step adds T(t) dt times the volume estimates (and
    // the medium's emission); T is exact in homogeneous media and marched in grids.
    const int n = std::clamp(int(std::ceil(t_end / o_.volume_step)), 1, 4096);
    const float dt = t_end / float(n);
    const float jitter = sampler.next();
    const Vec3 wo = -d;
    Rgb T(1.0f);
    float t_prev = 0;
    for (int k = 0; k < n; ++k) {
        const float t = (float(k) + jitter) * dt;
        const Vec3 x = o + d * t;
        const shading::MediumCoefficients c = medium.at(x);
        T = medium.homogeneous() ? exp(medium.sigma_t() * -t) : T * exp(c.sigma_t() * -(t - t_prev));
        t_prev = t;
        if (T.max() < 1e-4f) break;
        const Rgb w = T * dt;
        if (o_.caustics)
            s.caustic += w * photon::volume_radiance_estimate(maps_.volume_caustic(), volume_caustic_est_, x,
                                                              wo, medium.phase());
        if (o_.indirect_light)
            s.multiple +=
                w * photon::volume_radiance_estimate(maps_.volume(), volume_est_, x, wo, medium.phase());
        if (!c.Le.is_black()) s.single += w * c.sigma_a * c.Le;
    }
    s.T = medium.homogeneous() ? exp(medium.sigma_t() * -t_end)
                               : T * exp(medium.at(o + d * t_end).sigma_t() * -(t_end - t_prev));
    return s;
}

}  // namespace phos::integrators
