// Environment light. Each texel's weight is luminance x its solid angle (2 pi / W) (cos_j - cos_j+1),
// so the 2D distribution picks texels in proportion to the flux they send; inside the chosen texel
// the direction is uniform in phi and in cos(theta), i.e. uniform in solid angle. The solid-angle
// pdf is therefore P(texel) / solid angle(texel) = pdf_uv / (2 pi H (cos_j - cos_j+1)).
#include "shading/infinite_light.h"

#include <array>
#include <cmath>
#include <string>

#include "core/equal_area.h"
#include "core/error.h"
#include "core/warp.h"

namespace phos::shading {
InfiniteLight::InfiniteLight(const scene::Light& light, const std::vector<scene::Texture>& textures,
                             const SceneSphere& sphere)
    : Light(light), frame_(light_frame(light.to_world)), scale_(light.color), sphere_(sphere) {
    if (!light.portal.empty() && light.portal.size() != 4)
        throw InputError("infinite light: a portal takes four points");
    if (light.texture >= 0) {
        if (size_t(light.texture) >= textures.size())
            throw InputError("infinite light: texture index " + std::to_string(light.texture) +
                             " out of range");
        const scene::Texture& tex = textures[size_t(light.texture)];
        scale_ = scale_ * tex.value;
        if (tex.kind == scene::Texture::Kind::Image) {
            if (!tex.image || tex.image->width <= 0 || tex.image->height <= 0)
                throw InputError("infinite light: environment map '" + tex.filename + "' has no pixels");
            width_ = tex.image->width;
            height_ = tex.image->height;
        } else if (tex.kind != scene::Texture::Kind::Constant) {
            throw InputError("infinite light: texture must be an image or a constant");
        }
        if (width_ > 0 && light.equal_area) {
            if (width_ != height_)
                throw InputError("infinite light: equal-area map '" + tex.filename + "' is not square");
            equal_area_ = EqualAreaMap(tex.image->texels, width_);
            width_ = height_ = 0;
            integral_ = equal_area_.hemisphere_integral() * scale_;
            make_portal(light);
            return;
        }
        if (width_ > 0) {
            texels_ = tex.image->texels;
            for (Rgb& c : texels_)
                for (int k = 0; k < 3; ++k) c[k] = std::isfinite(c[k]) ? std::max(c[k], 0.0f) : 0.0f;
        }
    }
    if (width_ == 0) {
        integral_ = scale_ * (4 * kPi);
        constant_ = light.spectrum
                        ? light.spectrum->scaled(light.color.max() > 0 ? scale_.max() / light.color.max() : 0)
                        : spectrum::Distribution::rgb(scale_, spectrum::RgbSpectrum::Use::Illuminant);
        make_portal(light);
        return;
    }
    cos_edge_.resize(size_t(height_) + 1);
    for (int j = 0; j <= height_; ++j) cos_edge_[size_t(j)] = std::cos(kPi * float(j) / float(height_));
    cos_edge_.front() = 1;
    cos_edge_.back() = -1;
    std::vector<float> weights(texels_.size());
    double sum[3] = {0, 0, 0};
    for (int j = 0; j < height_; ++j) {
        const double omega =
            2 * double(kPi) / width_ * (double(cos_edge_[size_t(j)]) - cos_edge_[size_t(j) + 1]);
        for (int i = 0; i < width_; ++i) {
            const size_t k = size_t(j) * size_t(width_) + size_t(i);
            const Rgb c = texels_[k] * scale_;
            weights[k] = float(c.luminance() * omega);
            for (int ch = 0; ch < 3; ++ch) sum[ch] += c[ch] * omega;
        }
    }
    integral_ = Rgb(float(sum[0]), float(sum[1]), float(sum[2]));
    distribution_ = Distribution2D(weights, width_, height_);
    make_portal(light);
}

namespace {

// pbrt-v4's bilinear lookup of an equal-area map at (u, v) with the octahedral-sphere wrap.
Rgb bilinear(const EqualAreaMap& map, Vec2 uv) {
    const int n = map.resolution();
    const float x = uv.x * float(n) - 0.5f, y = uv.y * float(n) - 0.5f;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const float dx = x - float(x0), dy = y - float(y0);
    return map.texel_wrapped(x0, y0) * ((1 - dx) * (1 - dy)) +
           map.texel_wrapped(x0 + 1, y0) * (dx * (1 - dy)) + map.texel_wrapped(x0, y0 + 1) * ((1 - dx) * dy) +
           map.texel_wrapped(x0 + 1, y0 + 1) * (dx * dy);
}

}  // namespace

void InfiniteLight::make_portal(const scene::Light& light) {
    if (light.portal.empty()) return;
    const std::array<Vec3, 4> corners{light.portal[0], light.portal[1], light.portal[2], light.portal[3]};
    if (!equal_area_.empty()) {
        const int n = equal_area_.resolution();
        portal_ = LightPortal(corners, n, n, [&](Vec3 w) {
            return bilinear(equal_area_, equal_area_sphere_to_square(frame_.to_local(normalize(w)))) * scale_;
        });
    } else if (width_ > 0) {
        portal_ = LightPortal(corners, std::max(width_ / 2, 1), height_, [&](Vec3 w) { return Le_rgb(w); });
    } else {
        portal_ = LightPortal(corners, 1, 1, [&](Vec3) { return scale_; });
    }
    integral_ = portal_.integral();
}

Rgb InfiniteLight::power() const {
    if (!portal_.empty()) return portal_.flux();
    return integral_ * (kPi * sphere_.radius * sphere_.radius);
}

void InfiniteLight::cell(Vec3 w, int& column, int& row, Vec2& uv) const {
    const float theta = std::acos(std::clamp(w.z, -1.0f, 1.0f));
    float phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    uv = {std::min(phi / (2 * kPi), std::nextafter(1.0f, 0.0f)),
          std::min(theta / kPi, std::nextafter(1.0f, 0.0f))};
    column = std::min(int(uv.x * float(width_)), width_ - 1);
    row = std::min(int(uv.y * float(height_)), height_ - 1);
}

Spectrum InfiniteLight::Le(Vec3, Vec3 w, const Wavelengths& lambda) const {
    if (width_ == 0 && equal_area_.empty() && portal_.empty()) return constant_.sample(lambda);
    return spectrum::RgbSpectrum(Le_rgb(w), spectrum::RgbSpectrum::Use::Illuminant,
                                 spectrum::RgbSpectrum::Fit::Table)
        .sample(lambda);
}

Spectrum InfiniteLight::escaped_Le(Vec3 origin, Vec3 w, const Wavelengths& lambda) const {
    if (!portal_.empty()) {
        const std::optional<Vec2> uv = portal_.uv_of(normalize(w));
        const std::optional<UvWindow> win = portal_.window(origin);
        if (!uv || !win || !win->contains(*uv)) return Spectrum(0.0f);
    }
    return Le({}, w, lambda);
}

Rgb InfiniteLight::Le_rgb(Vec3 w) const {
    if (!portal_.empty()) return portal_.radiance(normalize(w));
    if (!equal_area_.empty()) return equal_area_.lookup(frame_.to_local(normalize(w))) * scale_;
    if (width_ == 0) return scale_;
    int i, j;
    Vec2 uv;
    cell(frame_.to_local(normalize(w)), i, j, uv);
    return texels_[size_t(j) * size_t(width_) + size_t(i)] * scale_;
}

float InfiniteLight::pdf_direction(Vec3 w) const {
    if (!portal_.empty()) {
        float pdf_pos = 0, pdf_dir = 0;
        portal_.pdf_emission(normalize(w), pdf_pos, pdf_dir);
        return pdf_dir;
    }
    if (!equal_area_.empty()) return equal_area_.pdf(frame_.to_local(normalize(w)));
    if (width_ == 0) return warp::uniform_sphere_pdf();
    int i, j;
    Vec2 uv;
    cell(frame_.to_local(normalize(w)), i, j, uv);
    const float band = cos_edge_[size_t(j)] - cos_edge_[size_t(j) + 1];
    return distribution_.pdf(uv) / (2 * kPi * float(height_) * band);
}

Vec3 InfiniteLight::sample_direction(Vec2 u) const {
    if (!equal_area_.empty()) {
        float pdf = 0;  // recomputed from the final direction by the callers
        return frame_.to_world(equal_area_.sample(u, &pdf));
    }
    if (width_ == 0) return warp::uniform_sphere(u);
    float pdf_uv = 0;
    const Vec2 uv = distribution_.sample(u, &pdf_uv);
    const int row = std::min(int(uv.y * float(height_)), height_ - 1);
    // Uniform in cos(theta) inside the row (uniform in solid angle), uniform in phi.
    const float frac = std::clamp(uv.y * float(height_) - float(row), 0.0f, 1.0f);
    const float c0 = cos_edge_[size_t(row)], c1 = cos_edge_[size_t(row) + 1];
    const float z = c0 + frac * (c1 - c0);
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const float phi = 2 * kPi * uv.x;
    return frame_.to_world({r * std::cos(phi), r * std::sin(phi), z});
}

LightLiSample InfiniteLight::sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const {
    LightLiSample s;
    Vec3 w;
    if (!portal_.empty()) {
        // pbrt-v4: a direction through the portal from ref, its pdf from the sampled (u, v).
        const std::optional<Vec3> through = portal_.sample_towards(ref, u, &s.pdf);
        if (!through) return {};
        w = *through;
    } else {
        w = normalize(sample_direction(u));
        // Density and radiance are looked up from the final direction, exactly as pdf_Li and Le do.
        s.pdf = pdf_direction(w);
    }
    if (!(s.pdf > 0)) return {};
    s.wi = w;
    s.L = Le({}, w, lambda);
    s.distance = kInf;
    s.p_light = ref + w * (2 * (sphere_.radius + length(ref - sphere_.center)) + 1);
    s.n_light = -w;
    return s;
}

float InfiniteLight::pdf_Li(Vec3 ref, Vec3 wi, Vec3, Vec3) const {
    if (!portal_.empty()) return portal_.pdf_towards(ref, wi);
    return pdf_direction(wi);
}

void InfiniteLight::pdf_Le(Vec3, Vec3 w, float& pdf_pos, float& pdf_dir) const {
    if (!portal_.empty()) {
        portal_.pdf_emission(-w, pdf_pos, pdf_dir);
        return;
    }
    const float R = sphere_.radius;
    pdf_pos = R > 0 ? 1 / (kPi * R * R) : 0;
    pdf_dir = pdf_direction(-w);  // light travelling along w comes from the sky direction -w
}

LightLeSample InfiniteLight::sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const {
    LightLeSample s;
    if (!portal_.empty()) {
        // Photons start on the portal and travel into the scene (light_portal.h).
        const std::optional<LightPortal::Emission> e = portal_.sample_emission(u_pos, u_dir);
        if (!e) return s;
        s.ray = {e->origin, -e->w};
        s.n = -e->w;
        s.Le = Le({}, e->w, lambda);
        s.pdf_pos = e->pdf_pos;
        s.pdf_dir = e->pdf_dir;
        s.weight = s.Le / (s.pdf_pos * s.pdf_dir);
        return s;
    }
    const Vec3 w = normalize(sample_direction(u_dir));
    const float pdf_dir = pdf_direction(w);
    const float R = sphere_.radius;
    if (!(pdf_dir > 0) || !(R > 0)) return s;
    const Frame f(w);
    const Vec2 d = warp::concentric_disk(u_pos);
    s.ray = {sphere_.center + (w + f.s * d.x + f.t * d.y) * R, -w};
    s.n = -w;
    s.Le = Le({}, w, lambda);
    s.pdf_pos = 1 / (kPi * R * R);
    s.pdf_dir = pdf_dir;
    s.weight = s.Le / (s.pdf_pos * s.pdf_dir);
    return s;
}

}  // namespace phos::shading
