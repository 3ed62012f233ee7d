// Building the prepared scene: BVH, light set (with scene bounds for directional/infinite lights),
// and the camera (framing the bounds when the scene has none).
#include "render/prepared.h"

#include "scene/texture_eval.h"
#include "shading/infinite_light.h"
#include "shading/light_media.h"

namespace phos::render {

scene::Camera Prepared::camera_for(const scene::Scene& scene, const accel::EmbreeScene& accel,
                                   const PrepareOptions& prepare) {
    scene::Camera camera = scene.camera ? *scene.camera : CameraModel::frame_bounds(accel.bounds());
    if (prepare.lens_radius >= 0) {
        camera.lens_radius = prepare.lens_radius;
        camera.focal_distance = prepare.focal_distance;
    }
    return camera;
}

std::shared_ptr<const scene::CameraFootprint> Prepared::footprint_for(const scene::Scene& scene,
                                                                      const CameraModel& camera, int spp) {
    if (!scene::reads_footprint(scene)) return nullptr;
    return std::make_shared<const scene::CameraFootprint>(camera.texture_footprint(spp));
}

Prepared::Prepared(const scene::Scene& scene_, const RenderOptions& options_, const PrepareOptions& prepare,
                   Stats& stats_)
    : scene(scene_),
      accel(scene_, prepare.embree_config.empty() ? nullptr : prepare.embree_config.c_str()),
      lights(scene_, accel.bounds(), prepare.lights),
      media(scene_),
      camera(camera_for(scene_, accel, prepare), options_.width, options_.height, options_.crop),
      texture_footprint(footprint_for(scene_, camera, options_.spp)),
      filter(effective_filter(scene_.pixel_filter, options_)),
      options(options_),
      bsdf_options(with_footprint(prepare.bsdf, texture_footprint.get())),
      bsdfs(scene_, bsdf_options),
      stats(stats_) {
    if (media.active())
        lights.set_media(shading::place_lights_in_media(accel, lights, camera.eye(), camera_medium()));
    using spectrum::RgbSpectrum;
    background_ = RgbSpectrum(scene.background, RgbSpectrum::Use::Illuminant);
    glow_.reserve(scene.materials.size());
    for (const scene::Material& m : scene.materials)
        glow_.push_back(m.emission + (options.ambient ? m.ambient * scene.ambient : Rgb(0.0f)));
}

Spectrum Prepared::escaped(Vec3 origin, Vec3 dir, const Wavelengths& lambda) const {
    Spectrum L(0.0f);
    for (size_t i : lights.infinite_lights()) L += lights[i].escaped_Le(origin, dir, lambda);
    return L;
}

Rgb Prepared::escaped_colour(Vec3 dir) const {
    Rgb L(0.0f);
    for (size_t i : lights.infinite_lights())
        L += static_cast<const shading::InfiniteLight&>(lights[i]).Le_rgb(dir);
    return L;
}

}  // namespace phos::render
