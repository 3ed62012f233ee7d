// vcm's pilot: light subpaths per pixel and the pixels' first merging radii (see vcm_pilot.h).
#include "integrators/vcm_pilot.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "integrators/eye_path.h"
#include "integrators/pilot_radius.h"

namespace phos::integrators::vcm {

namespace {

// The merging radius of the first iteration: --radius, else --radius-pixels pixel footprints at
// the distance from the camera to the scene's centre.
float base_radius(const Prepared& P, const ProgressiveOptions& o) {
    if (o.radius > 0) return o.radius;
    const Bounds b = P.accel.bounds();
    const float d = b.empty() ? 1.0f : length(b.center() - P.camera.eye());
    const float r = o.radius_pixels * P.camera.pixel_footprint().at(d);
    return r > 0 ? r : 1e-3f * (b.empty() ? 1.0f : length(b.extent()));
}

// A pilot light pass: appends the mergeable vertices of light subpaths [first, end) to `points`,
// in subpath order.
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
            trace_light_path(P, {std::max(1, ro.max_depth), MisFactors{}, merge_from, false}, sampler,
                             Wavelengths::visible(sampler.next()), traced, rays);
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
//  - with --edge-aware-radius, bounded at geometric edges as SPPM's (pilot_radius.h: a disc reaching
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
            VisiblePoint vp;
            float camera_weight = 1;
            const Ray ray =
                P.camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f, Vec2(0.5f, 0.5f), camera_weight);
            ++rays.camera;
            if (camera_weight == 0) continue;  // blocked by the camera's lenses: the pixel takes `base`
            trace_eye_path(P, ray, sampler, 0, vp, rays);
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
    if (o.edge_aware_radius) bound_radii_at_edges(p, n, r2, r2_min);
    std::vector<float> r(pixels);
    for (size_t i = 0; i < pixels; ++i) r[i] = r2[i] > 0 ? float(std::sqrt(r2[i])) : base;
    return r;
}

}  // namespace

MergingPlan plan_merging(const Prepared& P, const ProgressiveOptions& o, const Strategies& strategies) {
    MergingPlan plan;
    if (!strategies.merge) return plan;
    const size_t pixels = size_t(P.options.width) * size_t(P.options.height);
    plan.merge_from = strategies.merge_next_to_light() ? 1 : 2;
    // Light subpaths per iteration: one per pixel for connections and light tracing, and K per
    // pixel for merging (eta counts them all), K from the pilot light pass when automatic.
    const bool radii_from_pilot = o.radius_photons > 0 && !(o.radius > 0);
    std::vector<Vec3> pilot;
    if (o.vcm_light_paths == 0 || (!strategies.merge_everywhere && radii_from_pilot))
        pilot_light_vertices(P, 0, pixels, plan.merge_from, pilot);
    plan.mergeable_per_path = double(pilot.size()) / double(pixels);
    plan.light_paths_per_pixel = light_paths_per_pixel(o, plan.mergeable_per_path);
    plan.base_radius = base_radius(P, o);
    if (!strategies.merge_everywhere) {
        if (radii_from_pilot)
            pilot_light_vertices(P, pixels, pixels * size_t(plan.light_paths_per_pixel), plan.merge_from,
                                 pilot);
        plan.pixel_radius = pixel_radii(P, o, plan.base_radius, radii_from_pilot ? &pilot : nullptr);
    }
    return plan;
}

}  // namespace phos::integrators::vcm
