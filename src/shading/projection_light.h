// Projection light (pbrt-v4's ProjectionLight): a point light that projects an RGB image like a
// slide projector. In the light space of scene::Light::to_world (the builder composes pbrt-v4's flip
// of y into it) the light looks down +z; a direction w with w.z >= 1e-3 meets the plane z = 1 at
// (w.x, w.y) / w.z, which is scaled by 1 / tan(fov / 2) into the screen window [-a, a] x [-1, 1]
// (a = width / height >= 1; [-1, 1] x [-1/a, 1/a] for a tall image), row 0 at the window's -y
// edge. The intensity is the nearest pixel's RGB (read as an illuminant) times `color`.
//
// Photons pick a pixel from a piecewise-constant distribution over the window weighted by the
// pixel's flux (channel average times its exact solid angle, the closed form for a rectangle on the
// plane z = 1), then a point uniformly in it: with A the window's area on that plane,
// pdf_dir = pdf_uv / (A cos^3) (dw = cos^3 dA there). Flux = sum over pixels of I x solid angle
// (pbrt-v4's Phi takes cos^3 at the pixel centre instead; the builder's "power" follows pbrt-v4).
#pragma once

#include <vector>

#include "core/frame.h"
#include "shading/distribution2d.h"
#include "shading/lights.h"

namespace phos::shading {

class ProjectionLight final : public Light {
public:
    // Throws InputError when the image is missing or the field of view is not in (0, pi).
    ProjectionLight(const scene::Light& light, const std::vector<scene::Texture>& textures);
    LightLiSample sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const override;
    float pdf_Li(Vec3, Vec3, Vec3, Vec3) const override { return 0; }
    Spectrum Le(Vec3, Vec3, const Wavelengths&) const override { return Spectrum(0.0f); }
    LightLeSample sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const override;
    void pdf_Le(Vec3 n, Vec3 w, float& pdf_pos, float& pdf_dir) const override;
    Rgb power() const override { return power_; }
    bool is_delta() const override { return true; }

    // The intensity's colour in world direction `w` (unit, leaving the light); 0 outside the image.
    Rgb intensity_rgb(Vec3 w) const;

private:
    // The window point (u, v) in [0,1)^2 a light-space direction projects to; false outside.
    bool project(Vec3 local, Vec2& uv) const;
    Spectrum intensity(Vec3 w, const Wavelengths& lambda) const;

    Vec3 position_;
    Frame frame_;  // light space -> world
    Rgb scale_;
    int width_ = 0, height_ = 0;
    std::vector<Rgb> texels_;
    float tan_half_ = 1;          // tan(fov / 2)
    Vec2 window_lo_, window_hi_;  // the screen window
    float area_ = 0;              // the window's area on the plane z = 1
    Distribution2D distribution_;
    Rgb power_{0.0f};
};

}  // namespace phos::shading
