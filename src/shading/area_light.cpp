// Area light: the shape sampler supplies points and densities; this file adds the emission
// direction rules (one- or two-sided) and the cosine-weighted photon emission.
#include "shading/area_light.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "accel/alpha_mask.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/warp.h"
#include "scene/texture_eval.h"
#include "spectrum/rgb_spectrum.h"

namespace phos::shading {

AreaLight::AreaLight(const scene::Light& light, const scene::Shape& shape,
                     const std::vector<scene::Texture>* textures)
    : Light(light), sampler_(shape), radiance_(light.color), two_sided_(light.two_sided) {
    alpha_ = shape.alpha;
    if (shape.alpha_texture >= 0 && shape.kind == scene::Shape::Kind::Mesh && textures &&
        size_t(shape.alpha_texture) < textures->size()) {
        alpha_texture_ = shape.alpha_texture;
        alpha_textures_ = std::make_unique<scene::Scene>();
        alpha_textures_->textures = *textures;
    }
    if (alpha_texture_ >= 0 || light.texture >= 0) {
        if (shape.mesh.uvs.size() == shape.mesh.positions.size()) uvs_ = shape.mesh.uvs;
        indices_ = shape.mesh.indices;
    }
    if (light.texture < 0) return;
    if (!textures || size_t(light.texture) >= textures->size())
        throw InputError("area light: texture index " + std::to_string(light.texture) + " out of range");
    const scene::Texture& tex = (*textures)[size_t(light.texture)];
    if (tex.kind != scene::Texture::Kind::Image || !tex.image || tex.image->width <= 0 ||
        tex.image->height <= 0)
        throw InputError("area light: the emission image must be an image");
    if (shape.kind != scene::Shape::Kind::Mesh) {
        accel::detail::Analytic a;
        const char* why = "";
        if (shape.kind == scene::Shape::Kind::Box || shape.kind == scene::Shape::Kind::Curves ||
            !accel::detail::make_analytic(shape, shape.area_light, a, why))
            throw InputError(
                "area light: image emission needs a surface with (u, v): a mesh, sphere, disk, "
                "cylinder or cone");
        a.source = nullptr;
        analytic_ = a;
    }
    image_ = tex.image;
    double sum[3] = {0, 0, 0};
    for (const Rgb& c : image_->texels)
        for (int k = 0; k < 3; ++k) sum[k] += std::max(c[k], 0.0f);
    const double count = double(image_->texels.size());
    image_mean_ = Rgb(float(sum[0] / count), float(sum[1] / count), float(sum[2] / count));
}

Rgb AreaLight::radiance_rgb(Vec2 uv) const {
    if (!image_) return radiance_;
    // pbrt-v4's Bilerp at (u, 1 - v) with clamped edges: pixel centres at (i + 0.5) / width.
    const int w = image_->width, h = image_->height;
    const float x = uv.x * float(w) - 0.5f, y = (1 - uv.y) * float(h) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float dx = x - fx, dy = y - fy;
    auto at = [&](int i, int j) {
        const Rgb c = image_->at(std::clamp(i, 0, w - 1), std::clamp(j, 0, h - 1));
        return Rgb(std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f));
    };
    const int x0 = int(fx), y0 = int(fy);
    const Rgb c = at(x0, y0) * ((1 - dx) * (1 - dy)) + at(x0 + 1, y0) * (dx * (1 - dy)) +
                  at(x0, y0 + 1) * ((1 - dx) * dy) + at(x0 + 1, y0 + 1) * (dx * dy);
    return c * radiance_;
}

Vec2 AreaLight::sample_uv(const ShapeSample& s) const {
    if (analytic_) {
        // The sampled point's place on the canonical shape; on a capped cylinder or cone, a cap
        // when it lies off the side's radius.
        using accel::detail::D3;
        const accel::detail::Analytic& a = *analytic_;
        accel::detail::CanonicalHit hit;
        hit.p = a.to_canon.point(D3(s.p.x, s.p.y, s.p.z));
        hit.part = accel::detail::kSide;
        if (a.capped && (a.kind == scene::Shape::Kind::Cylinder || a.kind == scene::Shape::Kind::Cone)) {
            const double rho = std::sqrt(hit.p.x * hit.p.x + hit.p.y * hit.p.y);
            const double side = a.kind == scene::Shape::Kind::Cone
                                    ? a.radius / a.height * (0.5 * a.height - hit.p.z)
                                    : a.radius;
            if (std::fabs(rho - side) > 1e-4 * a.radius)
                hit.part = hit.p.z > 0 ? accel::detail::kCapTop : accel::detail::kCapBottom;
        }
        return accel::detail::analytic_surface(a, hit, 0).uv;
    }
    if (s.triangle < 0) return {0, 0};
    const Vec2 b = s.barycentric;
    if (uvs_.empty()) return b;  // the accel layer's uv of a mesh without uvs
    const uint32_t* idx = &indices_[3 * size_t(s.triangle)];
    return uvs_[idx[0]] * (1 - b.x - b.y) + uvs_[idx[1]] * b.x + uvs_[idx[2]] * b.y;
}

bool AreaLight::alpha_masked(Vec3 p, const ShapeSample& s) const {
    if (alpha_texture_ < 0 && alpha_ >= 1) return false;
    const float a = alpha_texture_ >= 0
                        ? scene::eval_texture(*alpha_textures_, alpha_texture_, sample_uv(s)).average()
                        : alpha_;
    if (a >= 1) return false;
    if (!(a > 0)) return true;
    return accel::alpha_hash(p, Vec3(0.0f), 0) > a;
}

Spectrum AreaLight::Le(Vec3 n, Vec3 wo, const Wavelengths& lambda) const {
    if (!(two_sided_ || dot(n, wo) > 0)) return Spectrum(0.0f);
    if (!image_) return emission(lambda);
    using spectrum::RgbSpectrum;
    return RgbSpectrum(image_mean_ * radiance_, RgbSpectrum::Use::Illuminant, RgbSpectrum::Fit::Table)
        .sample(lambda);
}

Spectrum AreaLight::surface_Le(Vec3 n, Vec2 uv, Vec3 wo, const Wavelengths& lambda) const {
    if (!image_) return Le(n, wo, lambda);
    if (!(two_sided_ || dot(n, wo) > 0)) return Spectrum(0.0f);
    const Rgb c = radiance_rgb(uv);
    if (!(c.max() > 0)) return Spectrum(0.0f);
    using spectrum::RgbSpectrum;
    return RgbSpectrum(c, RgbSpectrum::Use::Illuminant, RgbSpectrum::Fit::Table).sample(lambda);
}

Rgb AreaLight::power() const {
    const Rgb L = image_ ? image_mean_ * radiance_ : radiance_;
    return L * (kPi * sampler_.area() * (two_sided_ ? 2.0f : 1.0f));
}

LightLiSample AreaLight::sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const {
    LightLiSample s;
    const ShapeSample ss = sampler_.sample(ref, u);
    if (!(ss.pdf > 0) || alpha_masked(ss.p, ss)) return s;
    const Vec3 d = ss.p - ref;
    const float dist = length(d);
    if (!(dist > 0)) return s;
    s.wi = d / dist;
    s.distance = dist;
    s.p_light = ss.p;
    s.n_light = ss.n;
    s.pdf = ss.pdf;
    s.L = surface_Le(ss.n, sample_uv(ss), -s.wi, lambda);
    return s;
}

float AreaLight::pdf_Li(Vec3 ref, Vec3 wi, Vec3 p_light, Vec3 n_light) const {
    return sampler_.pdf(ref, wi, p_light, n_light);
}

void AreaLight::pdf_Le(Vec3 n, Vec3 w, float& pdf_pos, float& pdf_dir) const {
    pdf_pos = sampler_.area() > 0 ? 1 / sampler_.area() : 0;
    const float c = dot(n, w);
    pdf_dir = two_sided_ ? 0.5f * std::fabs(c) / kPi : std::max(c, 0.0f) / kPi;
}

LightLeSample AreaLight::sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const {
    LightLeSample s;
    const ShapeSample ss = sampler_.sample_area(u_pos);
    if (!(ss.pdf > 0) || alpha_masked(ss.p, ss)) return s;
    Vec3 n = ss.n;
    float side_pdf = 1;
    if (two_sided_) {
        // Reuse u_dir.x: its lower half picks the front, the upper half the back.
        side_pdf = 0.5f;
        if (u_dir.x < 0.5f) {
            u_dir.x *= 2;
        } else {
            u_dir.x = std::min(2 * u_dir.x - 1, std::nextafter(1.0f, 0.0f));
            n = -n;
            s.back = true;
        }
    }
    const Vec3 local = warp::cosine_hemisphere(u_dir);
    const Vec3 w = Frame(n).to_world(local);
    // The ray starts on the emitting surface: skip that surface itself (a relative epsilon, as for
    // spawned rays), or the photon would "hit" its own light at t = 0.
    const float extent = std::max(std::fabs(ss.p.x), std::max(std::fabs(ss.p.y), std::fabs(ss.p.z)));
    s.ray = {ss.p, w, 1e-5f * (1 + extent)};
    s.n = n;
    s.Le = image_ ? surface_Le(n, sample_uv(ss), w, lambda) : emission(lambda);
    s.pdf_pos = ss.pdf;
    s.pdf_dir = warp::cosine_hemisphere_pdf(local.z) * side_pdf;
    // L |cos| / (pdf_pos pdf_dir), which is L pi A / side_pdf; a grazing direction (cos = 0) takes
    // that limit instead of 0/0.
    s.weight = s.pdf_dir > 0 ? s.Le * (local.z / (s.pdf_pos * s.pdf_dir))
                             : s.Le * (kPi * sampler_.area() / side_pdf);
    return s;
}

}  // namespace phos::shading
