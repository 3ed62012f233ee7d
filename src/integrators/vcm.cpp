// The bdpt / vcm engine (see vcm.h). Per iteration: the light pass (vcm: every pixel's light
// subpath, stored and indexed for merging; bdpt traces each one beside its camera subpath), then
// the camera pass, tile by tile. Each pixel's value is the mean over iterations of its camera
// subpath's estimate plus the light-tracing splats that landed on it; both are added as 2^-30
// fixed-point integers, so the sums do not depend on the order threads (or ranks) add them.
#include "integrators/vcm.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <span>

#include "core/byte_buffer.h"
#include "core/low_discrepancy.h"
#include "dist/ranks.h"
#include "film/tiles.h"
#include "integrators/bidirectional_path.h"
#include "integrators/sppm.h"
#include "integrators/sppm_core.h"
#include "integrators/vertex_grid.h"
#include "render/progressive_budget.h"
#include "shading/surface_walk.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

namespace {

using vcm::Scattering;
using vcm::SubpathMis;
using vcm::Vertex;

constexpr double kFixedScale = 1073741824.0;  // 2^30: the sums' fixed point

// The component a contribution belongs to with --layers (path_radiance.h's Component, in
// its order): what reached the camera after a delta bounce at its first vertex x1
// (specular), else light reaching x1 straight from the light (direct, x1's own emission too),
// through delta bounces only (caustic), or through a diffuse or glossy vertex (indirect).
enum Part { kDirect, kCaustic, kIndirect, kSpecular, kParts };
const char* const kPartNames[kParts] = {"direct", "caustic", "indirect", "specular"};

// Light arriving at light vertex `l`, seen at the camera's first vertex x1 = l.
Part part_at_first_vertex(const vcm::VertexCore& l) {
    return l.length == 1 ? kDirect : l.delta_chain ? kCaustic : kIndirect;
}

// The image's per-pixel sums over iterations (r, g, b), in fixed point: any order of adding gives
// the same bits. Rounding to 2^-30 per contribution is far below a float's resolution of the
// pixel values phos writes. Plane 0 is the image; with layers, planes 1.. are the Parts.
class FixedFilm {
public:
    FixedFilm(size_t pixels, bool layers) : pixels_(pixels), planes_(layers ? 1 + kParts : 1) {
        sums_ = std::vector<std::atomic<int64_t>>(pixels * 3 * planes_);
    }
    bool layers() const { return planes_ > 1; }
    void add(size_t pixel, Rgb v, Part part) {
        if (!v.is_finite()) {
            rejected_.fetch_add(1, std::memory_order_relaxed);
            return;
        }
        for (int c = 0; c < 3; ++c) {
            const double x = std::clamp(double(v[c]) * kFixedScale, -4.6e18, 4.6e18);
            const auto q = int64_t(std::llround(x));
            if (q == 0) continue;
            sums_[pixel * 3 + size_t(c)].fetch_add(q, std::memory_order_relaxed);
            if (planes_ > 1)
                sums_[((1 + size_t(part)) * pixels_ + pixel) * 3 + size_t(c)].fetch_add(
                    q, std::memory_order_relaxed);
        }
    }
    size_t planes() const { return planes_; }
    std::vector<int64_t> values() const {
        std::vector<int64_t> v(sums_.size());
        for (size_t i = 0; i < v.size(); ++i) v[i] = sums_[i].load();
        return v;
    }
    void set(const std::vector<int64_t>& v) {
        for (size_t i = 0; i < v.size() && i < sums_.size(); ++i) sums_[i].store(v[i]);
    }
    uint64_t rejected() const { return rejected_.load(); }

private:
    size_t pixels_, planes_;
    std::vector<std::atomic<int64_t>> sums_;
    std::atomic<uint64_t> rejected_{0};
};

// What merging needs of a light vertex on a surface, packed (the grid visits many per query).
// Plain data, so that ranks can exchange them (under MPI each traces its own pixels' subpaths).
struct MergeVertex {
    Vec3 p, wo;
    Rgb beta;
    SubpathMis mis;
    int length;
    Part part;      // part_at_first_vertex
    uint32_t path;  // the light subpath it belongs to: the order every rank count agrees on
};

// The strategies of one iteration and their constants.
struct Iteration {
    bool connect = true, merge = false, ppm = false;
    bool lt = false;  // light tracing alone (with the emitters the camera sees directly)
    // Merging at the vertex next to the light (direct light): ppm only, where nothing else finds
    // it; vcm leaves direct light to light sampling, emitter hits and light tracing (vcm_mis.h).
    bool merge_direct = false;
    // Light samples at the camera subpath's first non-delta vertex x_f (--direct-samples; deeper
    // vertices take one): the light-sampling strategy of paths whose vertex next to the light is
    // x_f has n times the density in every weight (direct_light_sample, the emitter hit right
    // after x_f, light tracing of a light subpath's first vertex).
    int direct_samples = 1;
    // The count the weights give those samples: direct_samples x --direct-mis-scale x
    // camera_samples. Any positive count used alike in all three weights keeps them a partition of
    // unity (the estimate unbiased); a larger one hands more of the direct light to the stratified
    // light samples, which converge faster than the BSDF samples and light-tracing splats they
    // compete with (on the Cornell boxes' walls, 8 cut the variance 3.4x at no cost;
    // docs/bidirectional.md).
    float direct_mis = 1;
    bool one_delta_light = false;  // the scene's only light is a point-like one (delta position)
    // Merging at every camera vertex (Georgiev et al.) or only at the camera subpath's first
    // non-delta vertex (--vcm-merge first, as SPPM gathers): vcm_mis.h.
    bool merge_everywhere = true;
    // Camera samples per pixel (--vcm-camera-samples M, merging at the first non-delta vertex only):
    // the first camera subpath takes every strategy; the other M - 1 stop after their first
    // non-delta vertex x_f. So the strategies that end at x_f on the camera side (its light samples,
    // merging there, emission found up to it) are M samples per iteration and every other strategy
    // one: multi-sample MIS (Veach 1997 sec. 9.2.2) counts those M times in every weight (M x eta in
    // the pixel's merging factors, M x direct_mis) and each of the M samples' estimates of them is
    // divided by M. Merging at x_f being a path's only merging strategy, eta is already per pixel.
    int camera_samples = 1;
    // The probability that the first camera sample goes on past its first non-delta vertex x_f
    // where x_f is a lone Lambert lobe (--vcm-continue, first-vertex merging; 1 elsewhere):
    // go_on_from.
    float go_on = 1;
    // Merging radii: pixel i's camera subpaths merge within pixel_radius[i] * shrink (first-vertex
    // merging; null: every pixel `radius`), and the grid is built for the largest, `radius`.
    float radius = 0, shrink = 1, light_paths = 0;
    const std::vector<float>* pixel_radius = nullptr;
    // Strategies whose MIS weight is below this cast their shadow ray by Russian roulette
    // (weight_roulette; 0: always).
    float rr_weight = 0;
    vcm::MisFactors factors;        // bdpt; vcm merging at every vertex (one radius for all)
    vcm::MisFactors light_factors;  // what the light pass uses (below)

    // What merging needs at the first non-delta vertex of pixel i's camera subpaths. With merging
    // there only, the merging area eta enters a path's weights at that vertex alone, so each pixel
    // may have its own: its camera subpaths, and the light-tracing splats that land on it, use
    // that pixel's factors; the light subpaths carry dVM without 1 / eta^2 (light_factors: vc = 1)
    // and merging multiplies it in.
    struct PixelMerge {
        vcm::MisFactors factors;
        float merge_norm = 0, radius2 = 0;  // 1 / (pi r^2 N_light M), r^2
    };
    PixelMerge pixel(size_t i) const {
        if (!merge || merge_everywhere || !pixel_radius) return {factors, uniform_norm, radius * radius};
        const float r = (*pixel_radius)[i] * shrink;
        const float eta = kPi * r * r * light_paths * float(camera_samples);
        return {vcm::MisFactors::of(connect, true, eta), 1 / eta, r * r};
    }
    float uniform_norm = 0;  // 1 / (pi r^2 N_light) of `radius`
};

// Everything a camera subpath needs to evaluate its strategies.
struct Context {
    const Prepared& P;
    const Iteration& it;
    FixedFilm& film;
    std::span<const Vertex> light_path;              // this pixel's light subpath (connections)
    const std::vector<MergeVertex>* merge_vertices;  // the iteration's light vertices on surfaces
    const VertexGrid* grid;
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
    const Scattering s = vcm::evaluate(C.P, v, c.wi, shading::TransportMode::Importance);
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
    float w = C.it.lt ? 1.0f
                      : 1 / (1 + vcm::connect_side(mis, camera_pdf_a, s.pdf_rev * go_on_from(C.it, v),
                                                   v.mergeable, C.it.pixel(pixel).factors));
    w *= weight_roulette(C.it, w, sampler);
    if (w == 0) return;
    ++C.rays.shadow;
    const Rgb T = vcm::transmittance_to(C.P, v, c.lens, sampler);
    if (T.is_black()) return;
    const Rgb value = v.beta * s.f * T * (w * camera_pdf_a);
    C.film.add(pixel, value, part_at_first_vertex(v));
}

// One light sample at camera vertex `v` (s = 1) from the random numbers (u_light, u), weighted
// against the other strategies with the light sampling density scaled by `n`, the light samples
// taken at this vertex (multi-sample MIS, Veach 1997 sec. 9.2.2: the n samples together are one
// strategy of density n p).
Rgb direct_light_sample(const Context& C, const Vertex& v, float u_light, Vec2 u, float n, float n_mis,
                        float go_on, Sampler& sampler) {
    const Prepared& P = C.P;
    if (P.lights.size() == 0) return Rgb(0.0f);
    float pmf = 0;
    const size_t li = P.lights.choose(u_light, pmf);
    if (!(pmf > 0)) return Rgb(0.0f);
    const shading::Light& light = P.lights[li];
    const shading::LightLiSample ls = light.sample_Li(v.p, u);
    if (!(ls.pdf > 0) || ls.L.is_black()) return Rgb(0.0f);
    const Scattering s = vcm::evaluate(P, v, ls.wi, shading::TransportMode::Radiance);
    if (s.f.is_black()) return Rgb(0.0f);
    const bool at_infinity = !(ls.distance < kInf);
    const bool area = P.scene.lights[li].kind == scene::Light::Kind::Area;
    float pdf_pos = 0, pdf_dir = 0;
    light.pdf_Le(ls.n_light, -ls.wi, pdf_pos, pdf_dir);
    const float cos_light = area ? std::fabs(dot(ls.n_light, ls.wi)) : 1.0f;
    const float d2 = at_infinity ? 1.0f : ls.distance * ls.distance;
    // BSDF sampling competes with area and infinite lights only (vcm_mis.h: direct_density).
    const float direct_pdf_a = n_mis * vcm::direct_density(pmf, pdf_pos, pdf_dir, at_infinity);
    const float direct_pdf_w = ls.delta ? 0.0f : at_infinity ? direct_pdf_a : direct_pdf_a * d2 / cos_light;
    float w = vcm::direct_light_weight(v.mis, s.pdf_dir * go_on, s.pdf_rev, direct_pdf_a,
                                       pmf * pdf_pos * pdf_dir, direct_pdf_w,
                                       v.mergeable && C.it.merge_direct, s.cos / d2, C.merge_at.factors);
    w *= weight_roulette(C.it, w, sampler);
    if (w == 0) return Rgb(0.0f);
    ++C.rays.shadow;
    const Rgb T = vcm::transmittance_to(P, v, ls.p_light, sampler);
    if (T.is_black()) return Rgb(0.0f);
    return s.f * ls.L * T * (w * s.cos / (n * pmf * ls.pdf));
}

// Direct light sampling at camera vertex `v` (s = 1): at the camera subpath's first non-delta vertex
// (`first`: the first vertex, or the first one seen through mirrors and glass), C.it.direct_samples
// samples from the pixel's stratified sequences, as SPPM's visible points take them (each estimate
// also divided by the camera samples, which all take them); deeper, one independent sample.
// `go_on`: the probability of the camera subpath going on from v (below 1 only when first).
Rgb direct_light(const Context& C, const Vertex& v, bool first, float go_on, Sampler& sampler) {
    if (!first) {
        const float u_light = sampler.next();
        return direct_light_sample(C, v, u_light, sampler.next2(), 1.0f, 1.0f, 1.0f, sampler);
    }
    const int n = C.it.direct_samples;
    const float all = float(n * C.it.camera_samples);
    // A lone point-like light gives the same sample every time: one shadow ray stands for all n.
    if (C.it.one_delta_light)
        return direct_light_sample(C, v, 0.5f, Vec2(0.5f, 0.5f), all, C.it.direct_mis, go_on, sampler) *
               float(n);
    Rgb sum(0.0f);
    for (int k = 0; k < n; ++k) {
        const uint32_t i = C.sample * uint32_t(n) + uint32_t(k);
        sum += direct_light_sample(C, v, padded_point1(i, hash_combine(C.sequence_key, 3)),
                                   padded_point2(i, hash_combine(C.sequence_key, 4)), all, C.it.direct_mis,
                                   go_on, sampler);
    }
    return sum;
}

// Connections of camera vertex `v` (depth d) with every vertex of its light subpath (s, t >= 2);
// `go_on`: the probability of the camera subpath going on from v.
Rgb connect_light_path(const Context& C, const Vertex& v, float go_on, Sampler& sampler) {
    Rgb sum(0.0f);
    for (const Vertex& l : C.light_path) {
        if (l.length + v.length > C.P.options.max_depth) continue;
        Vec3 d = l.p - v.p;
        const float dist2 = dot(d, d);
        if (!(dist2 > 0)) continue;
        const float dist = std::sqrt(dist2);
        d = d / dist;
        const Scattering sc = vcm::evaluate(C.P, v, d, shading::TransportMode::Radiance);
        const Scattering sl = vcm::evaluate(C.P, l, -d, shading::TransportMode::Importance);
        if (sc.f.is_black() || sl.f.is_black()) continue;
        const float camera_pdf_a = go_on * sc.pdf_dir * sl.cos / dist2;  // v's BSDF reaching l
        const float light_pdf_a = sl.pdf_dir * sc.cos / dist2;           // l's BSDF reaching v
        float w =
            1 / (vcm::connect_side(l.mis, camera_pdf_a, sl.pdf_rev, l.mergeable && C.it.merge_everywhere,
                                   C.merge_at.factors) +
                 1 + vcm::connect_side(v.mis, light_pdf_a, sc.pdf_rev, v.mergeable, C.merge_at.factors));
        w *= weight_roulette(C.it, w, sampler);
        if (w == 0) continue;
        ++C.rays.shadow;
        const Rgb T = vcm::transmittance_between(C.P, v, l, sampler);
        if (T.is_black()) continue;
        sum += sc.f * sl.f * l.beta * T * (w * sc.cos * sl.cos / dist2);
    }
    return sum;
}

// Merging camera vertex `v` with the light vertices within the radius (vertex merging): the sum
// per Part of the light vertex (meaningful when v is the camera's first vertex). `first`: v is the
// camera subpath's first non-delta vertex; `go_on`: the probability of the camera subpath going on
// from v (below 1 only when first).
void merge(const Context& C, const Vertex& v, bool first, float go_on, Rgb sum[kParts]) {
    const int max_length = C.P.options.max_depth + 1 - v.length;
    const std::vector<MergeVertex>& lights = *C.merge_vertices;
    // A light vertex next to the light (merged only with merge_direct) completes a path whose
    // light-sampling strategy is at v, with its direct_samples samples when v is the first
    // non-delta vertex.
    const float direct_scale = first ? vcm::mis(C.it.direct_mis) : 1.0f;
    const auto add = [&](const MergeVertex& l, Rgb f, float pdf_dir, float pdf_rev) {
        float w = 1;
        if (!C.it.ppm) {
            SubpathMis lm = l.mis;
            if (l.length == 1) lm.dVCM *= direct_scale;
            if (C.it.pixel_radius) lm.dVM *= C.merge_at.factors.vc;  // the pixel's 1 / eta^2
            w = vcm::merge_weight(v.mis, lm, pdf_dir * go_on, pdf_rev, C.merge_at.factors);
        }
        sum[l.part] += f * l.beta * (w * C.merge_at.merge_norm);
    };
    const shading::Bsdf& b = *v.bsdf;
    if (b.is_lambertian()) {
        // Bsdf::eval and pdf of a lone Lambert lobe, written out: reflection on wo's side of ng
        // and of the shading normal, f = kd / pi, pdf = cos / pi.
        const Vec3 ng = b.geometric_normal(), ns = b.frame().n;
        const float side = dot(v.wo, ng) > 0 ? 1.0f : -1.0f;
        const float cos_o = dot(v.wo, ns) * side;
        const float pdf_rev = cos_o > 0 ? cos_o * kInvPi : 0.0f;
        const Rgb f = b.diffuse_albedo() * kInvPi;
        C.grid->query(v.p, C.merge_at.radius2, [&](uint32_t i, float) {
            const MergeVertex& l = lights[i];
            const float cos_i = dot(l.wo, ns) * side;
            if (l.length > max_length || !(dot(l.wo, ng) * side > 0) || !(cos_i > 0)) return;
            add(l, f, cos_i * kInvPi, pdf_rev);
        });
        return;
    }
    C.grid->query(v.p, C.merge_at.radius2, [&](uint32_t i, float) {
        const MergeVertex& l = lights[i];
        if (l.length > max_length) return;
        const Scattering s = vcm::evaluate(C.P, v, l.wo, shading::TransportMode::Radiance);
        if (!s.f.is_black()) add(l, s.f, s.pdf_dir, s.pdf_rev);
    });
}

// The emitter the camera subpath hit (s = 0): area light `li` at a point with normal n, seen along wo.
// `after_first`: the vertex before the emitter was the camera subpath's first non-delta one, whose
// light-sampling strategy took C.it.direct_samples samples.
float emitter_weight(const Context& C, const SubpathMis& camera, size_t li, Vec3 n, Vec3 wo, bool at_infinity,
                     bool after_first) {
    float pdf_pos = 0, pdf_dir = 0;
    C.P.lights[li].pdf_Le(n, wo, pdf_pos, pdf_dir);
    const float pmf = C.P.lights.pmf(li);
    const float samples = after_first ? C.it.direct_mis : 1.0f;
    return vcm::emitter_hit_weight(camera, samples * vcm::direct_density(pmf, pdf_pos, pdf_dir, at_infinity),
                                   pmf * pdf_pos * pdf_dir, C.it.merge_direct);
}

// One camera subpath through film position (fx, fy) with every strategy of the iteration: adds its
// estimate for the pixel to C.parts (light tracing adds to other pixels itself). Without `full`
// (the pixel's extra camera samples, Iteration::camera_samples) it ends after its first non-delta
// vertex's light samples and merging, without connections. What the camera subpath finds up to
// that vertex counts 1 / camera_samples (every camera sample finds it).
void camera_path(const Context& C, float fx, float fy, Vec2 lens, Sampler& sampler, bool full) {
    const Prepared& P = C.P;
    const scene::Scene& scene = P.scene;
    const Ray first = P.camera.generate_ray(fx, fy, lens);
    ++C.rays.camera;
    Ray ray = first;
    const float camera_pdf = P.camera.direction_pdf(normalize(first.dir));
    SubpathMis mis = camera_pdf > 0 ? vcm::start_camera(camera_pdf) : SubpathMis{};
    Rgb beta(1.0f);
    bool specular_chain = true;  // only delta bounces so far: the camera sees what it meets directly
    // The previous vertex was the first non-delta one (its light samples: direct_light's `first`).
    bool after_first = false;
    // For --layers: whether x1 (the first vertex) was a delta bounce, and whether every vertex
    // after x1 so far was.
    bool x1_delta = false, delta_after_x1 = true;
    // The Part of light found (emission) or sampled at the vertex reached at `depth`.
    const auto found_part = [&](int depth) {
        if (depth == 1) return kDirect;
        if (x1_delta) return kSpecular;
        if (depth == 2) return kDirect;
        return delta_after_x1 ? kCaustic : kIndirect;
    };
    const auto sampled_part = [&](int depth) {
        return depth == 1 ? kDirect : x1_delta ? kSpecular : kIndirect;
    };
    Rgb* const parts = C.parts;
    const float prefix_scale = 1 / float(C.it.camera_samples);
    const shading::MediaSet* media = P.active_media();
    shading::SurfaceWalk walk(P.accel, media, P.camera_medium());
    Vec3 from = first.origin;
    for (int depth = 1;; ++depth) {
        accel::SurfaceHit hit;
        Rgb emitted(0.0f);
        const auto event = media ? walk.next(ray, hit, sampler, beta, emitted) : walk.next(ray, hit);
        // Found up to the first non-delta vertex: by every camera sample of the pixel.
        const float found_scale = specular_chain ? prefix_scale : 1.0f;
        // Media's own emission: only camera subpaths find it.
        parts[found_part(depth)] += emitted * found_scale;
        if (event == shading::SurfaceWalk::Event::Escaped) {
            const Vec3 dir = normalize(ray.dir);
            if (specular_chain || P.options.background_light)
                parts[found_part(depth)] += beta * scene.background * found_scale;
            if (C.it.ppm && !specular_chain) break;
            for (size_t i : P.lights.infinite_lights()) {
                const Rgb Le = P.lights[i].Le(Vec3(0.0f), dir);
                if (Le.is_black()) continue;
                const float w = depth == 1 ? 1.0f : emitter_weight(C, mis, i, {}, -dir, true, after_first);
                parts[found_part(depth)] += beta * Le * (w * found_scale);
            }
            break;
        }
        if (event != shading::SurfaceWalk::Event::Surface && event != shading::SurfaceWalk::Event::Medium)
            break;
        Vertex v = vcm::reach_vertex(P, event, walk, ray, hit, depth, beta);
        vcm::arrive(mis, length(v.p - from), vcm::cos_at(v, v.wo), true);
        v.mis = mis;
        if (!v.in_medium) {
            // s = 0: the surface's own emission, and the .scn glow on the camera's specular chain.
            const Rgb Le = P.emitted(hit, v.wo);
            if (!Le.is_black() && (!C.it.ppm || specular_chain)) {
                const float w = depth == 1 || C.it.ppm ? 1.0f
                                                       : emitter_weight(C, mis, size_t(hit.area_light),
                                                                        hit.ng, v.wo, false, after_first);
                parts[found_part(depth)] += beta * Le * (w * found_scale);
            }
            if (specular_chain) {
                const scene::Material& mat = scene.materials[size_t(hit.material)];
                parts[found_part(depth)] += beta * mat.emission * found_scale;
                if (P.options.ambient)
                    parts[found_part(depth)] += beta * mat.ambient * scene.ambient * found_scale;
            }
        }
        if (depth > P.options.max_depth || C.it.lt) break;
        const bool smooth = v.in_medium || v.bsdf->has_non_specular();
        // Merging here: at every vertex, or only at the first non-delta one.
        v.mergeable = C.it.merge && !v.in_medium && smooth && (C.it.merge_everywhere || specular_chain);
        // The probability of going on past this vertex: below 1 only at x_f (go_on_from).
        const float go_on = specular_chain && smooth ? go_on_from(C.it, v) : 1.0f;
        if (smooth) {
            if (C.it.connect) {
                parts[sampled_part(depth)] += beta * direct_light(C, v, specular_chain, go_on, sampler);
                if (full && !C.light_path.empty())
                    parts[x1_delta ? kSpecular : kIndirect] +=
                        beta * connect_light_path(C, v, go_on, sampler);
            }
            if (v.mergeable) {
                Rgb merged[kParts] = {Rgb(0.0f), Rgb(0.0f), Rgb(0.0f), Rgb(0.0f)};
                merge(C, v, specular_chain, go_on, merged);
                for (int k = 0; k < kParts; ++k)
                    parts[depth == 1 ? k : x1_delta ? kSpecular : kIndirect] += beta * merged[k];
                if (C.it.ppm) break;  // ppm: the first non-delta camera vertex gathers everything
            }
            if (!full && specular_chain) break;  // an extra camera sample: its x_f is done
        }

        // Continue the camera subpath (radiance transport): past x_f with probability go_on.
        if (go_on < 1) {
            if (!(sampler.next() < go_on)) break;
            beta *= 1 / go_on;
        }
        Vec3 wi;
        bool delta = false;
        if (!vcm::continue_from(P, v, shading::TransportMode::Radiance, C.merge_at.factors, v.mergeable,
                                sampler, mis, beta, wi, delta, go_on))
            break;
        after_first = specular_chain && smooth;  // (a delta lobe sampled here zeroes dVCM anyway)
        specular_chain = specular_chain && delta;
        if (depth == 1)
            x1_delta = delta;
        else
            delta_after_x1 = delta_after_x1 && delta;
        ++C.rays.bounce;
        if (!vcm::survives(depth, beta, Rgb(1.0f), sampler)) break;
        from = v.p;
        ray = vcm::leave_vertex(v, wi, walk);
    }
}

// The merging radius of the first iteration: --radius, else --radius-pixels pixel footprints at
// the distance from the camera to the scene's centre.
float base_radius(const Prepared& P, const ProgressiveOptions& o) {
    if (o.radius > 0) return o.radius;
    const Bounds b = P.accel.bounds();
    const float d = b.empty() ? 1.0f : length(b.center() - P.camera.eye());
    const float r = o.radius_pixels * P.camera.pixel_footprint().at(d);
    return r > 0 ? r : 1e-3f * (b.empty() ? 1.0f : length(b.extent()));
}

std::string two_decimals(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

// A pilot light pass (vcm, before the first iteration; its own random numbers, the same on every
// rank, not part of the image): appends the mergeable vertices of light subpaths [first, end) to
// `points`, in subpath order.
void pilot_light_vertices(const Prepared& P, size_t first, size_t end, int merge_from,
                          std::vector<Vec3>& points) {
    const RenderOptions& ro = P.options;
    constexpr size_t kBatch = 4096;
    std::vector<std::vector<Vec3>> batches((end - first + kBatch - 1) / kBatch);
    tbb::parallel_for(size_t(0), batches.size(), [&](size_t b) {
        RayCounts rays;
        std::vector<Vertex> traced;
        for (size_t i = first + b * kBatch; i < std::min(end, first + (b + 1) * kBatch); ++i) {
            Sampler sampler(ro.seed, 0x7663706c6f74ULL, i);
            traced.clear();
            vcm::trace_light_path(P, sampler, std::max(1, ro.max_depth), vcm::MisFactors{}, merge_from, false,
                                  traced, rays);
            for (const Vertex& v : traced)
                if (v.mergeable) batches[b].push_back(v.p);
        }
        P.stats.add_rays(rays);
    });
    for (const std::vector<Vec3>& batch : batches) points.insert(points.end(), batch.begin(), batch.end());
}

// Light subpaths per pixel and iteration for merging (--vcm-light-paths, automatic when 0): where
// few light subpaths reach a surface that can merge (a point light over an open floor: most
// leave the scene or end on a mirror or glass), more of them per iteration keep the merging
// estimate's density up at little cost, those subpaths being short. Automatic: enough subpaths
// for kMergeablePerPixel mergeable vertices per pixel, from the pilot's `mergeable_per_path`,
// between 2 and 8. On the bench scenes: 2 on the Cornell boxes (2.0 and 1.65 per subpath; 3 and 4
// were worse at equal time), 8 on caustic-point (under 0.01 per subpath: its point light's
// subpaths mostly leave the open scene; 8 gave 0.00107 against 2's 0.00197, docs/bidirectional.md).
constexpr double kMergeablePerPixel = 3;
int light_paths_per_pixel(const ProgressiveOptions& o, double mergeable_per_path) {
    if (o.vcm_light_paths > 0) return o.vcm_light_paths;
    if (!(mergeable_per_path > 0)) return 2;
    return int(std::clamp(std::ceil(kMergeablePerPixel / mergeable_per_path), 2.0, 8.0));
}

// The first merging radius of each pixel (merging at the first non-delta camera vertex), from the
// point a camera ray through the pixel's centre finds first on a non-delta surface (its own random
// numbers, the same on every rank), as SPPM chooses its radii after its pilot (sppm.cpp):
//  - --radius if given; else `base` (--radius-pixels footprints at the scene's centre) scaled to
//    the density of light vertices: the pilot's mergeable vertices `pilot` (of as many light
//    subpaths as an iteration has; null: no such scaling) in the base disc count m, and the radius becomes
//    base sqrt(--radius-photons / m), at least one pixel footprint (a sharp caustic keeps its
//    edge) and at most base (radii up to twice base where light is sparse biased the point-light
//    caustic's window by 20 % at 128 x 128);
//  - with --edge-aware-radius, bounded at geometric edges as SPPM's (sppm_core.h: a disc reaching
//    across a corner, a contact or a light's rim averages light vertices from another surface or
//    a shadowed strip, and the kernel's bias gathers there).
// The grid's cells are sized by `base`, the largest radius. Pixels whose ray finds no such surface
// take `base`.
std::vector<float> pixel_radii(const Prepared& P, const ProgressiveOptions& o, float base,
                               const std::vector<Vec3>* pilot) {
    const RenderOptions& ro = P.options;
    const size_t pixels = size_t(ro.width) * size_t(ro.height);
    const CameraModel::Footprint footprint = P.camera.pixel_footprint();
    std::vector<Vec3> p(pixels), n(pixels);
    std::vector<double> r2(pixels, 0.0), r2_min(pixels, 0.0);
    tbb::parallel_for(0, ro.height, [&](int y) {
        RayCounts rays;
        for (int x = 0; x < ro.width; ++x) {
            const size_t i = size_t(y) * size_t(ro.width) + size_t(x);
            Sampler sampler(ro.seed, 0x7663706966ULL, i);
            sppm::VisiblePoint vp;
            const Ray ray = P.camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f, Vec2(0.5f, 0.5f));
            ++rays.camera;
            sppm::trace_eye_path(P, ray, sampler, 0, vp, rays);
            if (!vp.bsdf) continue;
            p[i] = vp.p;
            n[i] = vp.bsdf->geometric_normal();
            r2[i] = double(base) * double(base);
            const double r_min =
                std::min(double(base), kPilotRadiusMinPixels * double(footprint.at(vp.path_length)));
            r2_min[i] = r_min * r_min;
        }
        P.stats.add_rays(rays);
    });
    if (pilot) {
        VertexGrid grid;
        grid.build(*pilot, base);
        tbb::parallel_for(size_t(0), pixels, [&](size_t i) {
            if (!(r2[i] > 0)) return;
            uint64_t m = 0;
            grid.query(p[i], [&](uint32_t, float) { ++m; });
            if (double(m) > o.radius_photons)
                r2[i] = std::max(r2_min[i], r2[i] * o.radius_photons / double(m));
        });
    }
    if (o.edge_aware_radius) sppm::bound_radii_at_edges(p, n, r2, r2_min);
    std::vector<float> r(pixels);
    for (size_t i = 0; i < pixels; ++i) r[i] = r2[i] > 0 ? float(std::sqrt(r2[i])) : base;
    return r;
}

}  // namespace

RenderDone VcmIntegrator::render(const Prepared& P, film::Film& film, Progress& progress) {
    const RenderOptions& ro = P.options;
    const std::string name = bdpt_ ? "bdpt" : "vcm";
    const size_t pixels = size_t(ro.width) * size_t(ro.height);
    ProgressiveState state = start_state(ro, budget_, name, 0, "iterations", uint64_t(std::max(1, ro.spp)));
    FixedFilm sums(pixels, ro.layers);  // this rank's image sums (all of them without MPI)
    std::vector<int64_t> total;         // under MPI: every rank's sums added up
    if (!state.payload.empty()) {
        ByteReader r(state.payload, "checkpoint '" + budget_.settings.resume_path + "': " + name + " sums");
        const std::vector<int64_t> v = r.get_vector<int64_t>();
        if (v.size() != pixels * 3 * sums.planes() || !r.at_end()) r.fail("size does not match the image");
        if (dist::root()) sums.set(v);
        if (dist::distributed()) total = v;
    }

    const VcmMode mode = bdpt_ ? VcmMode::Bpt : opt_.vcm_mode;
    Iteration it;
    it.lt = mode == VcmMode::Lt;
    it.connect = mode == VcmMode::Bpt || mode == VcmMode::Vcm;
    it.merge = mode == VcmMode::Ppm || mode == VcmMode::Vcm;
    it.ppm = mode == VcmMode::Ppm;
    it.merge_direct = it.ppm;
    it.direct_samples = bidirectional_direct_samples(opt_);
    it.merge_everywhere = opt_.vcm_merge == VcmMerge::Every;
    it.camera_samples = it.merge && !it.merge_everywhere ? opt_.vcm_camera_samples : 1;
    it.go_on = it.merge && !it.merge_everywhere ? opt_.vcm_continue : 1.0f;
    it.direct_mis = float(it.direct_samples) * opt_.direct_mis_scale * float(it.camera_samples);
    it.one_delta_light = P.lights.size() == 1 && P.lights[0].is_delta();
    it.rr_weight = it.lt ? 0.0f : opt_.vcm_rr_weight;

    const int merge_from = !it.merge ? 0 : it.merge_direct ? 1 : 2;  // light subpath vertices merged
    // Light subpaths per iteration: one per pixel for connections and light tracing, and K per
    // pixel for merging (eta counts them all), K from the pilot light pass when automatic.
    // (The pilot: for the automatic count, and for the per-pixel radii below.)
    const bool radii_from_pilot = opt_.radius_photons > 0 && !(opt_.radius > 0);
    std::vector<Vec3> pilot;
    if (it.merge && (opt_.vcm_light_paths == 0 || (!it.merge_everywhere && radii_from_pilot)))
        pilot_light_vertices(P, 0, pixels, merge_from, pilot);
    const double mergeable_per_path = double(pilot.size()) / double(pixels);
    const int per_pixel = bdpt_ || !it.merge ? 1 : light_paths_per_pixel(opt_, mergeable_per_path);
    const size_t light_paths = pixels * size_t(per_pixel);
    it.light_paths = float(light_paths);
    const float r0 = it.merge ? base_radius(P, opt_) : 0.0f;
    // Merging at the first non-delta vertex: each pixel's own first radius (pixel_radii).
    std::vector<float> pixel_radius;
    if (it.merge && !it.merge_everywhere) {
        // The pilot grows to an iteration's light subpaths, whose density the radii are set for.
        if (radii_from_pilot) pilot_light_vertices(P, pixels, light_paths, merge_from, pilot);
        pixel_radius = pixel_radii(P, opt_, r0, radii_from_pilot ? &pilot : nullptr);
        it.pixel_radius = &pixel_radius;
    }
    pilot = {};
    const int max_depth = std::max(1, ro.max_depth);
    const auto tiles = film::make_tiles(ro.width, ro.height);
    std::vector<uint8_t> owned_pixel(pixels, 0);  // under MPI: the pixels of this rank's tiles
    for (size_t t = 0; t < tiles.size(); ++t)
        if (dist::owns(t))
            for (int y = tiles[t].y0; y < tiles[t].y1; ++y)
                for (int x = tiles[t].x0; x < tiles[t].x1; ++x)
                    owned_pixel[size_t(y) * size_t(ro.width) + size_t(x)] = 1;
    // vcm: the iteration's light subpaths, kept from one iteration to the next (no allocation per
    // iteration). Batch b holds subpaths [b kLightBatch, (b + 1) kLightBatch): the vertices of
    // those below `pixels` (subpath i's are light_batches[i / kLightBatch][path_begin[i] ..
    // path_end[i])) and the mergeable vertices of all.
    constexpr size_t kLightBatch = 4096;
    const size_t light_batch_count = bdpt_ ? 0 : (light_paths + kLightBatch - 1) / kLightBatch;
    std::vector<std::vector<vcm::VertexCore>> light_batches(light_batch_count);
    std::vector<std::vector<MergeVertex>> merge_batches(light_batch_count);
    std::vector<uint32_t> path_begin(bdpt_ ? 0 : pixels), path_end(bdpt_ ? 0 : pixels);
    std::vector<MergeVertex> all_mergeable;   // under MPI: every rank's, in light subpath order
    std::vector<Vec3> merge_points;           // their positions, for the grid
    std::vector<MergeVertex> merge_vertices;  // in the grid's order
    VertexGrid grid;

    // Pixel = sum / iterations, for the image and each layer.
    const auto resolve_film = [&] {
        const std::vector<int64_t> local = total.empty() ? sums.values() : std::vector<int64_t>{};
        const std::vector<int64_t>& v = total.empty() ? local : total;
        const double scale = state.iterations > 0 ? 1 / (kFixedScale * double(state.iterations)) : 0;
        const auto mean = [&](size_t plane, size_t i) {
            Rgb r;
            for (int c = 0; c < 3; ++c) r[c] = float(double(v[(plane * pixels + i) * 3 + size_t(c)]) * scale);
            return r;
        };
        for (int y = 0; y < ro.height; ++y)
            for (int x = 0; x < ro.width; ++x) {
                const size_t i = size_t(y) * size_t(ro.width) + size_t(x);
                film.set_pixel(x, y, mean(0, i));
                if (sums.layers())
                    for (int k = 0; k < kParts; ++k)
                        film.layer(kPartNames[k]).set(x, y, mean(1 + size_t(k), i));
            }
    };
    RenderBudget budget = budget_;
    budget.observers.on_checkpoint = [&](const ProgressiveState& s) {
        if (!budget_.observers.on_checkpoint) return;
        ProgressiveState saved = s;
        ByteWriter w(saved.payload);
        w.put_vector(total.empty() ? sums.values() : total);
        budget_.observers.on_checkpoint(saved);
    };

    ProgressiveBudget loop(ro, budget, state, film, progress);
    while (loop.next()) {
        const uint64_t iteration = state.iterations;
        if (it.merge) {
            // Radius reduction (Knaus & Zwicker 2011): r_i = r_1 i^((alpha - 1) / 2), per pixel.
            it.shrink = float(std::pow(double(iteration + 1), 0.5 * (double(opt_.alpha) - 1)));
            it.radius = r0 * it.shrink;  // r0: the largest per-pixel radius
            const float eta = kPi * it.radius * it.radius * it.light_paths;
            it.factors = vcm::MisFactors::of(it.connect, true, eta);
            it.uniform_norm = 1 / eta;
            // With per-pixel merging areas the light subpaths carry dVM without 1 / eta^2.
            const bool per_pixel = it.pixel_radius != nullptr;
            it.light_factors = per_pixel ? vcm::MisFactors{0, it.connect ? 1.0f : 0.0f} : it.factors;
        } else {
            it.factors = it.light_factors = vcm::MisFactors::of(true, false, 0);
        }
        // Light pass (vcm): the iteration's light subpaths, in batches of consecutive subpaths; each
        // rank traces those of its own pixels (light subpath j belongs to pixel j mod pixels).
        // Subpaths j < pixels keep their vertices for the connections and light tracing of pixel
        // j; every subpath adds its mergeable vertices to the batch's merge list, in order.
        if (!bdpt_) {
            tbb::parallel_for(size_t(0), light_batches.size(), [&](size_t b) {
                RayCounts rays;
                std::vector<Vertex> traced;
                std::vector<vcm::VertexCore>& kept = light_batches[b];
                std::vector<MergeVertex>& mergeable = merge_batches[b];
                kept.clear();
                mergeable.clear();
                for (size_t i = b * kLightBatch; i < std::min(light_paths, (b + 1) * kLightBatch); ++i) {
                    if (i < pixels) path_begin[i] = uint32_t(kept.size());
                    if (owned_pixel[i % pixels]) {
                        Sampler sampler(ro.seed, 0x6c69676874ULL, i, iteration);
                        traced.clear();
                        vcm::trace_light_path(P, sampler, max_depth, it.light_factors, merge_from,
                                              it.merge_everywhere, traced, rays);
                        for (const Vertex& v : traced) {
                            if (i < pixels) kept.push_back(v);  // without the BSDF
                            if (v.mergeable)
                                mergeable.push_back({v.p, v.wo, v.beta, v.mis, v.length,
                                                     part_at_first_vertex(v), uint32_t(i)});
                        }
                    }
                    if (i < pixels) path_end[i] = uint32_t(kept.size());
                }
                P.stats.add_rays(rays);
            });
            if (it.merge) {
                // The mergeable vertices (surfaces only; see merge_direct) of every rank, in light
                // subpath order, then indexed by the grid and stored in its order (a bucket's
                // vertices side by side).
                std::vector<size_t> offset(merge_batches.size() + 1, 0);
                for (size_t b = 0; b < merge_batches.size(); ++b)
                    offset[b + 1] = offset[b] + merge_batches[b].size();
                if (dist::distributed()) {
                    all_mergeable.resize(offset.back());
                    tbb::parallel_for(size_t(0), merge_batches.size(), [&](size_t b) {
                        std::copy(merge_batches[b].begin(), merge_batches[b].end(),
                                  all_mergeable.begin() + std::ptrdiff_t(offset[b]));
                    });
                    all_mergeable = dist::all_gather(std::span<const MergeVertex>(all_mergeable));
                    std::stable_sort(
                        all_mergeable.begin(), all_mergeable.end(),
                        [](const MergeVertex& a, const MergeVertex& b) { return a.path < b.path; });
                }
                // Mergeable vertex k of the iteration: from the gathered list, or (one process) in
                // place in its batch.
                const size_t count = dist::distributed() ? all_mergeable.size() : offset.back();
                const auto mergeable_vertex = [&](size_t k) -> const MergeVertex& {
                    if (dist::distributed()) return all_mergeable[k];
                    const size_t b =
                        size_t(std::upper_bound(offset.begin(), offset.end(), k) - offset.begin()) - 1;
                    return merge_batches[b][k - offset[b]];
                };
                merge_points.resize(count);
                tbb::parallel_for(size_t(0), count,
                                  [&](size_t k) { merge_points[k] = mergeable_vertex(k).p; });
                grid.build(merge_points, it.radius);
                merge_vertices.resize(count);
                const std::vector<uint32_t>& order = grid.order();
                tbb::parallel_for(size_t(0), order.size(),
                                  [&](size_t k) { merge_vertices[k] = mergeable_vertex(order[k]); });
            }
        }
        // Camera pass, tile by tile: each pixel's camera subpath with its light subpath.
        tbb::parallel_for(size_t(0), tiles.size(), [&](size_t t) {
            if (!dist::owns(t)) return;
            const film::Tile& tile = tiles[t];
            RayCounts rays;
            std::vector<Vertex> own;  // the pixel's light subpath, with its BSDFs
            for (int y = tile.y0; y < tile.y1; ++y)
                for (int x = tile.x0; x < tile.x1; ++x) {
                    const size_t i = size_t(y) * size_t(ro.width) + size_t(x);
                    std::span<const Vertex> light;
                    if (bdpt_) {
                        own.clear();
                        Sampler ls(ro.seed, 0x6c69676874ULL, i, iteration);
                        vcm::trace_light_path(P, ls, max_depth, it.factors, 0, false, own, rays);
                        light = own;
                    } else if (it.connect || it.lt) {
                        own.clear();
                        const std::vector<vcm::VertexCore>& batch = light_batches[i / kLightBatch];
                        for (uint32_t k = path_begin[i]; k < path_end[i]; ++k)
                            own.push_back(vcm::with_bsdf(P, batch[k]));
                        light = own;
                    }
                    Rgb parts[kParts] = {Rgb(0.0f), Rgb(0.0f), Rgb(0.0f), Rgb(0.0f)};
                    // The pixel's stratified sequences: point `iteration` gives the position in the
                    // pixel and on the lens, as in SPPM; the rest is independent random.
                    const uint64_t key = Sampler(ro.seed, 0x7663707365717563ULL, i).next_bits();
                    const uint32_t first_sample = uint32_t(iteration) * uint32_t(it.camera_samples);
                    Context C{P,    it,    sums, light,        &merge_vertices, &grid,
                              rays, parts, key,  first_sample, it.pixel(i)};
                    Sampler sampler(ro.seed, 0x766370657965ULL, i, iteration);
                    if (it.connect || it.lt)  // light tracing
                        for (const Vertex& v : light) connect_to_camera(C, v, sampler);
                    // Camera sample j: point iteration x camera_samples + j of the pixel's sequences;
                    // the first (with the light-tracing sampler) takes every strategy, the others
                    // (each its own sampler) stop after x_f.
                    const auto camera_sample = [&](int j, Sampler& s) {
                        C.sample = first_sample + uint32_t(j);
                        const Vec2 jitter = padded_point2(C.sample, hash_combine(key, 1));
                        const Vec2 lens = padded_point2(C.sample, hash_combine(key, 2));
                        camera_path(C, float(x) + jitter.x, float(y) + jitter.y, lens, s, j == 0);
                    };
                    camera_sample(0, sampler);
                    for (int j = 1; j < it.camera_samples; ++j) {
                        Sampler extra(ro.seed, hash_combine(0x7663706578ULL, uint64_t(j)), i, iteration);
                        camera_sample(j, extra);
                    }
                    for (int k = 0; k < kParts; ++k) sums.add(i, parts[k], Part(k));
                }
            P.stats.add_rays(rays);
        });
        if (dist::distributed()) {
            total = sums.values();
            dist::sum(total.data(), total.size());
        }
        loop.after_iteration(resolve_film);
    }
    resolve_film();
    const RenderDone done = loop.finish();
    P.stats.add_dropped_samples(sums.rejected());
    std::string merging;
    if (it.merge) {
        merging = ", " + std::to_string(per_pixel) + " light subpaths per pixel";
        if (opt_.vcm_light_paths == 0)
            merging += " (pilot: " + two_decimals(mergeable_per_path) + " mergeable vertices per subpath)";
        if (it.camera_samples > 1) merging += ", " + std::to_string(it.camera_samples) + " camera samples";
        merging += ", largest radius " + std::to_string(it.radius);
    }
    P.stats.add_value(name, std::to_string(state.iterations) + " iterations" + merging);
    return done;
}

}  // namespace phos::integrators
