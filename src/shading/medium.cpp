// Runtime media: coefficients and majorant segments (see medium.h).
#include "shading/medium.h"

#include <algorithm>

namespace phos::shading {

Medium::Medium(const scene::Medium& m)
    : sigma_a_(m.sigma_a * m.scale),
      sigma_s_(m.sigma_s * m.scale),
      phase_{m.g},
      to_medium_(m.to_world.inverse()) {
    using spectrum::RgbSpectrum;
    sigma_a_s_ = RgbSpectrum(sigma_a_, RgbSpectrum::Use::Unbounded);
    sigma_s_s_ = RgbSpectrum(sigma_s_, RgbSpectrum::Use::Unbounded);
    // The spectra are smooth: their largest sum on a 1 nm grid, with a margin for in between
    // (none for grey coefficients, whose spectra are flat: a grey medium's walk then scatters at
    // its first collision, medium_tracking.h).
    for (float l = spectrum::kLambdaMin; l <= spectrum::kLambdaMax; l += 1.0f)
        max_sigma_t_ = std::max(max_sigma_t_, sigma_a_s_(l) + sigma_s_s_(l));
    const auto grey = [](Rgb c) { return c.r == c.g && c.g == c.b; };
    if (!grey(sigma_a_) || !grey(sigma_s_)) max_sigma_t_ *= 1.001f;
    grid_ = make_density_grid(m);
    Le_ = m.emission;
    Le_s_ = RgbSpectrum(Le_, RgbSpectrum::Use::Illuminant);
    if (grid_) {
        majorant_grid_ = std::make_unique<MajorantGrid>(*grid_);
        if (!m.emission_scale.empty() && !Le_.is_black()) {
            // The emission factors live on the density's cells: the same grid class reads them.
            scene::Medium scale;
            scale.name = m.name + " (Lescale)";
            scale.kind = m.kind;
            scale.nx = m.nx, scale.ny = m.ny, scale.nz = m.nz;
            scale.p0 = m.p0, scale.p1 = m.p1;
            scale.density = m.emission_scale;
            le_scale_ = make_density_grid(scale);
        }
    }
}

Medium::~Medium() = default;
Medium::Medium(Medium&&) noexcept = default;

MediumCoefficients Medium::at(Vec3 p, const Wavelengths& lambda) const {
    const Spectrum sa = sigma_a_s_.sample(lambda), ss = sigma_s_s_.sample(lambda);
    const Spectrum le = Le_s_.sample(lambda);
    if (!grid_) return {sa, ss, le};
    const Vec3 q = to_medium_.point(p);
    const float d = grid_->density(q);
    // Emission sigma_a(p) Le(p): through sigma_a it follows the density, times the Lescale grid.
    return {sa * d, ss * d, le_scale_ ? le * le_scale_->density(q) : le};
}

Rgb Medium::sigma_t_rgb(Vec3 p) const {
    const Rgb s = sigma_a_ + sigma_s_;
    return grid_ ? s * grid_->density(to_medium_.point(p)) : s;
}

Medium::Majorants Medium::majorants(Vec3 o, Vec3 d, float t0, float t1) const {
    Majorants it;
    it.t0_ = t0, it.t1_ = t1;
    if (!grid_) {
        it.single_ = true;
        it.sigma_ = max_sigma_t_;
        it.done_ = !(t1 > t0);
        return it;
    }
    it.single_ = false;
    it.sigma_ = max_sigma_t_;
    it.cells_ = majorant_grid_->segments(to_medium_.point(o), to_medium_.vector(d), t0, t1);
    return it;
}

bool Medium::Majorants::next(float& ta, float& tb, float& sigma_maj) {
    if (single_) {
        if (done_) return false;
        done_ = true;
        ta = t0_, tb = t1_, sigma_maj = sigma_;
        return true;
    }
    float dmax = 0;
    if (!cells_.next(ta, tb, dmax)) return false;
    sigma_maj = sigma_ * dmax;
    return true;
}

MediaSet::MediaSet(const scene::Scene& scene) {
    media_.reserve(scene.media.size());
    for (const scene::Medium& m : scene.media) media_.emplace_back(m);
    const auto valid = [&](int i) { return i >= 0 && size_t(i) < media_.size(); };
    active_ = valid(scene.camera_medium);
    for (const scene::Light& l : scene.lights) active_ |= valid(l.medium);
    for (const scene::Shape& s : scene.shapes) active_ |= valid(s.media.inside) || valid(s.media.outside);
    for (const scene::Object& o : scene.objects)
        for (const scene::Shape& s : o.shapes) active_ |= valid(s.media.inside) || valid(s.media.outside);
}

}  // namespace phos::shading
