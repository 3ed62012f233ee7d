// Environment light at infinity: constant radiance, a lat-long radiance map importance-sampled
// in proportion to luminance, or pbrt-v4's square equal-area map (shading/equal_area_map.h: nearest
// lookup, sampled by the pixels' channel average, solid-angle pdf = pdf_uv / (4 pi)).
//
// Equal-area convention (pbrt-v4's ImageInfiniteLight): a world direction is taken to light space
// as below and mapped to the square by Clarberg's octahedral map (core/equal_area.h), u the column
// (left to right) and v the row (row 0 at the top).
//
// With a portal (scene::Light::portal; pbrt-v4's PortalImageInfiniteLight) the environment, whichever
// of the three it is, is resampled once into the portal's frame (shading/light_portal.h): the
// radiance is that image's nearest pixel for directions in front of the portal's plane (0 behind
// it), sample_Li draws directions through the portal rectangle from the reference point, and
// photons start on the portal. The resampled image has the equal-area map's N x N pixels, a lat-long
// map's (W / 2) x H, and one pixel for a constant.
//
// Map convention (pbrt-v3's lat-long): a world direction is first taken to light space with the
// inverse of the light's `to_world` (its linear part orthonormalised: only its rotation / mirroring
// counts); there theta is measured from +z and phi = atan2(y, x) in [0, 2 pi) around z, and the
// texel lookup uses u = phi / (2 pi) (column, left to right) and v = theta / pi (row, row 0 = top =
// +z). Texels are piecewise constant (nearest lookup), so the sampling density matches the
// radiance exactly: within a texel, directions are uniform in solid angle.
#pragma once

#include <vector>

#include "core/frame.h"
#include "shading/distribution2d.h"
#include "shading/equal_area_map.h"
#include "shading/light_portal.h"
#include "shading/lights.h"

namespace phos::shading {

class InfiniteLight final : public Light {
public:
    // Constant radiance L (`texture` < 0 or a Constant texture) or a lat-long map; the light's colour
    // multiplies the map. Throws InputError on a bad texture reference.
    InfiniteLight(const scene::Light& light, const std::vector<scene::Texture>& textures,
                  const SceneSphere& sphere);
    LightLiSample sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const override;
    float pdf_Li(Vec3 ref, Vec3 wi, Vec3 p_light, Vec3 n_light) const override;
    // Radiance arriving from direction `w` (pointing from the scene towards the sky); `n` unused.
    Spectrum Le(Vec3 n, Vec3 w, const Wavelengths& lambda) const override;
    // With a portal: 0 unless the ray from `origin` along `w` passes through the portal rectangle.
    Spectrum escaped_Le(Vec3 origin, Vec3 w, const Wavelengths& lambda) const override;
    // The radiance's colour from direction `w` (what the map holds, times the scale).
    Rgb Le_rgb(Vec3 w) const;
    // Direction as for sample_Li, origin uniform on a disk of the scene radius R perpendicular to it
    // outside the scene; power = pi R^2 * integral of L over the sphere.
    LightLeSample sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const override;
    void pdf_Le(Vec3 n, Vec3 w, float& pdf_pos, float& pdf_dir) const override;
    Rgb power() const override;
    bool is_delta() const override { return false; }
    bool is_infinite() const override { return true; }

    // Integral of the radiance over the sphere of directions (4 pi L when constant).
    Rgb integral() const { return integral_; }
    // Solid-angle density of sample_Li's directions without a portal (independent of the reference
    // point); with one, that of photons' sky directions.
    float pdf_direction(Vec3 w) const;
    // The portal (empty without one).
    const LightPortal& portal() const { return portal_; }

private:
    Vec3 sample_direction(Vec2 u) const;
    // Resamples the environment into the portal's frame when the light has one.
    void make_portal(const scene::Light& light);
    // Texel (column, row) of a light-space unit direction.
    void cell(Vec3 local, int& column, int& row, Vec2& uv) const;

    Frame frame_;                      // light space -> world
    Rgb scale_;                        // constant radiance, or the multiplier of the map
    spectrum::Distribution constant_;  // the constant radiance's spectrum
    int width_ = 0, height_ = 0;       // 0: constant
    std::vector<Rgb> texels_;
    std::vector<float> cos_edge_;  // cos(theta) at the row edges, height_ + 1 values from 1 to -1
    Distribution2D distribution_;  // luminance x solid angle of each texel
    EqualAreaMap equal_area_;      // the map when it is an equal-area one (width_ = height_ = 0)
    LightPortal portal_;           // pbrt-v4's portal: the environment seen through it
    Rgb integral_;
    SceneSphere sphere_;
};

}  // namespace phos::shading
