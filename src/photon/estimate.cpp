// Photon density estimates (see estimate.h).
#include "photon/estimate.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "spectrum/color.h"

namespace phos::photon {
namespace {

// Per-thread neighbour buffer: estimates run inside the parallel pixel loop and must not allocate.
Neighbour* scratch(uint32_t k) {
    thread_local std::vector<Neighbour> buf;
    if (buf.size() < k) buf.resize(k);
    return buf.data();
}

// Runs the kNN query with the surface test and calls g(photon, weight) for every accepted photon,
// weight including the filter and the 1 / (mean_w pi r^2) normalisation; `r2` receives the squared
// radius of the disc used (the search radius when nothing was found).
template <class G>
uint32_t gather(const PhotonKdTree& map, const EstimateOptions& o, const SurfaceQuery& q, float& r2_used,
                G&& g) {
    r2_used = o.max_radius * o.max_radius;
    if (map.empty() || o.k == 0) return 0;
    Neighbour* nb = scratch(o.k);
    const float max_r2 = o.max_radius * o.max_radius;
    const KnnResult r =
        map.knn_if(q.p, o.k, max_r2, nb, [&](const Photon& ph) { return accept_photon(ph, q, o); });
    if (r.count == 0) return 0;
    // With fewer than k photons the search covered the whole max-radius disk; using the farthest
    // photon's distance instead would overestimate sparse regions (one photon very close -> huge).
    const float r2 = r.count < o.k ? max_r2 : r.max_dist2;
    const float min_r2 = std::min(q.min_radius * q.min_radius, max_r2);
    if (r.count == o.k && r2 < min_r2) {
        // Dense region: every accepted photon within the minimum radius instead of the k nearest.
        const float norm = 1.0f / (o.filter.mean_weight() * kPi * min_r2);
        r2_used = min_r2;
        uint32_t n = 0;
        map.for_each_in_radius(q.p, min_r2, [&](uint32_t i, float d2) {
            const Photon& ph = map.photon(i);
            if (!accept_photon(ph, q, o)) return;
            g(ph, o.filter.weight(d2, min_r2) * norm);
            ++n;
        });
        return n;
    }
    if (!(r2 > 0)) return 0;
    r2_used = r2;
    const float norm = 1.0f / (o.filter.mean_weight() * kPi * r2);
    const bool box = o.filter.kind == FilterKind::Box;
    for (uint32_t i = 0; i < r.count; ++i) {
        const float w = box ? norm : o.filter.weight(nb[i].dist2, r2) * norm;
        g(map.photon(nb[i].index), w);
    }
    return r.count;
}

}  // namespace

SurfaceQuery make_query(Vec3 p, Vec3 ng, Vec3 wo, const shading::Bsdf& bsdf) {
    SurfaceQuery q;
    q.p = p;
    q.n = dot(ng, wo) >= 0 ? ng : -ng;
    // Lambertian transmission (and frosted glass) receive light through the surface.
    const uint32_t f = bsdf.flags();
    q.accept_back = (f & shading::kTransmission) && (f & (shading::kDiffuse | shading::kGlossy));
    return q;
}

bool accept_photon(const Photon& ph, const SurfaceQuery& q, const EstimateOptions& o) {
    if (ph.has_normal()) {
        const float c = dot(ph.normal(), q.n);
        if (!(c >= o.normal_cos || (q.accept_back && -c >= o.normal_cos))) return false;
    }
    if (o.flatness > 0) {
        const Vec3 d = ph.position - q.p;
        const float h = dot(d, q.n);
        if (h * h > o.flatness * o.flatness * length_squared(d)) return false;
    }
    return true;
}

Rgb radiance_estimate(const PhotonKdTree& map, const EstimateOptions& o, const SurfaceQuery& q, Vec3 wo,
                      const shading::Bsdf& bsdf, uint32_t* n_used, float* radius_used) {
    Rgb sum(0.0f);
    uint32_t n;
    float r2;
    // Each photon's power meets the BSDF at the photon's own wavelengths, and the product goes to
    // colour there.
    if (bsdf.is_lambertian()) {
        // Lambert only: f = kd / pi for every photon on wo's side, which the normal test ensures.
        const spectrum::RgbSpectrum& kd = bsdf.diffuse_spectrum();
        n = gather(map, o, q, r2, [&](const Photon& ph, float w) {
            const Wavelengths lambda = ph.wavelengths();
            sum += spectrum::to_srgb(kd.sample(lambda) * ph.power(), lambda) * w;
        });
        sum *= kInvPi;
    } else {
        n = gather(map, o, q, r2, [&](const Photon& ph, float w) {
            const Wavelengths lambda = ph.wavelengths();
            sum += spectrum::to_srgb(bsdf.eval(wo, ph.wi(), lambda) * ph.power(), lambda) * w;
        });
    }
    if (n_used) *n_used = n;
    if (radius_used) *radius_used = std::sqrt(r2);
    return sum;
}

Rgb irradiance_estimate(const PhotonKdTree& map, const EstimateOptions& o, const SurfaceQuery& q,
                        uint32_t* n_used) {
    Rgb sum(0.0f);
    float r2;
    const uint32_t n = gather(map, o, q, r2, [&](const Photon& ph, float w) { sum += ph.colour() * w; });
    if (n_used) *n_used = n;
    return sum;
}

}  // namespace phos::photon
