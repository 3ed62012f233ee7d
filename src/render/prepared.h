// Everything an integrator needs that is derived once from the scene: the Embree BVH, the light
// set, the camera model and the shading options, plus the statistics sink.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "accel/embree_scene.h"
#include "core/stats.h"
#include "render/camera.h"
#include "render/options.h"
#include "render/pixel_filter.h"
#include "scene/scene.h"
#include "shading/bsdf.h"
#include "shading/lights.h"
#include "shading/material_bsdfs.h"
#include "shading/medium.h"
#include "spectrum/rgb_spectrum.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::render {

struct PrepareOptions {
    shading::BsdfOptions bsdf;
    shading::LightOptions lights;
    // --dof: thin-lens aperture radius and focal distance replacing the camera's (also for the
    // camera framed for scenes without one); ignored when lens_radius < 0.
    float lens_radius = -1;
    float focal_distance = 1;
    // Embree's device configuration (accel/device_config.h; empty: Embree's choice).
    std::string embree_config;
};

class Prepared {
public:
    Prepared(const scene::Scene& scene, const RenderOptions& options, const PrepareOptions& prepare,
             Stats& stats);

    const scene::Scene& scene;
    accel::EmbreeScene accel;
    shading::LightSet lights;
    shading::MediaSet media;
    CameraModel camera;
    // pbrt-v4's camera footprint for filtered image textures (CameraModel::texture_footprint at
    // options.spp); null when no texture of the scene reads it (scene::reads_footprint).
    std::shared_ptr<const scene::CameraFootprint> texture_footprint;
    PixelFilterSampler filter;  // where camera samples fall and how they weigh (pixel_filter.h)
    RenderOptions options;
    shading::BsdfOptions bsdf_options;
    shading::MaterialBsdfs bsdfs;  // every material's BSDF, placed at hits by bsdf()
    Stats& stats;

    // The BSDF at a hit (material looked up and textured).
    shading::Bsdf bsdf(const accel::SurfaceHit& hit) const { return bsdfs.at(hit); }
    // Radiance emitted by the light surface at `hit` towards `wo` (0 if it does not emit), at `lambda`.
    Spectrum emitted(const accel::SurfaceHit& hit, Vec3 wo, const Wavelengths& lambda) const {
        return hit.area_light >= 0 ? lights[size_t(hit.area_light)].surface_Le(hit.ng, hit.uv, wo, lambda)
                                   : Spectrum(0.0f);
    }
    // Radiance arriving along an escaped ray from `origin` with direction `dir` from infinite lights, at
    // `lambda`, and its colour.
    Spectrum escaped(Vec3 origin, Vec3 dir, const Wavelengths& lambda) const;
    Rgb escaped_colour(Vec3 dir) const;
    // The scene's background radiance (Scene::background) at `lambda`.
    Spectrum background(const Wavelengths& lambda) const { return background_.sample(lambda); }
    // The glow material `m` shows camera and specular rays (Material::emission, and with --ambient
    // its ambient term): a colour.
    Rgb glow(int m) const { return glow_[size_t(m)]; }
    // The media walks and shadow rays use (null when no ray can travel in a medium).
    const shading::MediaSet* active_media() const { return media.active() ? &media : nullptr; }
    // The medium camera rays start in.
    int camera_medium() const { return media.active() ? scene.camera_medium : -1; }

private:
    spectrum::RgbSpectrum background_;
    std::vector<Rgb> glow_;  // per material
    static std::shared_ptr<const scene::CameraFootprint> footprint_for(const scene::Scene& scene,
                                                                       const CameraModel& camera, int spp);
    static shading::BsdfOptions with_footprint(shading::BsdfOptions options,
                                               const scene::CameraFootprint* f) {
        options.texture_footprint = f;
        return options;
    }
    static scene::Camera camera_for(const scene::Scene& scene, const accel::EmbreeScene& accel,
                                    const PrepareOptions& prepare);
};

}  // namespace phos::render
