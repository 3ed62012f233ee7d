// The transmittance along one stretch of a camera ray in a medium, T(t) = exp(-int_0^t sigma_t),
// and its integral over sub-intervals: what the beam radiance estimate (beam_estimate.h) weights
// each photon's chord with. It is computed from the medium's RGB coefficients (the colour of
// sigma_t), as the estimate multiplies it with each photon's colour: exact for grey media, the RGB
// product's approximation for coloured ones.
//   homogeneous media  exact: T(t) = exp(-sigma_t t), one piece.
//   grid media         a table over the ray-marching steps (length <= `step`): sigma_t is taken
//                      constant over each step, at a jittered point in it (as the ray march
//                      evaluates it), so T is exponential within a step and the integrals below are
//                      exact for that piecewise-constant medium. The table ends where every
//                      channel of T falls below 1e-4 (where the march stops too).
// Per channel, over a piece starting at t_k with T_k and sigma_k:
//   T(t) = T_k exp(-sigma_k (t - t_k)),
//   int_a^b T = T((a + b) / 2) L sinh(x) / x = T(a) (1 - exp(-sigma_k L)) / sigma_k,
//   L = b - a, x = sigma_k L / 2 (the first form costs one exp per channel; integrals across
//   pieces add up from the pieces' running integrals).
#pragma once

#include <vector>

#include "core/vec.h"
#include "shading/medium.h"

namespace phos::photon {

class StretchTransmittance {
public:
    // The stretch o + t d, t in [0, t_end] (d unit, t_end finite) of `medium`; `step` and
    // `jitter` (in [0, 1)) place the grid media's evaluation points.
    StretchTransmittance(const shading::Medium& medium, Vec3 o, Vec3 d, float t_end, float step,
                         float jitter);

    // Where the table ends (<= t_end): beyond it every channel of T is below 1e-4, and the
    // estimate may stop there.
    float end() const { return end_; }
    // T(t) for t in [0, end()].
    Rgb at(float t) const;
    // int_a^b T(t) dt for 0 <= a <= b <= end().
    Rgb integral(float a, float b) const;
    // T over the whole stretch, T(t_end) (what lies behind it is attenuated by this).
    Rgb total() const { return total_; }

private:
    struct Piece {
        float t;    // start
        Rgb T, C;   // T(t) and int_0^t T
        Rgb sigma;  // sigma_t over the piece
    };
    size_t piece_of(float t) const;

    std::vector<Piece> pieces_;
    float dt_ = 0;  // piece length (all but possibly the last)
    float end_ = 0;
    Rgb total_{1.0f};
};

}  // namespace phos::photon
