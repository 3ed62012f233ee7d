// LightSet: turns scene::Light records into runtime lights and keeps a power-proportional
// distribution for choosing one (for photon emission and, by default, for direct lighting).
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/log.h"
#include "shading/area_light.h"
#include "shading/directional_light.h"
#include "shading/goniometric_light.h"
#include "shading/infinite_light.h"
#include "shading/lights.h"
#include "shading/point_light.h"
#include "shading/projection_light.h"
#include "shading/spot_light.h"

namespace phos::shading {

SceneSphere SceneSphere::from_bounds(const Bounds& b) {
    SceneSphere s;
    if (b.empty() || !is_finite(b.lo) || !is_finite(b.hi)) {
        s.radius = 1;
        return s;
    }
    s.center = b.center();
    s.radius = 0.5f * length(b.extent());
    if (!(s.radius > 0)) s.radius = 1e-3f;  // a single point: keep the emission disk non-degenerate
    return s;
}

Frame light_frame(const Transform& t) {
    const Vec3 x = normalize(t.vector({1, 0, 0}));
    Vec3 y = t.vector({0, 1, 0});
    y = normalize(y - x * dot(x, y));
    const Vec3 z = cross(x, y) * (t.swaps_handedness() ? -1.0f : 1.0f);
    return Frame(x, y, z);
}

Light::Light(const scene::Light& light)
    : emission_(light.spectrum
                    ? *light.spectrum
                    : spectrum::Distribution::rgb(light.color, spectrum::RgbSpectrum::Use::Illuminant)) {}

namespace {

const char* kind_name(scene::Light::Kind k) {
    switch (k) {
        case scene::Light::Kind::Point:
            return "point";
        case scene::Light::Kind::Spot:
            return "spot";
        case scene::Light::Kind::Directional:
            return "directional";
        case scene::Light::Kind::Area:
            return "area";
        case scene::Light::Kind::Infinite:
            return "infinite";
        case scene::Light::Kind::Goniometric:
            return "goniometric";
        case scene::Light::Kind::Projection:
            return "projection";
    }
    return "?";
}

}  // namespace

LightSet::LightSet(const scene::Scene& scene, const Bounds& scene_bounds, const LightOptions& options) {
    const SceneSphere sphere = SceneSphere::from_bounds(scene_bounds);
    using K = scene::Light::Kind;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const scene::Light& l = scene.lights[i];
        const std::string name = "light " + std::to_string(i) + " (" + kind_name(l.kind) + ")";
        switch (l.kind) {
            case K::Point:
            case K::Spot:
                // Non-physical attenuation constants are ignored unless legacy_attenuation; the
                // .scn loader, which reads them, warns once per light at its file location.
                if (l.kind == K::Point)
                    lights_.push_back(std::make_unique<PointLight>(l, options));
                else
                    lights_.push_back(std::make_unique<SpotLight>(l, options));
                break;
            case K::Directional:
                lights_.push_back(std::make_unique<DirectionalLight>(l, sphere));
                break;
            case K::Area:
                // Area lights refer to top-level shapes (Scene::shapes); instanced emitters are not
                // lights.
                if (l.shape < 0 || size_t(l.shape) >= scene.shapes.size())
                    throw InputError(name + ": shape index " + std::to_string(l.shape) + " out of range");
                lights_.push_back(
                    std::make_unique<AreaLight>(l, scene.shapes[size_t(l.shape)], &scene.textures));
                break;
            case K::Infinite:
                lights_.push_back(std::make_unique<InfiniteLight>(l, scene.textures, sphere));
                infinite_.push_back(i);
                break;
            case K::Goniometric:
                lights_.push_back(std::make_unique<GoniometricLight>(l, scene.textures));
                break;
            case K::Projection:
                lights_.push_back(std::make_unique<ProjectionLight>(l, scene.textures));
                break;
        }
    }
    std::vector<float> weights(lights_.size());
    for (size_t i = 0; i < lights_.size(); ++i) {
        const Rgb p = lights_[i]->power();
        const float w = p.average();
        weights[i] = std::isfinite(w) && w > 0 ? w : 0;
        if (weights[i] == 0) {
            const scene::Light& l = scene.lights[i];
            log::warn((l.origin.empty() ? "" : l.origin + ": ") + "light " + std::to_string(i) + " (" +
                      kind_name(l.kind) + ") has zero power: it emits no photons and is never chosen");
        }
    }
    distribution_ = Distribution1D(weights);
}

LightSet::~LightSet() = default;

float LightSet::pmf(size_t i) const { return distribution_.pmf(i); }

Rgb LightSet::total_power() const {
    Rgb sum(0.0f);
    for (const auto& l : lights_) sum += l->power();
    return sum;
}

}  // namespace phos::shading
