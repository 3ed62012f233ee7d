// Lights as plain data. Positions and directions are in world space. Area lights are tied to a
// shape (the emitting surface, which is also visible geometry) by index.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/transform.h"
#include "core/vec.h"
#include "spectrum/distribution.h"

namespace phos::scene {

struct Light {
    enum class Kind {
        Point,        // intensity I (W/sr) at `position`
        Spot,         // intensity I on the axis `direction`, cone `cutoff` (half angle, rad), cos^dropoff
        Directional,  // irradiance E (W/m^2) on a surface facing the light, travelling along `direction`
        Area,         // radiance L (W/sr/m^2) leaving the surface of shape `shape`
        Infinite,     // environment: radiance L (constant, or a `texture` map: lat-long or equal-area)
        // Point lights whose intensity I over directions is an image (`texture`) times `color`:
        Goniometric,  // the image is an equal-area map over the sphere of directions (pbrt-v4)
        Projection,   // the image is projected like a slide, field of view `fov` (pbrt-v4)
    };
    Kind kind = Kind::Point;
    Rgb color{1.0f};  // I, E or L as stated above (already multiplied by any scale)
    // The emission's spectrum (blackbody, a named illuminant, a table), scale included, when the
    // file gives one; `color` then holds its linear sRGB. Unset: `color` read as an illuminant RGB.
    std::optional<spectrum::Distribution> spectrum;
    Vec3 position{0.0f};
    Vec3 direction{0, -1, 0};
    float cutoff = 0.5f;
    float dropoff = 0.0f;
    // Spot lights from pbrt: smooth fall-off between `falloff_start` and `cutoff` (radians) instead of
    // cos^dropoff when >= 0.
    float falloff_start = -1.0f;
    // .scn attenuation constants (ca, la, qa); physical is (0, 0, 1).
    Vec3 attenuation{0, 0, 1};
    // Area: the emitting shape; emission on the side its normal faces unless two_sided.
    int shape = -1;
    bool two_sided = false;
    // Infinite: radiance map (texture index, -1 = constant) and its orientation; `equal_area`: the
    // map is pbrt-v4's square equal-area octahedral map, else a lat-long map.
    // Goniometric, projection: the image (required), in the light space of `to_world`, whose
    // origin is the light's position (Light::position).
    // Area: an image of the radiance over the surface's (u, v) replacing `color` (-1: none).
    int texture = -1;
    bool equal_area = false;
    // Infinite, pbrt-v4's "portal": the four corners p0..p3 (world space) of a rectangle the light
    // shines through (shading/light_portal.h); empty: no portal.
    std::vector<Vec3> portal;
    float fov = 1.5707964f;  // projection: the full angle across the image's shorter side (radians)
    Transform to_world;
    // The medium the light sits in (-1 = vacuum) when the file says so (`medium_declared`: pbrt's
    // MediumInterface in effect at the light, the .scene containment rule). An undeclared light sits
    // where medium tracking from the camera reaches it (shading/light_media.h); photons and light
    // subpaths start in that medium.
    int medium = -1;
    bool medium_declared = false;
    std::string origin;  // "file:line:col" where it was defined, for messages (may be empty)
};

}  // namespace phos::scene
