// Placing lights in media by tracking from the camera (see light_media.h).
#include "shading/light_media.h"

#include <map>
#include <string>

#include "core/log.h"
#include "shading/surface_walk.h"

namespace phos::shading {

std::optional<int> medium_reached(const accel::EmbreeScene& accel, Vec3 from, int medium, Vec3 to) {
    // Stops just short of `to`: an emitting surface there is not crossed.
    Ray ray{from, to - from, 0.0f, 1 - 1e-4f};
    const Vec3 end = from + (to - from) * ray.tmax;
    for (int crossings = 0; crossings <= SurfaceWalk::kMaxCrossings; ++crossings) {
        accel::SurfaceHit hit;
        if (!accel.intersect(ray, hit)) return medium;
        medium = SurfaceWalk::medium_after(hit, ray.dir, medium);
        Ray next = accel::spawn_ray(hit, ray.dir);
        next.tmax = dot(end - next.origin, ray.dir) / dot(ray.dir, ray.dir);
        if (!(next.tmax > next.tmin)) return medium;
        ray = next;
    }
    return std::nullopt;
}

namespace {

std::string medium_name(const scene::Scene& scene, int medium) {
    return medium < 0 ? std::string("vacuum") : "medium \"" + scene.media[size_t(medium)].name + "\"";
}

std::string light_name(const scene::Light& light, size_t i) {
    const std::string name = "light " + std::to_string(i);
    return light.origin.empty() ? name : light.origin + ": " + name;
}

// The media camera tracking reaches at up to 16 emitting points of `light` (stratified over
// sample_Le's position, front side): medium -> how many points lie in it.
std::map<int, int> tracked_media(const accel::EmbreeScene& accel, const Light& light, bool single_point,
                                 Vec3 eye, int camera_medium) {
    std::map<int, int> count;
    // Where a light sits does not depend on wavelength: any set of wavelengths will do.
    const Wavelengths any_wavelengths = Wavelengths::visible(0.5f);
    const int n = single_point ? 1 : 4;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const LightLeSample s = light.sample_Le({(i + 0.5f) / float(n), (j + 0.5f) / float(n)},
                                                    {0.25f, 0.5f}, any_wavelengths);
            if (!(s.pdf_pos > 0)) continue;
            if (const std::optional<int> m = medium_reached(accel, eye, camera_medium, s.ray.origin))
                ++count[*m];
        }
    return count;
}

}  // namespace

std::vector<LightMedia> place_lights_in_media(const accel::EmbreeScene& accel, const LightSet& lights,
                                              Vec3 eye, int camera_medium) {
    const scene::Scene& scene = accel.scene();
    std::vector<LightMedia> out(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        const scene::Light& spec = scene.lights[i];
        using K = scene::Light::Kind;
        if (spec.kind == K::Area) {
            const scene::MediumInterface& mi = scene.shapes[size_t(spec.shape)].media;
            if (mi.is_transition()) {
                out[i] = {mi.outside, mi.inside};
                continue;
            }
        }
        const bool single_point = spec.kind == K::Point || spec.kind == K::Spot ||
                                  spec.kind == K::Goniometric || spec.kind == K::Projection;
        const std::map<int, int> count = tracked_media(accel, lights[i], single_point, eye, camera_medium);
        int tracked = spec.medium, most = 0, total = 0;
        for (const auto& [medium, k] : count) {
            total += k;
            if (k > most) tracked = medium, most = k;
        }
        const int medium = spec.medium_declared ? spec.medium : tracked;
        out[i] = {medium, medium};
        if (count.size() > 1) {
            std::string where;
            for (const auto& [m, k] : count)
                where += (where.empty() ? "" : ", ") + std::to_string(k) + " in " + medium_name(scene, m);
            log::warn(light_name(spec, i) +
                      ": seen from the camera, its emitting points lie in different media (" +
                      std::to_string(total) + " sampled: " + where + "); its light starts in " +
                      medium_name(scene, medium));
        } else if (spec.medium_declared && most > 0 && tracked != spec.medium) {
            log::warn(light_name(spec, i) + " is declared in " + medium_name(scene, spec.medium) +
                      " but rays from the camera reach it in " + medium_name(scene, tracked) +
                      "; the declaration wins");
        }
    }
    return out;
}

}  // namespace phos::shading
