// The open share of a ball around a volume visible point (see open_ball.h).
#include "photon/open_ball.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "accel/ray.h"

namespace phos::photon {

namespace {

// Spherical Fibonacci points: evenly spread unit directions (z uniform, golden-angle azimuths).
std::array<Vec3, kOpenBallDirections> directions() {
    std::array<Vec3, kOpenBallDirections> d;
    const double golden = M_PI * (3 - std::sqrt(5.0));
    for (int i = 0; i < kOpenBallDirections; ++i) {
        const double z = 1 - (2 * i + 1) / double(kOpenBallDirections);
        const double s = std::sqrt(std::max(0.0, 1 - z * z)), phi = golden * i;
        d[size_t(i)] = Vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
    }
    return d;
}

}  // namespace

float open_ball_fraction(const accel::EmbreeScene& accel, Vec3 p, float r) {
    static const std::array<Vec3, kOpenBallDirections> dirs = directions();
    if (!(r > 0)) return 1;
    double sum = 0;
    for (const Vec3& w : dirs) {
        Ray ray{p, w, 0.0f, r};
        accel::SurfaceHit hit;
        const double d = accel.intersect(ray, hit) ? std::min(double(hit.t), double(r)) : double(r);
        sum += (d / r) * (d / r) * (d / r);
    }
    return std::max(float(sum / kOpenBallDirections), kOpenBallMinFraction);
}

}  // namespace phos::photon
