// The camera subpath of bdpt and vcm with every strategy of the iteration (see camera_subpath.h).
// A pixel's value per iteration is its camera subpaths' estimate plus the light-tracing splats that
// land on it, both added to the fixed-point sums (fixed_film.h).
#include "integrators/camera_subpath.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/low_discrepancy.h"
#include "dist/ranks.h"
#include "render/path_recorder.h"
#include "shading/surface_walk.h"
#include "spectrum/color.h"

namespace phos::integrators::vcm {

Iteration::PixelMerge Iteration::pixel(size_t i) const {
    if (!strategies.merge || strategies.merge_everywhere || !pixel_radius)
        return {factors, uniform_norm, radius * radius};
    const float r = (*pixel_radius)[i] * shrink;
    const float eta = kPi * r * r * light_paths * float(camera_samples);
    return {MisFactors::of(strategies.connect, true, eta), 1 / eta, r * r};
}

Iteration iteration_for(const Strategies& strategies, const ProgressiveOptions& o) {
    Iteration it;
    it.strategies = strategies;
    it.direct_samples = bidirectional_direct_samples(o);
    it.camera_samples = strategies.merge_first_vertex_only() ? o.vcm_camera_samples : 1;
    it.go_on = strategies.merge_first_vertex_only() ? o.vcm_continue : 1.0f;
    it.direct_mis = float(it.direct_samples) * o.direct_mis_scale * float(it.camera_samples);
    it.rr_weight = strategies.light_tracing_only ? 0.0f : o.vcm_rr_weight;
    if (!strategies.merge) it.factors = it.light_factors = MisFactors::of(true, false, 0);
    return it;
}

void begin_merging_iteration(Iteration& it, uint64_t iteration, float r1, float alpha) {
    it.shrink = float(std::pow(double(iteration + 1), 0.5 * (double(alpha) - 1)));
    it.radius = r1 * it.shrink;  // r1: the largest per-pixel radius
    const float eta = kPi * it.radius * it.radius * it.light_paths;
    it.factors = MisFactors::of(it.strategies.connect, true, eta);
    it.uniform_norm = 1 / eta;
    // With per-pixel merging areas the light subpaths carry dVM without 1 / eta^2.
    const bool per_pixel = it.pixel_radius != nullptr;
    it.light_factors = per_pixel ? MisFactors{0, it.strategies.connect ? 1.0f : 0.0f} : it.factors;
}

namespace {

// Everything a camera subpath needs to evaluate its strategies.
struct Context {
    const Prepared& P;
    const Iteration& it;
    FixedFilm& film;
    std::span<const Vertex> light_path;  // this pixel's light subpath (connections)
    const LightVertexGrid* merging;      // the iteration's light vertices on surfaces
    RayCounts& rays;
    Rgb* parts;  // the camera subpath's estimate per Part
    // The pixel's stratified sequences (core/low_discrepancy.h), keyed per pixel: over the
    // iterations, its first non-delta vertex's light samples (point sample x direct_samples + k)
    // cover the lights evenly, as SPPM's do. `sample`: the camera sample's index in them
    // (iteration x camera_samples + j).
    uint64_t sequence_key;
    uint32_t sample;
    Iteration::PixelMerge merge_at;  // merging at the pixel's first non-delta vertex
};

// The probability that a camera subpath goes on past vertex v when v is its first non-delta vertex
// x_f. On a lone Lambert lobe merging there takes over what the continuation's strategies would
// add (with --vcm-camera-samples 3 the bench scenes' images had the same error with and without
// them, in 17-25 % less time: docs/bidirectional.md), so they go on with it.go_on (0 by default:
// merging, light samples, connections and light tracing of x_f make every path); glossy vertices
// and vertices in media, where no merging takes over, always go on. It is a factor of the
// continuation's density in every weight that counts a strategy continuing from x_f (the light
// side of connections, merging and light samples at x_f and of light tracing of x_f), in the
// continuation's own MIS state, and 1 / go_on in its throughput: a partition of unity for any
// value, 0 included.
float go_on_from(const Iteration& it, const Vertex& v) {
    return !v.in_medium && v.bsdf && v.bsdf->is_lambertian() ? it.go_on : 1.0f;
}

// Russian roulette on a strategy's shadow ray by its MIS weight w: below it.rr_weight the ray is
// cast with probability q = w / rr_weight and its contribution counted 1 / q times, so the estimate
// stays unbiased. Where another strategy makes most of a path (merging, on diffuse surfaces), the
// connection's few percent of it are not worth a ray each time. Returns 1 / q, or 0 when the ray
// is not cast.
float weight_roulette(const Iteration& it, float w, Sampler& sampler) {
    if (!(w < it.rr_weight)) return 1;
    const float q = w / it.rr_weight;
    return sampler.next() < q ? 1 / q : 0.0f;
}

// Light tracing (t = 1): light vertex `v` seen by the camera, splatted onto the film.
void connect_to_camera(const Context& C, const Vertex& v, Sampler& sampler) {
    CameraModel::Connection c;
    if (!C.P.camera.connect(v.p, sampler.next2(), c)) return;
    const Scattering s = evaluate(C.P, v, c.wi, shading::TransportMode::Importance, v.lambda);
    if (s.f.is_black()) return;
    const float camera_pdf_a = c.pdf_dir * s.cos / (c.distance * c.distance);
    // A light subpath's first vertex seen by the camera makes a path whose light-sampling strategy
    // is at the camera's first vertex: its ratio (all of dVCM before any scattering) counts the
    // direct_samples samples taken there.
    SubpathMis mis = v.mis;
    if (v.length == 1) mis.dVCM *= vcm::mis(C.it.direct_mis);
    const size_t pixel = size_t(int(c.fy)) * size_t(C.P.options.width) + size_t(int(c.fx));
    // Merging at v is the strategy of the camera subpaths of the pixel the splat lands on.
    // (The camera subpath would go on from v with probability go_on.)
    float w = C.it.strategies.light_tracing_only
                  ? 1.0f
                  : 1 / (1 + connect_side(mis, camera_pdf_a, s.pdf_rev * go_on_from(C.it, v), v.mergeable,
                                          C.it.pixel(pixel).factors));
    w *= weight_roulette(C.it, w, sampler);
    if (w == 0) return;
    ++C.rays.shadow;
    const Spectrum T = transmittance_to(C.P, v, c.lens, sampler, v.lambda);
    if (T.is_black()) return;
    const Rgb value = spectrum::to_srgb(v.beta * s.f * T * (w * camera_pdf_a), v.lambda);
    if (C.P.filter.is_pixel_box()) {
        C.film.add(pixel, value, part_at_first_vertex(v));
        return;
    }
    // A wider pixel filter shares the splat out to every pixel whose filter covers its film position
    // (the camera subpaths of those pixels sample positions with the same filter).
    const Vec2 r = C.P.filter.radius();
    const int w_px = C.P.options.width, h_px = C.P.options.height;
    const int x0 = std::max(0, int(std::ceil(c.fx - 0.5f - r.x))),
              x1 = std::min(w_px - 1, int(std::floor(c.fx - 0.5f + r.x)));
    const int y0 = std::max(0, int(std::ceil(c.fy - 0.5f - r.y))),
              y1 = std::min(h_px - 1, int(std::floor(c.fy - 0.5f + r.y)));
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const float f = C.P.filter.splat_weight(Vec2(c.fx - (float(x) + 0.5f), c.fy - (float(y) + 0.5f)));
            if (f != 0) C.film.add(size_t(y) * size_t(w_px) + size_t(x), value * f, part_at_first_vertex(v));
        }
}

// One light sample at camera vertex `v` (s = 1) from the random numbers (u_light, u), weighted
// against the other strategies with the light sampling density scaled by `n`, the light samples
// taken at this vertex (multi-sample MIS, Veach 1997 sec. 9.2.2: the n samples together are one
// strategy of density n p).
Spectrum direct_light_sample(const Context& C, const Vertex& v, float u_light, Vec2 u, float n, float n_mis,
                             float go_on, Sampler& sampler, const Wavelengths& lambda) {
    const Prepared& P = C.P;
    if (P.lights.size() == 0) return Spectrum(0.0f);
    float pmf = 0;
    const size_t li = P.lights.choose(u_light, pmf);
    if (!(pmf > 0)) return Spectrum(0.0f);
    const shading::Light& light = P.lights[li];
    const shading::LightLiSample ls = light.sample_Li(v.p, u, lambda);
    if (!(ls.pdf > 0) || ls.L.is_black()) return Spectrum(0.0f);
    const Scattering s = evaluate(P, v, ls.wi, shading::TransportMode::Radiance, lambda);
    if (s.f.is_black()) return Spectrum(0.0f);
    const bool at_infinity = !(ls.distance < kInf);
    const bool area = P.scene.lights[li].kind == scene::Light::Kind::Area;
    float pdf_pos = 0, pdf_dir = 0;
    light.pdf_Le(ls.n_light, -ls.wi, pdf_pos, pdf_dir);
    const float cos_light = area ? std::fabs(dot(ls.n_light, ls.wi)) : 1.0f;
    const float d2 = at_infinity ? 1.0f : ls.distance * ls.distance;
    // BSDF sampling competes with area and infinite lights only (vcm_mis.h: direct_density). An
    // infinite light's direct density is that of its sample (a portal's depends on the point).
    const float direct_pdf_a =
        n_mis * direct_density(pmf, pdf_pos, light.is_infinite() ? ls.pdf : pdf_dir, at_infinity);
    const float direct_pdf_w = ls.delta ? 0.0f : at_infinity ? direct_pdf_a : direct_pdf_a * d2 / cos_light;
    float w = direct_light_weight(v.mis, s.pdf_dir * go_on, s.pdf_rev, direct_pdf_a, pmf * pdf_pos * pdf_dir,
                                  direct_pdf_w, v.mergeable && C.it.strategies.merge_next_to_light(),
                                  s.cos / d2, C.merge_at.factors);
    w *= weight_roulette(C.it, w, sampler);
    if (w == 0) return Spectrum(0.0f);
    ++C.rays.shadow;
    const Spectrum T = transmittance_to(P, v, ls.p_light, sampler, lambda);
    if (T.is_black()) return Spectrum(0.0f);
    return s.f * ls.L * T * (w * s.cos / (n * pmf * ls.pdf));
}

// Direct light sampling at camera vertex `v` (s = 1): at the camera subpath's first non-delta vertex
// (`first`: the first vertex, or the first one seen through mirrors and glass), C.it.direct_samples
// samples from the pixel's stratified sequences, as SPPM's visible points take them (each estimate
// also divided by the camera samples, which all take them); deeper, one independent sample.
// `go_on`: the probability of the camera subpath going on from v (below 1 only when first).
Spectrum direct_light(const Context& C, const Vertex& v, bool first, float go_on, Sampler& sampler,
                      const Wavelengths& lambda) {
    if (!first) {
        const float u_light = sampler.next();
        return direct_light_sample(C, v, u_light, sampler.next2(), 1.0f, 1.0f, 1.0f, sampler, lambda);
    }
    const int n = C.it.direct_samples;
    const float all = float(n * C.it.camera_samples);
    // A lone point-like light gives the same sample every time: one shadow ray stands for all n.
    if (C.P.lights.size() == 1 && C.P.lights[0].is_delta())
        return direct_light_sample(C, v, 0.5f, Vec2(0.5f, 0.5f), all, C.it.direct_mis, go_on, sampler,
                                   lambda) *
               float(n);
    Spectrum sum(0.0f);
    for (int k = 0; k < n; ++k) {
        const uint32_t i = C.sample * uint32_t(n) + uint32_t(k);
        sum += direct_light_sample(C, v, padded_point1(i, hash_combine(C.sequence_key, 3)),
                                   padded_point2(i, hash_combine(C.sequence_key, 4)), all, C.it.direct_mis,
                                   go_on, sampler, lambda);
    }
    return sum;
}

// Connections of camera vertex `v` (depth d) with every vertex of its light subpath (s, t >= 2);
// `go_on`: the probability of the camera subpath going on from v.
// The sum is a colour: each connection at the wavelengths both subpaths share (joined).
Rgb connect_light_path(const Context& C, const Vertex& v, float go_on, Sampler& sampler, const Spectrum& beta,
                       const Wavelengths& lambda) {
    Rgb sum(0.0f);
    for (const Vertex& l : C.light_path) {
        if (l.length + v.length > C.P.options.max_depth) continue;
        Vec3 d = l.p - v.p;
        const float dist2 = dot(d, d);
        if (!(dist2 > 0)) continue;
        const float dist = std::sqrt(dist2);
        d = d / dist;
        const Scattering sc = evaluate(C.P, v, d, shading::TransportMode::Radiance, lambda);
        const Scattering sl = evaluate(C.P, l, -d, shading::TransportMode::Importance, lambda);
        if (sc.f.is_black() || sl.f.is_black()) continue;
        const float camera_pdf_a = go_on * sc.pdf_dir * sl.cos / dist2;  // v's BSDF reaching l
        const float light_pdf_a = sl.pdf_dir * sc.cos / dist2;           // l's BSDF reaching v
        float w = 1 / (connect_side(l.mis, camera_pdf_a, sl.pdf_rev,
                                    l.mergeable && C.it.strategies.merge_everywhere, C.merge_at.factors) +
                       1 + connect_side(v.mis, light_pdf_a, sc.pdf_rev, v.mergeable, C.merge_at.factors));
        w *= weight_roulette(C.it, w, sampler);
        if (w == 0) continue;
        ++C.rays.shadow;
        const Spectrum T = transmittance_between(C.P, v, l, sampler, lambda);
        if (T.is_black()) continue;
        sum += spectrum::to_srgb(beta * sc.f * sl.f * l.beta * T * (w * sc.cos * sl.cos / dist2),
                                 joined(lambda, l.lambda));
    }
    return sum;
}

// Merging camera vertex `v` with the light vertices within the radius (vertex merging): the sum
// per Part of the light vertex (meaningful when v is the camera's first vertex). `first`: v is the
// camera subpath's first non-delta vertex; `go_on`: the probability of the camera subpath going on
// from v (below 1 only when first).
// Each light vertex's light meets v's BSDF at that vertex's wavelengths: the sums are colours.
void merge(const Context& C, const Vertex& v, bool first, float go_on, Rgb sum[kParts]) {
    const int max_length = C.P.options.max_depth + 1 - v.length;
    const std::vector<MergeVertex>& lights = C.merging->vertices;
    // A light vertex next to the light (merged only with merge_next_to_light) completes a path
    // whose light-sampling strategy is at v, with its direct_samples samples when v is the first
    // non-delta vertex.
    const float direct_scale = first ? vcm::mis(C.it.direct_mis) : 1.0f;
    const auto add = [&](const MergeVertex& l, const Spectrum& f, float pdf_dir, float pdf_rev) {
        float w = 1;
        if (!C.it.strategies.ppm) {
            SubpathMis lm = l.mis;
            if (l.length == 1) lm.dVCM *= direct_scale;
            if (C.it.pixel_radius) lm.dVM *= C.merge_at.factors.vc;  // the pixel's 1 / eta^2
            w = merge_weight(v.mis, lm, pdf_dir * go_on, pdf_rev, C.merge_at.factors);
        }
        sum[l.part] += l.beta.of(f) * (w * C.merge_at.merge_norm);
    };
    const shading::Bsdf& b = *v.bsdf;
    if (b.is_lambertian()) {
        // Bsdf::eval and pdf of a lone Lambert lobe, written out: reflection on wo's side of ng
        // and of the shading normal, f = kd / pi, pdf = cos / pi.
        const Vec3 ng = b.geometric_normal(), ns = b.frame().n;
        const float side = dot(v.wo, ng) > 0 ? 1.0f : -1.0f;
        const float cos_o = dot(v.wo, ns) * side;
        const float pdf_rev = cos_o > 0 ? cos_o * kInvPi : 0.0f;
        const spectrum::RgbSpectrum& kd = b.diffuse_spectrum();
        C.merging->grid.query(v.p, C.merge_at.radius2, [&](uint32_t i, float) {
            const MergeVertex& l = lights[i];
            const float cos_i = dot(l.wo, ns) * side;
            if (l.length > max_length || !(dot(l.wo, ng) * side > 0) || !(cos_i > 0)) return;
            add(l, kd.sample(l.lambda) * kInvPi, cos_i * kInvPi, pdf_rev);
        });
        return;
    }
    C.merging->grid.query(v.p, C.merge_at.radius2, [&](uint32_t i, float) {
        const MergeVertex& l = lights[i];
        if (l.length > max_length) return;
        const Wavelengths lambda = l.wavelengths();
        const Scattering s = evaluate(C.P, v, l.wo, shading::TransportMode::Radiance, lambda);
        if (!s.f.is_black()) add(l, s.f, s.pdf_dir, s.pdf_rev);
    });
}

// The emitter the camera subpath hit (s = 0): area light `li` at a point with normal n, seen along wo.
// `after_first`: the vertex before the emitter was the camera subpath's first non-delta one, whose
// light-sampling strategy took C.it.direct_samples samples.
// `from`: the camera subpath's vertex before the emitter (an infinite light's direct density there).
float emitter_weight(const Context& C, const SubpathMis& camera, size_t li, Vec3 n, Vec3 wo, bool at_infinity,
                     bool after_first, Vec3 from) {
    const shading::Light& light = C.P.lights[li];
    float pdf_pos = 0, pdf_dir = 0;
    light.pdf_Le(n, wo, pdf_pos, pdf_dir);
    const float pmf = C.P.lights.pmf(li);
    const float samples = after_first ? C.it.direct_mis : 1.0f;
    const float direct_dir = light.is_infinite() ? light.pdf_Li(from, -wo, {}, {}) : pdf_dir;
    return emitter_hit_weight(camera, samples * direct_density(pmf, pdf_pos, direct_dir, at_infinity),
                              pmf * pdf_pos * pdf_dir, C.it.strategies.merge_next_to_light());
}

// A camera subpath between its vertices: its throughput and MIS state, where it left from, and
// what --layers needs of its vertices so far.
struct CameraWalk {
    SubpathState path{Spectrum(1.0f), {}, {}};
    Spectrum beta0{1.0f};  // the throughput it starts with: the camera's weight
    Vec3 from;
    bool specular_chain = true;  // only delta bounces so far: the camera sees what it meets directly
    // The previous vertex was the first non-delta one (its light samples: direct_light's `first`).
    bool after_first = false;
    // Whether x1 (the first vertex) was a delta bounce, and whether every vertex after x1 so far
    // was.
    bool x1_delta = false, delta_after_x1 = true;

    // The Part of light found (emission) or sampled at the vertex reached at `depth`.
    Part found_part(int depth) const {
        if (depth == 1) return kDirect;
        if (x1_delta) return kSpecular;
        if (depth == 2) return kDirect;
        return delta_after_x1 ? kCaustic : kIndirect;
    }
    Part sampled_part(int depth) const { return depth == 1 ? kDirect : x1_delta ? kSpecular : kIndirect; }
    // The Part of a connection's light, and of merged light of Part k, at the vertex at `depth`.
    Part connected_part() const { return x1_delta ? kSpecular : kIndirect; }
    Part merged_part(int depth, int k) const { return depth == 1 ? Part(k) : connected_part(); }
};

// The camera subpath escaped the scene after `depth` segments: the background (seen directly, or
// with --background-light), and the lights at infinity (s = 0) but for ppm past the specular chain.
void escaped(const Context& C, const CameraWalk& w, const Ray& ray, int depth, float found_scale) {
    const Prepared& P = C.P;
    const Vec3 dir = normalize(ray.dir);
    const Spectrum& beta = w.path.beta;
    const Wavelengths& lambda = w.path.lambda;
    if (w.specular_chain || P.options.background_light)
        C.parts[w.found_part(depth)] += spectrum::to_srgb(beta * P.background(lambda) * found_scale, lambda);
    if (C.it.strategies.ppm && !w.specular_chain) return;
    for (size_t i : P.lights.infinite_lights()) {
        const Spectrum Le = P.lights[i].escaped_Le(ray.origin, dir, lambda);
        if (Le.is_black()) continue;
        const float wt =
            depth == 1 ? 1.0f : emitter_weight(C, w.path.mis, i, {}, -dir, true, w.after_first, w.from);
        C.parts[w.found_part(depth)] += spectrum::to_srgb(beta * Le * (wt * found_scale), lambda);
    }
}

// At surface vertex `v` (depth segments from the camera): its own emission (s = 0), and on the
// camera's specular chain the .scn glow and ambient terms.
void emission_at(const Context& C, const CameraWalk& w, const Vertex& v, const accel::SurfaceHit& hit,
                 int depth, float found_scale) {
    const Prepared& P = C.P;
    const Spectrum& beta = w.path.beta;
    const Wavelengths& lambda = w.path.lambda;
    const bool ppm = C.it.strategies.ppm;
    const Spectrum Le = P.emitted(hit, v.wo, lambda);
    if (!Le.is_black() && (!ppm || w.specular_chain)) {
        const float wt = depth == 1 || ppm ? 1.0f
                                           : emitter_weight(C, w.path.mis, size_t(hit.area_light), hit.ng,
                                                            v.wo, false, w.after_first, w.from);
        C.parts[w.found_part(depth)] += spectrum::to_srgb(beta * Le * (wt * found_scale), lambda);
    }
    if (w.specular_chain)
        C.parts[w.found_part(depth)] +=
            spectrum::colour_through(beta, lambda, P.glow(hit.material)) * found_scale;
}

// The strategies at a camera vertex `v` with a non-delta lobe (or in a medium): light samples,
// connections (`full` camera samples only) and merging. False when the camera subpath ends here
// (ppm after its merge).
bool strategies_at(const Context& C, const CameraWalk& w, const Vertex& v, int depth, float go_on, bool full,
                   Sampler& sampler) {
    const Spectrum& beta = w.path.beta;
    const Wavelengths& lambda = w.path.lambda;
    if (C.it.strategies.connect) {
        C.parts[w.sampled_part(depth)] +=
            spectrum::to_srgb(beta * direct_light(C, v, w.specular_chain, go_on, sampler, lambda), lambda);
        if (full && !C.light_path.empty())
            C.parts[w.connected_part()] += connect_light_path(C, v, go_on, sampler, beta, lambda);
    }
    if (v.mergeable) {
        Rgb merged[kParts] = {Rgb(0.0f), Rgb(0.0f), Rgb(0.0f), Rgb(0.0f)};
        merge(C, v, w.specular_chain, go_on, merged);
        for (int k = 0; k < kParts; ++k)
            C.parts[w.merged_part(depth, k)] += spectrum::colour_through(beta, lambda, merged[k]);
        if (C.it.strategies.ppm) return false;  // ppm: the first non-delta camera vertex gathers everything
    }
    return true;  // an extra camera sample goes past its x_f only through a delta lobe (go_on_past)
}

// Continues the camera subpath from `v` (radiance transport): past x_f with probability go_on,
// then a sampled direction, Russian roulette, and the ray to the next vertex. False when it ends.
// An extra camera sample (not `full`) goes past its x_f only through a delta lobe, always: what a
// delta lobe of x_f shows (a smooth coat's reflection over a diffuse walk) is found by every
// camera sample, as the vertices before x_f are, while the rest past x_f is the full sample's.
bool go_on_past(const Context& C, CameraWalk& w, const Vertex& v, int depth, bool smooth, float go_on,
                bool full, Sampler& sampler, shading::SurfaceWalk& walk, Ray& ray) {
    const bool extra_at_x_f = !full && w.specular_chain && smooth;
    if (go_on < 1 && !extra_at_x_f) {
        if (!(sampler.next() < go_on)) return false;
        w.path.beta *= 1 / go_on;
    }
    const std::optional<Direction> d = continue_from(
        C.P, v, shading::TransportMode::Radiance, {C.merge_at.factors, v.mergeable, go_on}, sampler, w.path);
    if (!d || (extra_at_x_f && !d->delta)) return false;
    w.after_first = w.specular_chain && smooth;  // (a delta lobe sampled here zeroes dVCM anyway)
    w.specular_chain = w.specular_chain && d->delta;
    if (depth == 1)
        w.x1_delta = d->delta;
    else
        w.delta_after_x1 = w.delta_after_x1 && d->delta;
    ++C.rays.bounce;
    if (!survives(depth, w.path.beta, w.beta0, sampler)) return false;
    w.from = v.p;
    ray = leave_vertex(v, d->wi, walk);
    return true;
}

// One camera subpath through film position (fx, fy) with every strategy of the iteration: adds its
// estimate for the pixel to C.parts (light tracing adds to other pixels itself). Without `full`
// (the pixel's extra camera samples, Iteration::camera_samples) it makes no connections and ends
// after its first non-delta vertex's light samples and merging, unless that vertex also has a
// delta lobe and samples it. What the camera subpath finds up to
// that vertex counts 1 / camera_samples (every camera sample finds it).
void camera_path(const Context& C, float fx, float fy, Vec2 lens, Sampler& sampler, const Wavelengths& lambda,
                 bool full) {
    const Prepared& P = C.P;
    float camera_weight = 1;
    const Ray first = P.camera.generate_ray(fx, fy, lens, camera_weight);
    ++C.rays.camera;
    if (camera_weight == 0) return;  // the camera's lenses blocked the ray: it finds nothing
    Ray ray = first;
    const float camera_pdf = P.camera.direction_pdf(normalize(first.dir));
    CameraWalk w;
    w.path.beta = w.beta0 = Spectrum(camera_weight);
    w.path.lambda = lambda;
    if (auto* r = recorder()) r->wavelengths(lambda);
    w.path.mis = camera_pdf > 0 ? start_camera(camera_pdf) : SubpathMis{};
    w.from = first.origin;
    const float prefix_scale = 1 / float(C.it.camera_samples);
    const shading::MediaSet* media = P.active_media();
    shading::SurfaceWalk walk(P.accel, media, P.camera_medium());
    for (int depth = 1;; ++depth) {
        accel::SurfaceHit hit;
        Spectrum emitted(0.0f);
        const auto event =
            media ? walk.next(ray, hit, sampler, w.path.lambda, w.path.beta, emitted) : walk.next(ray, hit);
        // Found up to the first non-delta vertex: by every camera sample of the pixel.
        const float found_scale = w.specular_chain ? prefix_scale : 1.0f;
        // Media's own emission: only camera subpaths find it.
        C.parts[w.found_part(depth)] += spectrum::to_srgb(emitted * found_scale, w.path.lambda);
        if (event == shading::SurfaceWalk::Event::Escaped) {
            escaped(C, w, ray, depth, found_scale);
            return;
        }
        if (event != shading::SurfaceWalk::Event::Surface && event != shading::SurfaceWalk::Event::Medium)
            return;
        Vertex v = reach_vertex(P, event, walk, ray, hit, depth, w.path.beta, w.path.lambda);
        arrive(w.path.mis, length(v.p - w.from), cos_at(v, v.wo), true);
        v.mis = w.path.mis;
        if (!v.in_medium) emission_at(C, w, v, hit, depth, found_scale);
        if (depth > P.options.max_depth || C.it.strategies.light_tracing_only) return;
        const bool smooth = v.in_medium || v.bsdf->has_non_specular();
        // Merging here: at every vertex, or only at the first non-delta one.
        v.mergeable = C.it.strategies.merge && !v.in_medium && smooth &&
                      (C.it.strategies.merge_everywhere || w.specular_chain);
        // The probability of going on past this vertex: below 1 only at x_f (go_on_from).
        const float go_on = w.specular_chain && smooth ? go_on_from(C.it, v) : 1.0f;
        if (smooth && !strategies_at(C, w, v, depth, go_on, full, sampler)) return;
        if (!go_on_past(C, w, v, depth, smooth, go_on, full, sampler, walk, ray)) return;
    }
}

// Pixel (x, y)'s share of iteration `iteration`: light tracing of its light subpath, then its camera
// samples; camera sample j is point iteration x camera_samples + j of the pixel's sequences (its
// position in the pixel and on the lens, as in SPPM; the rest is independent random). The first
// (with the light-tracing sampler) takes every strategy, the others (each its own sampler) stop
// after x_f.
void render_pixel(const Prepared& P, const Iteration& it, const LightVertexGrid* merging,
                  std::span<const Vertex> light, int x, int y, uint64_t iteration, FixedFilm& sums,
                  RayCounts& rays) {
    const RenderOptions& ro = P.options;
    const size_t i = size_t(y) * size_t(ro.width) + size_t(x);
    Rgb parts[kParts] = {Rgb(0.0f), Rgb(0.0f), Rgb(0.0f), Rgb(0.0f)};
    const uint64_t key = Sampler(ro.seed, 0x7663707365717563ULL, i).next_bits();
    const uint32_t first_sample = uint32_t(iteration) * uint32_t(it.camera_samples);
    Context C{P, it, sums, light, merging, rays, parts, key, first_sample, it.pixel(i)};
    Sampler sampler(ro.seed, 0x766370657965ULL, i, iteration);
    if (it.strategies.light_tracing())
        for (const Vertex& v : light) connect_to_camera(C, v, sampler);
    // The first camera sample shares the pixel's light subpath's wavelengths (it connects to it);
    // the others draw their own.
    const auto camera_sample = [&](int j, Sampler& s) {
        C.sample = first_sample + uint32_t(j);
        const PixelFilterSampler::FilmSample at =
            P.filter.sample(padded_point2(C.sample, hash_combine(key, 1)));
        const Vec2 lens = padded_point2(C.sample, hash_combine(key, 2));
        const Wavelengths lambda =
            j == 0
                ? subpath_wavelengths(ro.seed, i, iteration)
                : Wavelengths::visible(spectrum::wavelength_sequence_point(C.sample, hash_combine(key, 3)));
        if (at.weight == 1) {
            camera_path(C, float(x) + at.position.x, float(y) + at.position.y, lens, s, lambda, j == 0);
            return;
        }
        // A weighted sample's estimate is scaled as a whole (its path throughput stays positive
        // for Russian roulette).
        Rgb own[kParts] = {Rgb(0.0f), Rgb(0.0f), Rgb(0.0f), Rgb(0.0f)};
        C.parts = own;
        camera_path(C, float(x) + at.position.x, float(y) + at.position.y, lens, s, lambda, j == 0);
        C.parts = parts;
        for (int k = 0; k < kParts; ++k) parts[k] += own[k] * at.weight;
    };
    camera_sample(0, sampler);
    for (int j = 1; j < it.camera_samples; ++j) {
        Sampler extra(ro.seed, hash_combine(0x7663706578ULL, uint64_t(j)), i, iteration);
        camera_sample(j, extra);
    }
    for (int k = 0; k < kParts; ++k) sums.add(i, parts[k], Part(k));
}

}  // namespace

void camera_pass(const Prepared& P, const Iteration& it, const LightVertexGrid* merging,
                 const std::vector<film::Tile>& tiles, uint64_t iteration, FixedFilm& sums,
                 const LightPathSource& light_path) {
    tbb::parallel_for(size_t(0), tiles.size(), [&](size_t t) {
        if (!dist::owns(t)) return;
        const film::Tile& tile = tiles[t];
        RayCounts rays;
        std::vector<Vertex> light;  // the pixel's light subpath, with its BSDFs
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                light.clear();
                light_path(size_t(y) * size_t(P.options.width) + size_t(x), light, rays);
                render_pixel(P, it, merging, light, x, y, iteration, sums, rays);
            }
        P.stats.add_rays(rays);
    });
}

}  // namespace phos::integrators::vcm
