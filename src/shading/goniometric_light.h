// Goniometric light (pbrt-v4's GoniometricLight): a point light whose intensity over directions is
// I times a grey equal-area map (shading/equal_area_map.h; an RGB image is read as its channels'
// average, as pbrt-v4 does), looked up in the light space of scene::Light::to_world (the builder
// composes pbrt-v4's swap of y and z into it). Flux 4 pi I mean(map); photons leave in proportion
// to the map (sampled by its pixel distribution, pdf_dir = pdf_uv / (4 pi)).
#pragma once

#include <vector>

#include "core/frame.h"
#include "shading/equal_area_map.h"
#include "shading/lights.h"

namespace phos::shading {

class GoniometricLight final : public Light {
public:
    // Throws InputError when the image is missing or not square.
    GoniometricLight(const scene::Light& light, const std::vector<scene::Texture>& textures);
    LightLiSample sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const override;
    float pdf_Li(Vec3, Vec3, Vec3, Vec3) const override { return 0; }
    Spectrum Le(Vec3, Vec3, const Wavelengths&) const override { return Spectrum(0.0f); }
    LightLeSample sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const override;
    void pdf_Le(Vec3 n, Vec3 w, float& pdf_pos, float& pdf_dir) const override;
    Rgb power() const override { return intensity_ * (4 * kPi * map_.mean().r); }
    bool is_delta() const override { return true; }

    // The map's grey value in world direction `w` (unit, leaving the light).
    float profile(Vec3 w) const { return map_.lookup(frame_.to_local(w)).r; }

private:
    Vec3 position_;
    Frame frame_;  // light space -> world
    Rgb intensity_;
    EqualAreaMap map_;  // grey: r = g = b
};

}  // namespace phos::shading
