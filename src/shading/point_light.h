// Isotropic point light of intensity I (W/sr): irradiance I cos / d^2, flux 4 pi I.
#pragma once

#include "shading/lights.h"

namespace phos::shading {

class PointLight final : public Light {
public:
    PointLight(const scene::Light& light, const LightOptions& options);
    LightLiSample sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const override;
    float pdf_Li(Vec3, Vec3, Vec3, Vec3) const override { return 0; }
    Spectrum Le(Vec3, Vec3, const Wavelengths&) const override { return Spectrum(0.0f); }
    LightLeSample sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const override;
    void pdf_Le(Vec3, Vec3, float& pdf_pos, float& pdf_dir) const override {
        pdf_pos = 1;
        pdf_dir = 1 / (4 * kPi);
    }
    Rgb power() const override { return intensity_ * (4 * kPi); }
    bool is_delta() const override { return true; }

private:
    Vec3 position_;
    Rgb intensity_;
    bool legacy_ = false;
    Vec3 attenuation_{0, 0, 1};
};

// Fall-off of a point or spot light at distance d: 1/d^2, or 1/(ca + la d + qa d^2) with the
// legacy .scn attenuation (a direct-lighting-only approximation; photons always use 1/d^2).
float distance_falloff(float d, bool legacy, Vec3 attenuation);

// sample_Li of a light at the point `position` (point and spot lights): the delta sample towards it
// from `ref` with pdf 1, or pdf 0 when `ref` sits on the light. L is left for the light to set.
LightLiSample sample_point_Li(Vec3 position, Vec3 ref);

}  // namespace phos::shading
