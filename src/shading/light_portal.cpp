// The portal of an infinite light (see the header): the rectified image, the windowed distribution
// for directions through the portal from a point, and the photon distribution over the portal.
#include "shading/light_portal.h"

#include <algorithm>
#include <cmath>

namespace phos::shading {

LightPortal::LightPortal(const std::array<Vec3, 4>& p, int nu, int nv,
                         const std::function<Rgb(Vec3)>& radiance)
    : corners_(p), nu_(std::max(nu, 1)), nv_(std::max(nv, 1)) {
    const Vec3 x = normalize(p[3] - p[0]), y = normalize(p[1] - p[0]);
    frame_ = Frame(x, y, normalize(cross(x, y)));
    area_ = length(p[1] - p[0]) * length(p[3] - p[0]);
    image_.resize(size_t(nu_) * size_t(nv_));
    std::vector<float> towards(image_.size()), emission(image_.size());
    double flux[3] = {0, 0, 0}, integral[3] = {0, 0, 0};
    const double cell = 1.0 / (double(nu_) * double(nv_));
    for (int j = 0; j < nv_; ++j)
        for (int i = 0; i < nu_; ++i) {
            const size_t k = size_t(j) * size_t(nu_) + size_t(i);
            float jac = 0;
            const Vec3 w =
                direction_of({(float(i) + 0.5f) / float(nu_), (float(j) + 0.5f) / float(nv_)}, &jac);
            Rgb c = radiance(w);
            for (int ch = 0; ch < 3; ++ch) c[ch] = std::isfinite(c[ch]) ? std::max(c[ch], 0.0f) : 0.0f;
            image_[k] = c;
            const float cos_theta = std::max(dot(w, frame_.n), 0.0f);
            // pbrt-v4's Image::GetSamplingDistribution: the channel average times dw/d(u, v).
            towards[k] = c.average() * jac;
            emission[k] = towards[k] * cos_theta;
            for (int ch = 0; ch < 3; ++ch) {
                integral[ch] += double(c[ch]) * jac * cell;
                flux[ch] += double(c[ch]) * jac * cos_theta * cell;
            }
        }
    towards_ = WindowedDistribution2D(towards, nu_, nv_);
    emission_ = Distribution2D(emission, nu_, nv_);
    integral_ = Rgb(float(integral[0]), float(integral[1]), float(integral[2]));
    flux_ = Rgb(float(flux[0]), float(flux[1]), float(flux[2])) * area_;
}

std::optional<Vec2> LightPortal::uv_of(Vec3 world, float* jacobian) const {
    const Vec3 w = frame_.to_local(world);
    if (!(w.z > 0) || !std::isfinite(w.x) || !std::isfinite(w.y)) return std::nullopt;
    if (jacobian) *jacobian = kPi * kPi * (1 - w.x * w.x) * (1 - w.y * w.y) / w.z;
    const float alpha = std::atan2(w.x, w.z), beta = std::atan2(w.y, w.z);
    return Vec2(std::clamp((alpha + 0.5f * kPi) / kPi, 0.0f, 1.0f),
                std::clamp((beta + 0.5f * kPi) / kPi, 0.0f, 1.0f));
}

Vec3 LightPortal::direction_of(Vec2 uv, float* jacobian) const {
    const float alpha = -0.5f * kPi + uv.x * kPi, beta = -0.5f * kPi + uv.y * kPi;
    const Vec3 w = normalize(Vec3(std::tan(alpha), std::tan(beta), 1.0f));
    if (jacobian) *jacobian = kPi * kPi * (1 - w.x * w.x) * (1 - w.y * w.y) / w.z;
    return frame_.to_world(w);
}

Rgb LightPortal::pixel(Vec2 uv) const {
    const int i = std::clamp(int(uv.x * float(nu_)), 0, nu_ - 1),
              j = std::clamp(int(uv.y * float(nv_)), 0, nv_ - 1);
    return image_[size_t(j) * size_t(nu_) + size_t(i)];
}

Rgb LightPortal::radiance(Vec3 w) const {
    const std::optional<Vec2> uv = uv_of(w);
    return uv ? pixel(*uv) : Rgb(0.0f);
}

std::optional<UvWindow> LightPortal::window(Vec3 p) const {
    const Vec3 d0 = corners_[0] - p, d2 = corners_[2] - p;
    if (!(length_squared(d0) > 0) || !(length_squared(d2) > 0)) return std::nullopt;
    const std::optional<Vec2> a = uv_of(normalize(d0)), b = uv_of(normalize(d2));
    if (!a || !b) return std::nullopt;
    return UvWindow{{std::min(a->x, b->x), std::min(a->y, b->y)},
                    {std::max(a->x, b->x), std::max(a->y, b->y)}};
}

std::optional<Vec3> LightPortal::sample_towards(Vec3 p, Vec2 u, float* pdf) const {
    const std::optional<UvWindow> win = window(p);
    if (!win) return std::nullopt;
    float pdf_uv = 0;
    const std::optional<Vec2> uv = towards_.sample(u, *win, &pdf_uv);
    if (!uv) return std::nullopt;
    const Vec3 w = direction_of(*uv);
    // The density of the final direction, exactly as pdf_towards gives it (a sample on a pixel's
    // edge may round into its neighbour).
    *pdf = pdf_towards(p, w);
    if (!(*pdf > 0)) return std::nullopt;
    return w;
}

float LightPortal::pdf_towards(Vec3 p, Vec3 w) const {
    float jac = 0;
    const std::optional<Vec2> uv = uv_of(w, &jac);
    if (!uv || !(jac > 0)) return 0;
    const std::optional<UvWindow> win = window(p);
    if (!win) return 0;
    return towards_.pdf(*uv, *win) / jac;
}

std::optional<LightPortal::Emission> LightPortal::sample_emission(Vec2 u_pos, Vec2 u_dir) const {
    Emission e;
    e.w = direction_of(emission_.sample(u_dir));
    // The densities of the final direction, exactly as pdf_emission gives them.
    pdf_emission(e.w, e.pdf_pos, e.pdf_dir);
    if (!(e.pdf_pos > 0) || !(e.pdf_dir > 0)) return std::nullopt;
    e.origin = corners_[0] + (corners_[1] - corners_[0]) * u_pos.x + (corners_[3] - corners_[0]) * u_pos.y;
    return e;
}

void LightPortal::pdf_emission(Vec3 w, float& pdf_pos, float& pdf_dir) const {
    pdf_pos = pdf_dir = 0;
    float jac = 0;
    const std::optional<Vec2> uv = uv_of(w, &jac);
    const float cos_theta = dot(w, frame_.n);
    if (!uv || !(jac > 0) || !(cos_theta > 0)) return;
    pdf_dir = emission_.pdf(*uv) / jac;
    pdf_pos = 1 / (area_ * cos_theta);
}

}  // namespace phos::shading
