// Projection light: the perspective projection of pbrt-v4's ProjectionLight (its screen window,
// hither 1e-3, nearest-pixel lookup) with the pixel distribution its SampleLe draws from.
#include "shading/projection_light.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "shading/point_light.h"
#include "spectrum/rgb_spectrum.h"

namespace phos::shading {
namespace {

constexpr float kHither = 1e-3f;  // pbrt-v4: directions closer than this to the plane z = 0 get nothing

// Solid angle the rectangle [x0, x1] x [y0, y1] of the plane z = 1 subtends at the origin:
// F(x1, y1) - F(x0, y1) - F(x1, y0) + F(x0, y0) with F(x, y) = atan(x y / sqrt(1 + x^2 + y^2)).
double rectangle_solid_angle(double x0, double x1, double y0, double y1) {
    auto F = [](double x, double y) { return std::atan(x * y / std::sqrt(1 + x * x + y * y)); };
    return F(x1, y1) - F(x0, y1) - F(x1, y0) + F(x0, y0);
}

}  // namespace

ProjectionLight::ProjectionLight(const scene::Light& light, const std::vector<scene::Texture>& textures)
    : Light(light),
      position_(light.to_world.point({0, 0, 0})),
      frame_(light_frame(light.to_world)),
      scale_(light.color) {
    if (light.texture < 0 || size_t(light.texture) >= textures.size())
        throw InputError("projection light: texture index " + std::to_string(light.texture) +
                         " out of range");
    const scene::Texture& tex = textures[size_t(light.texture)];
    if (tex.kind != scene::Texture::Kind::Image || !tex.image || tex.image->width <= 0 ||
        tex.image->height <= 0)
        throw InputError("projection light: the slide must be an image");
    if (!(light.fov > 0 && light.fov < kPi))
        throw InputError("projection light: fov must be in (0, 180) degrees");
    width_ = tex.image->width;
    height_ = tex.image->height;
    texels_ = tex.image->texels;
    for (Rgb& c : texels_)
        for (int k = 0; k < 3; ++k) c[k] = std::isfinite(c[k]) ? std::max(c[k], 0.0f) : 0.0f;
    tan_half_ = std::tan(0.5f * light.fov);
    const float aspect = float(width_) / float(height_);
    if (aspect > 1) {
        window_lo_ = {-aspect, -1};
        window_hi_ = {aspect, 1};
    } else {
        window_lo_ = {-1, -1 / aspect};
        window_hi_ = {1, 1 / aspect};
    }
    area_ = (window_hi_.x - window_lo_.x) * (window_hi_.y - window_lo_.y) * tan_half_ * tan_half_;
    std::vector<float> weights(texels_.size());
    double sum[3] = {0, 0, 0};
    const double dx = double(window_hi_.x - window_lo_.x) / width_,
                 dy = double(window_hi_.y - window_lo_.y) / height_;
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const double x0 = (window_lo_.x + dx * x) * tan_half_, y0 = (window_lo_.y + dy * y) * tan_half_;
            const double omega = rectangle_solid_angle(x0, x0 + dx * tan_half_, y0, y0 + dy * tan_half_);
            const size_t k = size_t(y) * size_t(width_) + size_t(x);
            weights[k] = float(texels_[k].average() * omega);
            for (int ch = 0; ch < 3; ++ch) sum[ch] += double(texels_[k][ch]) * omega;
        }
    distribution_ = Distribution2D(weights, width_, height_);
    power_ = Rgb(float(sum[0]), float(sum[1]), float(sum[2])) * scale_;
}

bool ProjectionLight::project(Vec3 local, Vec2& uv) const {
    if (!(local.z >= kHither)) return false;
    const float sx = local.x / (local.z * tan_half_), sy = local.y / (local.z * tan_half_);
    uv = {(sx - window_lo_.x) / (window_hi_.x - window_lo_.x),
          (sy - window_lo_.y) / (window_hi_.y - window_lo_.y)};
    return uv.x >= 0 && uv.x < 1 && uv.y >= 0 && uv.y < 1;
}

Rgb ProjectionLight::intensity_rgb(Vec3 w) const {
    Vec2 uv;
    if (!project(frame_.to_local(w), uv)) return Rgb(0.0f);
    const int x = std::min(int(uv.x * float(width_)), width_ - 1),
              y = std::min(int(uv.y * float(height_)), height_ - 1);
    return texels_[size_t(y) * size_t(width_) + size_t(x)] * scale_;
}

Spectrum ProjectionLight::intensity(Vec3 w, const Wavelengths& lambda) const {
    const Rgb c = intensity_rgb(w);
    if (c.max() <= 0) return Spectrum(0.0f);
    using spectrum::RgbSpectrum;
    return RgbSpectrum(c, RgbSpectrum::Use::Illuminant, RgbSpectrum::Fit::Table).sample(lambda);
}

LightLiSample ProjectionLight::sample_Li(Vec3 ref, Vec2, const Wavelengths& lambda) const {
    LightLiSample s = sample_point_Li(position_, ref);
    if (s.pdf > 0) s.L = intensity(-s.wi, lambda) / (s.distance * s.distance);
    return s;
}

void ProjectionLight::pdf_Le(Vec3, Vec3 w, float& pdf_pos, float& pdf_dir) const {
    pdf_pos = 1;
    pdf_dir = 0;
    const Vec3 local = frame_.to_local(normalize(w));
    Vec2 uv;
    if (!project(local, uv)) return;
    pdf_dir = distribution_.pdf(uv) / (area_ * local.z * local.z * local.z);
}

LightLeSample ProjectionLight::sample_Le(Vec2, Vec2 u_dir, const Wavelengths& lambda) const {
    LightLeSample s;
    float pdf_uv = 0;
    const Vec2 uv = distribution_.sample(u_dir, &pdf_uv);
    if (!(pdf_uv > 0)) return s;
    const float sx = window_lo_.x + (window_hi_.x - window_lo_.x) * uv.x;
    const float sy = window_lo_.y + (window_hi_.y - window_lo_.y) * uv.y;
    const Vec3 w = normalize(frame_.to_world(normalize(Vec3(sx * tan_half_, sy * tan_half_, 1))));
    // Density and intensity from the final direction, exactly as pdf_Le and sample_Li see it.
    float pdf_pos = 1, pdf_dir = 0;
    pdf_Le({}, w, pdf_pos, pdf_dir);
    if (!(pdf_dir > 0)) return s;
    s.ray = {position_, w};
    s.n = w;
    s.Le = intensity(w, lambda);
    s.pdf_pos = 1;
    s.pdf_dir = pdf_dir;
    s.weight = s.Le / pdf_dir;
    return s;
}

}  // namespace phos::shading
