// The beam radiance estimate and the photon radii it uses (see beam_estimate.h).
#include "photon/beam_estimate.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace phos::photon {

std::vector<PhotonSphere> photon_spheres(const PhotonKdTree& map, uint32_t k, float max_radius,
                                         const accel::EmbreeScene* surfaces) {
    std::vector<PhotonSphere> out(map.size());
    if (map.empty()) return out;
    k = std::max(k, 1u);
    const float r_min = 1e-3f * max_radius;
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, map.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
            thread_local std::vector<Neighbour> nb;
            nb.resize(k);
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const Photon& p = map.photon(uint32_t(i));
                const KnnResult kr = map.knn(p.position, k, max_radius * max_radius, nb.data());
                const float radius = std::max(kr.count < k ? max_radius : std::sqrt(kr.max_dist2), r_min);
                const float open = surfaces ? open_ball_fraction(*surfaces, p.position, radius) : 1.0f;
                out[i] = {p.position, radius, p.colour() * (1 / open), p.wi()};
            }
        });
    return out;
}

Rgb beam_radiance_estimate(const BeamBvh& map, Vec3 o, Vec3 d, const StretchTransmittance& T,
                           const shading::PhaseFunction& phase, uint32_t* n_used) {
    // L_b = sum_p p(wo, wi_p) Phi_p / (4/3 pi r_p^3) int_{t0_p}^{t1_p} T(t) dt   (beam_estimate.h)
    const Vec3 wo = -d;
    const std::span<const PhotonSphere> s = map.spheres();
    Rgb sum(0.0f);
    uint32_t n = 0;
    map.for_each_hit(o, d, T.end(), [&](uint32_t i, const SphereHit& hit) {
        const PhotonSphere& p = s[i];
        const float w = phase.eval(wo, p.wi) / (4.0f / 3.0f * kPi * p.radius * p.radius * p.radius);
        sum += p.power * T.integral(hit.t0, hit.t1) * w;
        ++n;
    });
    if (n_used) *n_used = n;
    return sum;
}

}  // namespace phos::photon
