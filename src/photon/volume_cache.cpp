// Precomputed in-scattered light at volume photons (see volume_cache.h).
#include "photon/volume_cache.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <utility>

namespace phos::photon {

Rgb VolumeMoments::estimate(Vec3 wo, float g) const {
    Rgb e;
    for (int c = 0; c < 3; ++c)
        e[c] = std::max(0.0f, f0[c] - 3 * g * dot(wo, f1[size_t(c)])) * (1 / (4 * kPi));
    return e;
}

VolumeMoments volume_moments(const PhotonKdTree& map, const VolumeEstimateOptions& o, Vec3 x) {
    VolumeMoments m;
    const float inv_volume = volume_estimate_photons(map, o, x, [&](const Photon& ph) {
        const Rgb phi = ph.colour();
        const Vec3 wi = ph.wi();
        m.f0 += phi;
        for (int c = 0; c < 3; ++c) m.f1[size_t(c)] += wi * phi[c];
    });
    m.f0 = m.f0 * inv_volume;
    for (Vec3& v : m.f1) v = v * inv_volume;
    return m;
}

void VolumeCache::save(ByteWriter& out) const {
    points_.save(out);
    out.put_vector(moments_);
}

void VolumeCache::load(ByteReader& in) {
    points_.load(in);
    moments_ = in.get_vector<VolumeMoments>();
    if (moments_.size() != points_.size()) in.fail("inconsistent volume cache");
}

void VolumeCache::build(const PhotonKdTree& volume, const VolumeEstimateOptions& volume_options,
                        const PhotonKdTree& volume_caustic, const VolumeEstimateOptions& caustic_options,
                        uint32_t stride) {
    stride = std::max<uint32_t>(stride, 1);
    const size_t n = (volume.size() + stride - 1) / stride;
    std::vector<Photon> pts(n);
    for (size_t i = 0; i < n; ++i) {
        const Photon& ph = volume.photon(uint32_t(i * stride));
        pts[i] = Photon(ph.position, Spectrum(0.0f), Wavelengths(), Vec3(0, 0, 1), Vec3(0, 0, 1));
    }
    points_.build(std::move(pts));  // in place: no second copy of the points
    moments_.assign(points_.size(), VolumeMoments{});
    tbb::parallel_for(tbb::blocked_range<size_t>(0, points_.size(), 256),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t i = r.begin(); i < r.end(); ++i) {
                              const Vec3 x = points_.photon(uint32_t(i)).position;
                              VolumeMoments m = volume_moments(volume, volume_options, x);
                              m += volume_moments(volume_caustic, caustic_options, x);
                              moments_[i] = m;
                          }
                      });
}

bool VolumeCache::lookup(Vec3 x, float max_radius, Vec3 wo, float g, Rgb& estimate) const {
    if (points_.empty()) return false;
    Neighbour nb;
    const KnnResult r = points_.knn(x, 1, max_radius * max_radius, &nb);
    if (r.count == 0) return false;
    estimate = moments_[nb.index].estimate(wo, g);
    return true;
}

}  // namespace phos::photon
