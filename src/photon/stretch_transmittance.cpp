// Transmittance along a camera-ray stretch and its integrals (see stretch_transmittance.h).
#include "photon/stretch_transmittance.h"

#include <algorithm>
#include <cmath>

namespace phos::photon {
namespace {

constexpr float kCutoff = 1e-4f;  // T below this in every channel ends the table

bool grey(Rgb s) { return s.r == s.g && s.g == s.b; }

// exp(-sigma x) per channel (once for a grey medium).
Rgb decay(Rgb sigma, float x) {
    if (grey(sigma)) return Rgb(std::exp(-sigma.r * x));
    return {std::exp(-sigma.r * x), std::exp(-sigma.g * x), std::exp(-sigma.b * x)};
}

// int_0^L exp(-sigma t) dt = (1 - exp(-sigma L)) / sigma, L where sigma = 0; expm1 keeps it exact
// for short chords and thin media.
float chord(float sigma, float L) { return sigma > 0 ? -std::expm1(-sigma * L) / sigma : L; }
Rgb chord(Rgb sigma, float L) {
    if (grey(sigma)) return Rgb(chord(sigma.r, L));
    return {chord(sigma.r, L), chord(sigma.g, L), chord(sigma.b, L)};
}

// The same integral over [m - L/2, m + L/2] divided by exp(-sigma m): L sinh(x) / x, x = sigma L / 2.
// A series below x = 0.05 (relative error < x^6 / 5040 ~ 3e-12).
float mid_chord(float sigma, float L) {
    const float x = 0.5f * sigma * L;
    if (x < 0.05f) {
        const float x2 = x * x;
        return L * (1 + x2 * (1.0f / 6 + x2 * (1.0f / 120)));
    }
    return L * std::sinh(x) / x;
}
Rgb mid_chord(Rgb sigma, float L) {
    if (grey(sigma)) return Rgb(mid_chord(sigma.r, L));
    return {mid_chord(sigma.r, L), mid_chord(sigma.g, L), mid_chord(sigma.b, L)};
}

}  // namespace

StretchTransmittance::StretchTransmittance(const shading::Medium& medium, Vec3 o, Vec3 d, float t_end,
                                           float step, float jitter) {
    if (medium.homogeneous()) {
        const Rgb sigma = medium.sigma_t_rgb();
        pieces_.push_back({0.0f, Rgb(1.0f), Rgb(0.0f), sigma});
        dt_ = kInf;
        const float thinnest = std::min(sigma.r, std::min(sigma.g, sigma.b));
        end_ = thinnest > 0 ? std::min(t_end, std::log(1.0f / kCutoff) / thinnest) : t_end;
        total_ = decay(sigma, t_end);
        return;
    }
    const int n = std::clamp(int(std::ceil(t_end / step)), 1, 4096);
    dt_ = t_end / float(n);
    pieces_.reserve(size_t(n));
    Rgb T(1.0f), C(0.0f);
    end_ = t_end;
    for (int k = 0; k < n; ++k) {
        const float t = float(k) * dt_;
        const Rgb sigma = medium.sigma_t_rgb(o + d * (t + jitter * dt_));
        pieces_.push_back({t, T, C, sigma});
        C += T * chord(sigma, dt_);
        T *= decay(sigma, dt_);
        if (T.max() < kCutoff) {
            end_ = std::min(t_end, float(k + 1) * dt_);
            break;
        }
    }
    total_ = T;
}

size_t StretchTransmittance::piece_of(float t) const {
    if (pieces_.size() == 1) return 0;
    return std::min(pieces_.size() - 1, size_t(std::max(t / dt_, 0.0f)));
}

Rgb StretchTransmittance::at(float t) const {
    const Piece& p = pieces_[piece_of(t)];
    return p.T * decay(p.sigma, t - p.t);
}

Rgb StretchTransmittance::integral(float a, float b) const {
    const size_t ka = piece_of(a), kb = piece_of(b);
    const Piece& pa = pieces_[ka];
    // Within one piece: T at the chord's middle times L sinh(x) / x, x = sigma L / 2 (one exp per
    // channel, no cancellation for short chords); where sinh could overflow, T(a) times
    // (1 - exp(-sigma L)) / sigma.
    if (ka == kb) {
        const float L = b - a;
        if (pa.sigma.max() * L < 80.0f)
            return pa.T * decay(pa.sigma, 0.5f * (a + b) - pa.t) * mid_chord(pa.sigma, L);
        return pa.T * decay(pa.sigma, a - pa.t) * chord(pa.sigma, L);
    }
    const Piece& pb = pieces_[kb];
    const Rgb Ca = pa.C + pa.T * chord(pa.sigma, a - pa.t);
    const Rgb Cb = pb.C + pb.T * chord(pb.sigma, b - pb.t);
    return max(Cb - Ca, Rgb(0.0f));
}

}  // namespace phos::photon
