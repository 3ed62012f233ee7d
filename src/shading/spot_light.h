// Spot light: intensity I on its axis, cos^dropoff fall-off inside the cutoff cone (the .scn
// model), or pbrt-v4's smoothstep between cos(cutoff) and cos(falloff_start) when falloff_start >= 0.
#pragma once

#include "core/frame.h"
#include "shading/lights.h"

namespace phos::shading {

class SpotLight final : public Light {
public:
    SpotLight(const scene::Light& light, const LightOptions& options);
    LightLiSample sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const override;
    float pdf_Li(Vec3, Vec3, Vec3, Vec3) const override { return 0; }
    Spectrum Le(Vec3, Vec3, const Wavelengths&) const override { return Spectrum(0.0f); }
    // Directions are drawn exactly in proportion to the angular fall-off, so every sample carries
    // the same weight (= power()).
    LightLeSample sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const override;
    void pdf_Le(Vec3 n, Vec3 w, float& pdf_pos, float& pdf_dir) const override;
    Rgb power() const override;
    bool is_delta() const override { return true; }

    // Angular fall-off in [0, 1] for cos(angle to the axis).
    float falloff(float cos_theta) const;
    // Solid-angle density of sample_Le's directions at cos(angle to the axis) = z.
    float direction_pdf(float z) const;
    Vec3 axis() const { return frame_.n; }

private:
    Vec3 position_;
    Frame frame_;  // n = the axis
    Rgb intensity_;
    float cos_cutoff_ = 0;  // cos^n model: directions with cos < this get nothing
    float exponent_ = 0;    // dropoff n
    bool smooth_ = false;   // pbrt smoothstep model
    float cos_start_ = 1;   // smoothstep: full intensity for cos >= this
    bool legacy_ = false;
    Vec3 attenuation_{0, 0, 1};
};

}  // namespace phos::shading
