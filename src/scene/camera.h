// The camera as plain data: position and orientation, field of view, lens, and image size hints.
#pragma once

#include "core/vec.h"

namespace phos::scene {

struct Camera {
    // Spherical: every direction around the eye, as pbrt-v4's spherical camera maps them to the
    // image (`spherical_mapping`); the image's top is the camera's up direction.
    enum class Projection { Perspective, Orthographic, Spherical };
    enum class SphericalMapping { EqualArea, Equirectangular };
    Projection projection = Projection::Perspective;
    SphericalMapping spherical_mapping = SphericalMapping::EqualArea;
    Vec3 eye{0, 0, 0};
    Vec3 forward{0, 0, -1};  // viewing direction (need not be normalised)
    Vec3 up{0, 1, 0};
    // Perspective: FULL field-of-view angle in radians along the SHORTER image side (or along the
    // image height when fov_vertical is set, as the .scene format's `d` defines it).
    float fov = 0.6981317f;
    bool fov_vertical = false;
    // Orthographic: half-extent of the view along the shorter image side, in scene units.
    float ortho_half_size = 1.0f;
    // Thin lens (depth of field): aperture radius (0 = pinhole) and distance of the focal plane.
    float lens_radius = 0.0f;
    float focal_distance = 1.0f;
    float near_clip = 0.0f;
    float far_clip = kInf;
    // True when the image x axis should be mirrored (pbrt's left-handed screen with `Scale -1 1 1`
    // is handled by the loader; this flag exists for formats that need it explicitly).
    bool flip_x = false;
};

}  // namespace phos::scene
