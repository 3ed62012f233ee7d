// The measured BSDF's consistency rules and its interpolants (measured_bsdf.h).
#include "scene/measured_bsdf.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace phos::scene {

namespace {

constexpr double kTwoPi = 6.283185307179586;

std::string axis_problem(const std::vector<float>& axis, const char* name) {
    if (axis.empty()) return std::string(name) + " is empty";
    for (size_t i = 0; i < axis.size(); ++i) {
        if (!std::isfinite(axis[i]))
            return std::string(name) + "[" + std::to_string(i) + "] is not a finite number";
        if (i > 0 && !(axis[i] > axis[i - 1]))
            return std::string(name) + " is not strictly increasing (at index " + std::to_string(i) + ")";
    }
    return {};
}

// Checks a table's size (count floats expected), finite values and, unless `negative_ok`, signs.
std::string values_problem(const std::vector<float>& v, size_t count, const char* name, bool negative_ok) {
    if (v.size() != count)
        return std::string(name) + " holds " + std::to_string(v.size()) + " values where its shape needs " +
               std::to_string(count);
    for (size_t i = 0; i < v.size(); ++i) {
        if (!std::isfinite(v[i]))
            return std::string(name) + "[" + std::to_string(i) + "] is not a finite number";
        if (!negative_ok && v[i] < 0)
            return std::string(name) + "[" + std::to_string(i) + "] is negative (" + std::to_string(v[i]) +
                   ")";
    }
    return {};
}

std::string grid_problem(int nx, int ny, const char* name) {
    if (nx < 2 || ny < 2)
        return std::string(name) + " is a " + std::to_string(ny) + " x " + std::to_string(nx) +
               " grid (an interpolant needs at least 2 x 2)";
    return {};
}

// Every slice of a warp must have mass, or its CDF cannot be normalised.
std::string mass_problem(const std::vector<float>& v, int nx, int ny, size_t slices, const char* name) {
    const size_t n = size_t(nx) * size_t(ny);
    for (size_t s = 0; s < slices; ++s)
        if (!(PiecewiseLinear2D::slice_integral(v.data() + s * n, nx, ny) > 0))
            return std::string(name) + " slice " + std::to_string(s) +
                   " is zero everywhere (nothing to sample)";
    return {};
}

}  // namespace

std::string MeasuredBsdfTables::check() const {
    std::string e;
    if (!(e = axis_problem(theta_i, "theta_i")).empty()) return e;
    if (!(e = axis_problem(phi_i, "phi_i")).empty()) return e;
    if (!isotropic()) {
        // pbrt-v4 reads anisotropic files whose phi_i spans the circle once (its "reduction" 1).
        const double span = double(phi_i.back()) - double(phi_i.front());
        if (std::fabs(kTwoPi / span - 1) >= 0.5)
            return "phi_i spans " + std::to_string(span) +
                   " rad: an anisotropic file must cover 2 pi (symmetry reductions are not read)";
    }
    if (spectral()) {
        if (!(e = axis_problem(wavelengths, "wavelengths")).empty()) return e;
        if (wavelengths.front() <= 0) return "wavelengths are not positive";
    }
    if (!(e = grid_problem(ndf_nx, ndf_ny, "ndf")).empty()) return e;
    if (!(e = grid_problem(sigma_nx, sigma_ny, "sigma")).empty()) return e;
    if (!(e = grid_problem(vndf_nx, vndf_ny, "vndf")).empty()) return e;
    if (!(e = grid_problem(n, n, "luminance")).empty()) return e;
    const size_t slices = phi_i.size() * theta_i.size();
    if (!(e = values_problem(ndf, size_t(ndf_nx) * size_t(ndf_ny), "ndf", false)).empty()) return e;
    if (!(e = values_problem(sigma, size_t(sigma_nx) * size_t(sigma_ny), "sigma", false)).empty()) return e;
    if (!(e = values_problem(vndf, slices * size_t(vndf_nx) * size_t(vndf_ny), "vndf", false)).empty())
        return e;
    if (!(e = values_problem(luminance, slices * size_t(n) * size_t(n), "luminance", false)).empty())
        return e;
    if (spectral()) {
        if (!(e = values_problem(spectra, slices * wavelengths.size() * size_t(n) * size_t(n), "spectra",
                                 true))
                 .empty())
            return e;
    } else {
        if (rgb.empty()) return "the file holds neither spectra (with wavelengths) nor rgb";
        if (!(e = values_problem(rgb, slices * 3 * size_t(n) * size_t(n), "rgb", true)).empty()) return e;
    }
    if (!(e = mass_problem(vndf, vndf_nx, vndf_ny, slices, "vndf")).empty()) return e;
    if (!(e = mass_problem(luminance, n, n, slices, "luminance")).empty()) return e;
    return {};
}

MeasuredBsdf::MeasuredBsdf(MeasuredBsdfTables tables) : t_(std::move(tables)) {
    if (const std::string e = t_.check(); !e.empty()) throw std::invalid_argument(e);
    ndf_ = PiecewiseLinear2D(t_.ndf.data(), t_.ndf_nx, t_.ndf_ny, {}, false);
    sigma_ = PiecewiseLinear2D(t_.sigma.data(), t_.sigma_nx, t_.sigma_ny, {}, false);
    vndf_ = PiecewiseLinear2D(t_.vndf.data(), t_.vndf_nx, t_.vndf_ny, {t_.phi_i, t_.theta_i}, true);
    luminance_ = PiecewiseLinear2D(t_.luminance.data(), t_.n, t_.n, {t_.phi_i, t_.theta_i}, true);
    const std::vector<float> channels = t_.spectral() ? t_.wavelengths : std::vector<float>{0.0f, 1.0f, 2.0f};
    const std::vector<float>& values = t_.spectral() ? t_.spectra : t_.rgb;
    spectra_ = PiecewiseLinear2D(values.data(), t_.n, t_.n, {t_.phi_i, t_.theta_i, channels}, false);

    // The albedo of each incident slice: the reduced BRDF's integral over the square, averaged over
    // the channels, negative values read as 0 (as evaluation clamps them).
    const size_t slices = t_.phi_i.size() * t_.theta_i.size(), nn = size_t(t_.n) * size_t(t_.n);
    std::vector<float> albedo(slices * 4), clamped(nn);
    for (size_t s = 0; s < slices; ++s) {
        double sum = 0;
        for (size_t c = 0; c < channels.size(); ++c) {
            const float* v = values.data() + (s * channels.size() + c) * nn;
            for (size_t i = 0; i < nn; ++i) clamped[i] = std::fmax(v[i], 0.0f);
            sum += PiecewiseLinear2D::slice_integral(clamped.data(), t_.n, t_.n);
        }
        for (int k = 0; k < 4; ++k) albedo[s * 4 + size_t(k)] = float(sum / double(channels.size()));
    }
    albedo_ = PiecewiseLinear2D(albedo.data(), 2, 2, {t_.phi_i, t_.theta_i}, false);
    // D at the normal (u(theta) = 0; any phi).
    const double d0 = ndf_.eval(Vec2(0.0f, 0.5f));
    equivalent_alpha_ = d0 > 0 ? float(std::min(1.0, 1 / std::sqrt(3.14159265358979323846 * d0))) : 1.0f;
}

float MeasuredBsdf::albedo(float phi_o, float theta_o) const {
    const float param[2] = {phi_o, theta_o};
    return std::fmax(albedo_.eval(Vec2(0, 0), param), 0.0f);
}

}  // namespace phos::scene
