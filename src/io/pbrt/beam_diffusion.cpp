// Photon beam diffusion profile and its effective-albedo table (see beam_diffusion.h).
#include "io/pbrt/beam_diffusion.h"

#include <algorithm>
#include <cmath>

namespace phos::io::pbrt {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr double kInv4Pi = 1.0 / (4.0 * kPiD);
constexpr int kDepthSamples = 100;  // stratified depths per profile value, as pbrt-v4 takes

// Polynomial fits of the first two moments of the dielectric Fresnel reflectance (d'Eon & Irving
// 2011, "A quantized-diffusion model for rendering translucent materials"), as the pbrt book
// gives them.
double fresnel_moment1(double eta) {
    const double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
    if (eta < 1) return 0.45966 - 1.73965 * eta + 3.37668 * e2 - 3.904945 * e3 + 2.49277 * e4 - 0.68441 * e5;
    return -4.61686 + 11.1136 * eta - 10.4646 * e2 + 5.11455 * e3 - 1.27198 * e4 + 0.12746 * e5;
}
double fresnel_moment2(double eta) {
    const double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
    if (eta < 1) return 0.27614 - 0.87350 * eta + 1.12077 * e2 - 0.65095 * e3 + 0.07883 * e4 + 0.04860 * e5;
    const double r = 1 / eta, r2 = r * r, r3 = r2 * r;
    return -547.033 + 45.3087 * r3 - 218.725 * r2 + 458.843 * r + 404.557 * eta - 189.519 * e2 +
           54.9327 * e3 - 9.00603 * e4 + 0.63942 * e5;
}

// Unpolarised Fresnel reflectance of a smooth dielectric of relative index eta for incidence
// cosine cos_i (negative: arriving from inside, the index inverted).
double fresnel_dielectric(double cos_i, double eta) {
    if (cos_i < 0) eta = 1 / eta, cos_i = -cos_i;
    const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return 1;
    const double cos_t = std::sqrt(1 - sin2_t);
    const double parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (parallel * parallel + perpendicular * perpendicular);
}

double henyey_greenstein(double cos_theta, double g) {
    const double denom = 1 + g * g + 2 * g * cos_theta;
    return kInv4Pi * (1 - g * g) / (denom * std::sqrt(std::max(denom, 0.0)));
}

// The Catmull-Rom segment [x[i], x[i+1]]: its end values and end derivatives (per unit of the
// segment's parameter t in [0, 1]).
struct Segment {
    double x0, width, f0, f1, d0, d1;
};
Segment segment(const std::vector<float>& x, const std::vector<float>& f, size_t i) {
    Segment s{x[i], double(x[i + 1]) - x[i], f[i], f[i + 1], 0, 0};
    s.d0 = i > 0 ? s.width * (double(f[i + 1]) - f[i - 1]) / (double(x[i + 1]) - x[i - 1]) : s.f1 - s.f0;
    s.d1 = i + 2 < x.size() ? s.width * (double(f[i + 2]) - f[i]) / (double(x[i + 2]) - x[i]) : s.f1 - s.f0;
    return s;
}
// The cubic Hermite interpolant of a segment at t.
double hermite(const Segment& s, double t) {
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * s.f0 + (-2 * t3 + 3 * t2) * s.f1 + (t3 - 2 * t2 + t) * s.d0 +
           (t3 - t2) * s.d1;
}
// The segment holding t (the last one for t at or beyond the end).
size_t segment_index(const std::vector<float>& x, double t) {
    const auto it = std::upper_bound(x.begin(), x.end(), float(t));
    const size_t i = it == x.begin() ? 0 : size_t(it - x.begin()) - 1;
    return std::min(i, x.size() - 2);
}

}  // namespace

float beam_diffusion_ms(float sigma_s, float sigma_a, float g, float eta, float r) {
    // Reduced coefficients, Grosjean's diffusion coefficient and the transport coefficient.
    const double sp_s = double(sigma_s) * (1 - g), sp_t = sigma_a + sp_s, rho_p = sp_s / sp_t;
    const double D = (2 * double(sigma_a) + sp_s) / (3 * sp_t * sp_t);
    const double sigma_tr = std::sqrt(std::max(0.0, sigma_a / D));
    // The extrapolated boundary's depth and the exitance factors of the fluence and of the flux.
    const double fm1 = fresnel_moment1(eta), fm2 = fresnel_moment2(eta);
    const double ze = -2 * D * (1 + 3 * fm2) / (1 - 2 * fm1);
    const double c_phi = 0.25 * (1 - 2 * fm1), c_e = 0.5 * (1 - 3 * fm2);
    double sum = 0;
    for (int i = 0; i < kDepthSamples; ++i) {
        // The real source's depth, sampled by the reduced beam's attenuation; its mirror source.
        const double zr = -std::log(1 - (i + 0.5) / kDepthSamples) / sp_t;
        const double zv = -zr + 2 * ze;
        const double dr = std::sqrt(double(r) * r + zr * zr), dv = std::sqrt(double(r) * r + zv * zv);
        const double er = std::exp(-sigma_tr * dr), ev = std::exp(-sigma_tr * dv);
        const double phi = kInv4Pi / D * (er / dr - ev / dv);
        const double e_n = kInv4Pi * (zr * (1 + sigma_tr * dr) * er / (dr * dr * dr) -
                                      zv * (1 + sigma_tr * dv) * ev / (dv * dv * dv));
        const double kappa = 1 - std::exp(-2 * sp_t * (dr + zr));
        sum += kappa * rho_p * rho_p * (phi * c_phi + e_n * c_e);
    }
    return float(sum / kDepthSamples);
}

float beam_diffusion_ss(float sigma_s, float sigma_a, float g, float eta, float r) {
    const double sigma_t = double(sigma_a) + sigma_s, rho = sigma_s / sigma_t;
    // Below this depth the connection to the exit point is beyond the critical angle.
    const double t_crit = r * std::sqrt(std::max(0.0, double(eta) * eta - 1));
    double sum = 0;
    for (int i = 0; i < kDepthSamples; ++i) {
        const double t = t_crit - std::log(1 - (i + 0.5) / kDepthSamples) / sigma_t;
        const double d = std::sqrt(double(r) * r + t * t), cos_o = t / d;
        sum += rho * std::exp(-sigma_t * (d + t_crit)) / (d * d) * henyey_greenstein(cos_o, g) *
               (1 - fresnel_dielectric(-cos_o, eta)) * std::abs(cos_o);
    }
    return float(sum / kDepthSamples);
}

double integrate_catmull_rom(const std::vector<float>& x, const std::vector<float>& f) {
    double sum = 0;
    for (size_t i = 0; i + 1 < x.size(); ++i) {
        const Segment s = segment(x, f, i);
        sum += s.width * ((s.f0 + s.f1) / 2 + (s.d0 - s.d1) / 12);
    }
    return sum;
}

double eval_catmull_rom(const std::vector<float>& x, const std::vector<float>& f, double t) {
    const Segment s = segment(x, f, segment_index(x, t));
    return hermite(s, std::clamp((t - s.x0) / s.width, 0.0, 1.0));
}

BeamDiffusionTable::BeamDiffusionTable(float g, float eta) {
    const int n_rho = 100, n_radius = 64;
    radius_.resize(n_radius);
    radius_[0] = 0;
    radius_[1] = 2.5e-3f;
    for (int i = 2; i < n_radius; ++i) radius_[size_t(i)] = radius_[size_t(i) - 1] * 1.2f;
    rho_.resize(n_rho);
    for (int i = 0; i < n_rho; ++i)
        rho_[size_t(i)] = float((1 - std::exp(-8.0 * i / (n_rho - 1))) / (1 - std::exp(-8.0)));
    rho_eff_.resize(n_rho);
    std::vector<float> profile(n_radius);
    for (int i = 0; i < n_rho; ++i) {
        const float rho = rho_[size_t(i)];
        for (int j = 0; j < n_radius; ++j) {
            const float r = radius_[size_t(j)];
            profile[size_t(j)] = float(2 * kPiD * r) * (beam_diffusion_ss(rho, 1 - rho, g, eta, r) +
                                                        beam_diffusion_ms(rho, 1 - rho, g, eta, r));
        }
        rho_eff_[size_t(i)] = float(integrate_catmull_rom(radius_, profile));
    }
}

float BeamDiffusionTable::effective_albedo(float rho) const {
    return float(eval_catmull_rom(rho_, rho_eff_, std::clamp(rho, 0.0f, 1.0f)));
}

float BeamDiffusionTable::albedo_for(float rho_eff) const {
    if (!(rho_eff > rho_eff_.front())) return rho_.front();
    if (!(rho_eff < rho_eff_.back())) return rho_.back();
    // The last tabulated effective albedo at or below the target, then the segment's spline
    // inverted by bisection (its ends bracket the target).
    const size_t i = segment_index(rho_eff_, rho_eff);
    const Segment s = segment(rho_, rho_eff_, i);
    double a = 0, b = 1;
    for (int k = 0; k < 60; ++k) {
        const double m = 0.5 * (a + b);
        (hermite(s, m) <= rho_eff ? a : b) = m;
    }
    return float(s.x0 + 0.5 * (a + b) * s.width);
}

}  // namespace phos::io::pbrt
