// Tabulation of analytic BRDFs into Dupuy & Jakob's measured tables (measured_tabulation.h).
#include "shading/measured_tabulation.h"

#include <algorithm>
#include <cmath>

#include "shading/fresnel.h"
#include "spectrum/cie_tables.h"

namespace phos::shading {

namespace {

constexpr double kPiD = 3.14159265358979323846;

// Trowbridge-Reitz D, Smith Lambda and the projected area sigma = cos (1 + Lambda), in double.
struct Ggx {
    double ax, ay;
    double D(Vec3 m) const {
        if (m.z <= 0) return 0;
        const double x = m.x / ax, y = m.y / ay, q = double(m.z) * m.z + x * x + y * y;
        return 1 / (kPiD * ax * ay * q * q);
    }
    double lambda(Vec3 w) const {
        const double z2 = double(w.z) * w.z, a2 = ax * ax * w.x * w.x + ay * ay * w.y * w.y;
        if (z2 <= 0) return 1e30;
        return 0.5 * (std::sqrt(1 + a2 / z2) - 1);
    }
    double sigma(Vec3 w) const {  // cos (1 + Lambda), finite at grazing angles
        const double z = std::max(double(w.z), 0.0), a2 = ax * ax * w.x * w.x + ay * ay * w.y * w.y;
        return 0.5 * (z + std::sqrt(z * z + a2));
    }
};

Vec3 spherical(double theta, double phi) {
    return Vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                float(std::cos(theta)));
}

double u_to_theta(double u) { return u * u * (kPiD / 2); }
double u_to_phi(double u) { return (2 * u - 1) * kPiD; }

float cie_y(float lambda) {
    const int i = int(std::lround(lambda)) - spectrum::kCieMin;
    return i >= 0 && i < spectrum::kCieSamples ? spectrum::kCieY[i] : 0.0f;
}

}  // namespace

float analytic_brdf(const TabulatedModel& model, Vec3 wo, Vec3 wi, float lambda) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    if (model.kind == TabulatedModel::Kind::Lambert) return float(model.reflectance / kPiD);
    const Ggx g{std::max(double(model.alpha_x), 1e-4), std::max(double(model.alpha_y), 1e-4)};
    const Vec3 wm = normalize(wo + wi);
    const double F = fresnel_conductor(dot(wo, wm), model.eta(lambda), model.k(lambda));
    const double G2 = 1 / (1 + g.lambda(wo) + g.lambda(wi));
    return float(F * g.D(wm) * G2 / (4 * double(wo.z) * double(wi.z)));
}

scene::MeasuredBsdfTables tabulate_brdf(const TabulatedModel& model, const TabulationGrid& grid) {
    const Ggx g{std::max(double(model.alpha_x), 1e-4), std::max(double(model.alpha_y), 1e-4)};
    const bool isotropic = model.alpha_x == model.alpha_y;
    scene::MeasuredBsdfTables t;
    t.description = grid.description;
    t.jacobian = true;
    // Up to 89.9 degrees: at 90 the conductor's f has only a limit (and cos(float(pi / 2)) < 0).
    for (int i = 0; i < grid.n_theta_i; ++i)
        t.theta_i.push_back(float(0.999 * kPiD / 2 * i / (grid.n_theta_i - 1)));
    if (isotropic) {
        t.phi_i = {0.0f};
    } else {
        for (int i = 0; i < grid.n_phi_i; ++i)
            t.phi_i.push_back(float(u_to_phi(double(i) / (grid.n_phi_i - 1))));
    }
    t.wavelengths = grid.wavelengths;

    // ndf and sigma over (u(theta), u(phi)).
    t.ndf_nx = t.ndf_ny = t.sigma_nx = t.sigma_ny = grid.ndf_n;
    for (int y = 0; y < grid.ndf_n; ++y)
        for (int x = 0; x < grid.ndf_n; ++x) {
            const Vec3 w =
                spherical(u_to_theta(double(x) / (grid.ndf_n - 1)), u_to_phi(double(y) / (grid.ndf_n - 1)));
            t.ndf.push_back(float(g.D(w)));
            t.sigma.push_back(float(g.sigma(w)));
        }
    const scene::PiecewiseLinear2D ndf(t.ndf.data(), t.ndf_nx, t.ndf_ny, {}, false);
    const scene::PiecewiseLinear2D sigma(t.sigma.data(), t.sigma_nx, t.sigma_ny, {}, false);

    // vndf per incident direction, as a density over the unit square of wm.
    t.vndf_nx = t.vndf_ny = grid.vndf_n;
    for (float phi_o : t.phi_i)
        for (float theta_o : t.theta_i) {
            const Vec3 wo = spherical(theta_o, phi_o);
            for (int y = 0; y < grid.vndf_n; ++y)
                for (int x = 0; x < grid.vndf_n; ++x) {
                    const double ux = double(x) / (grid.vndf_n - 1), theta_m = u_to_theta(ux);
                    const double phi_m = u_to_phi(double(y) / (grid.vndf_n - 1)) + (isotropic ? phi_o : 0.0);
                    const Vec3 wm = spherical(theta_m, phi_m);
                    const double visible = std::max(double(dot(wo, wm)), 0.0) * g.D(wm) / g.sigma(wo);
                    t.vndf.push_back(float(visible * 2 * kPiD * kPiD * ux * std::sin(theta_m)));
                }
        }
    const scene::PiecewiseLinear2D vndf(t.vndf.data(), t.vndf_nx, t.vndf_ny, {t.phi_i, t.theta_i}, true);

    // The reduced BRDF over the warp's input square, and its luminance.
    const bool spectral = !grid.wavelengths.empty();
    const std::vector<float> channels = spectral ? grid.wavelengths : std::vector<float>{612, 549, 465};
    std::vector<double> weight(channels.size());
    double weight_sum = 0;
    for (size_t c = 0; c < channels.size(); ++c) {
        weight[c] = spectral ? cie_y(channels[c]) : (c == 0 ? 0.2126 : c == 1 ? 0.7152 : 0.0722);
        weight_sum += weight[c];
    }
    if (!(weight_sum > 0)) {
        std::fill(weight.begin(), weight.end(), 1.0);
        weight_sum = double(channels.size());
    }
    t.n = grid.n;
    const size_t nn = size_t(grid.n) * size_t(grid.n);
    std::vector<float>& values = spectral ? t.spectra : t.rgb;
    for (float phi_o : t.phi_i)
        for (float theta_o : t.theta_i) {
            const Vec3 wo = spherical(theta_o, phi_o);
            const float param[2] = {phi_o, theta_o};
            const double sigma_o =
                sigma.eval(Vec2(float(std::sqrt(theta_o * 2 / kPiD)), float(phi_o / (2 * kPiD) + 0.5)));
            std::vector<float> slice(channels.size() * nn, 0.0f), lum(nn, 0.0f);
            for (int y = 0; y < grid.n; ++y)
                for (int x = 0; x < grid.n; ++x) {
                    const Vec2 u(float(x) / float(grid.n - 1), float(y) / float(grid.n - 1));
                    const Vec2 u_wm = vndf.sample(u, param).p;
                    const double phi_m = u_to_phi(u_wm.y) + (isotropic ? phi_o : 0.0);
                    const Vec3 wm = spherical(u_to_theta(u_wm.x), phi_m);
                    const Vec3 wi = reflect(wo, wm);
                    const double d = ndf.eval(u_wm);
                    if (wi.z <= 0 || !(d > 0)) continue;
                    double y_sum = 0;
                    for (size_t c = 0; c < channels.size(); ++c) {
                        const double fr = analytic_brdf(model, wo, wi, channels[c]) * 4 * sigma_o * wi.z / d;
                        slice[c * nn + size_t(y) * size_t(grid.n) + size_t(x)] = float(fr);
                        y_sum += weight[c] * fr;
                    }
                    lum[size_t(y) * size_t(grid.n) + size_t(x)] = float(y_sum / weight_sum);
                }
            values.insert(values.end(), slice.begin(), slice.end());
            t.luminance.insert(t.luminance.end(), lum.begin(), lum.end());
        }
    return t;
}

}  // namespace phos::shading
