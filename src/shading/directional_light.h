// Directional light: parallel light travelling along `direction` with irradiance E (W/m^2) on a
// surface facing it. Photons leave a disk of the scene's bounding radius R outside the scene, so
// its power is E pi R^2 (the flux that can reach the scene).
#pragma once

#include "core/frame.h"
#include "shading/lights.h"

namespace phos::shading {

class DirectionalLight final : public Light {
public:
    DirectionalLight(const scene::Light& light, const SceneSphere& sphere);
    LightLiSample sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const override;
    float pdf_Li(Vec3, Vec3, Vec3, Vec3) const override { return 0; }
    Spectrum Le(Vec3, Vec3, const Wavelengths&) const override { return Spectrum(0.0f); }
    LightLeSample sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const override;
    void pdf_Le(Vec3, Vec3, float& pdf_pos, float& pdf_dir) const override {
        pdf_pos = sphere_.radius > 0 ? 1 / (kPi * sphere_.radius * sphere_.radius) : 0;
        pdf_dir = 1;
    }
    Rgb power() const override { return irradiance_ * (kPi * sphere_.radius * sphere_.radius); }
    bool is_delta() const override { return true; }

private:
    Frame frame_;  // n = the direction of travel
    Rgb irradiance_;
    SceneSphere sphere_;
};

}  // namespace phos::shading
