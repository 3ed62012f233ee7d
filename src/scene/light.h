// Lights as plain data. Positions and directions are in world space. Area lights are tied to a
// shape (the emitting surface, which is also visible geometry) by index.
#pragma once

#include "core/transform.h"
#include "core/vec.h"

namespace phos::scene {

struct Light {
    enum class Kind {
        Point,        // intensity I (W/sr) at `position`
        Spot,         // intensity I on the axis `direction`, cone `cutoff` (half angle, rad), cos^dropoff
        Directional,  // irradiance E (W/m^2) on a surface facing the light, travelling along `direction`
        Area,         // radiance L (W/sr/m^2) leaving the surface of shape `shape`
        Infinite,     // environment: radiance L (constant or `texture` lat-long map)
    };
    Kind kind = Kind::Point;
    Rgb color{1.0f};  // I, E or L as stated above (already multiplied by any scale)
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
    // Infinite: lat-long radiance map (texture index, -1 = constant) and its orientation.
    int texture = -1;
    Transform to_world;
    // The medium the light sits in (point, spot and area lights; -1 = vacuum): photons start in it.
    int medium = -1;
};

}  // namespace phos::scene
