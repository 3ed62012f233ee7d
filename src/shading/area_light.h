// Diffuse area light: uniform radiance L leaving one side of a shape (the side its emitting normal
// faces, see shape_sampler.h) or both sides when two-sided. Flux pi L A (doubled when two-sided).
//
// With an image (scene::Light::texture, pbrt-v4's DiffuseAreaLight "filename") the radiance at a
// surface point is the image looked up bilinearly at the point's (u, 1 - v) (clamped at the edges,
// as pbrt-v4) times `color`, read as an illuminant; the flux is pi A times the image's mean (the
// surface's uv assumed to cover the image without distortion, as pbrt-v4 assumes). The (u, v) is
// the surface's own: a mesh's uvs (or its triangles' parameterisation), and on spheres, disks,
// cylinders and cones what the accel layer gives their hits (accel/analytic.h, pbrt's (u, v) for
// pbrt's shapes), computed for sampled points from their place on the shape; points are sampled by
// area (or solid angle) as without an image.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "accel/analytic.h"
#include "scene/scene.h"
#include "scene/texture.h"
#include "shading/lights.h"
#include "shading/shape_sampler.h"

namespace phos::shading {

class AreaLight final : public Light {
public:
    // `textures` holds the image when light.texture >= 0 (an InputError if it does not, or if the
    // shape is a box, which has no (u, v)).
    AreaLight(const scene::Light& light, const scene::Shape& shape,
              const std::vector<scene::Texture>* textures = nullptr);
    LightLiSample sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const override;
    float pdf_Li(Vec3 ref, Vec3 wi, Vec3 p_light, Vec3 n_light) const override;
    // With an image, Le without a surface point is the image's mean.
    Spectrum Le(Vec3 n, Vec3 wo, const Wavelengths& lambda) const override;
    Spectrum surface_Le(Vec3 n, Vec2 uv, Vec3 wo, const Wavelengths& lambda) const override;
    // The radiance's colour at surface parameters uv (`color`, or the image there times it).
    Rgb radiance_rgb(Vec2 uv) const;
    // Uniform by area, then cosine-weighted on the emitting side (a random side when two-sided):
    // weight = L pi A (x2 when two-sided) for every sample.
    LightLeSample sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const override;
    void pdf_Le(Vec3 n, Vec3 w, float& pdf_pos, float& pdf_dir) const override;
    Rgb power() const override;
    bool is_delta() const override { return false; }

    const ShapeSampler& sampler() const { return sampler_; }
    bool two_sided() const { return two_sided_; }

private:
    // The surface parameters of a sample (the mesh's uvs, or the triangle's barycentrics as the
    // accel layer gives them; an analytic shape's (u, v) as its hits have them).
    Vec2 sample_uv(const ShapeSample& s) const;
    // pbrt-v4's DiffuseAreaLight::AlphaMasked: whether the shape's alpha cut-out (scene::Shape::alpha)
    // removes the sampled point: alpha 0 always, alpha in (0, 1) when a hash of p exceeds it. An
    // alpha texture is read at the sample's uv on meshes; other shapes with one are not masked.
    bool alpha_masked(Vec3 p, const ShapeSample& s) const;

    ShapeSampler sampler_;
    Rgb radiance_;
    bool two_sided_ = false;
    std::shared_ptr<const scene::TextureImage> image_;  // null: uniform radiance
    Rgb image_mean_{0.0f};
    std::vector<Vec2> uvs_;  // the mesh's, when it has them
    std::vector<uint32_t> indices_;
    std::optional<accel::detail::Analytic> analytic_;  // a sphere, disk, cylinder or cone with an image
    float alpha_ = 1;
    int alpha_texture_ = -1;
    // The scene's textures (and nothing else), for evaluating the alpha texture; null without one.
    std::unique_ptr<scene::Scene> alpha_textures_;
};

}  // namespace phos::shading
