// The camera as plain data: position and orientation, field of view, lens, and image size hints.
#pragma once

#include <vector>

#include "core/vec.h"

namespace phos::scene {

// One interface of a realistic camera's lens system (pbrt-v4's lens description, in scene units):
// a spherical surface of signed curvature radius (0: the aperture stop, a plane), the distance to
// the next interface towards the film (or, for the rear one, to the film), the index of refraction
// of the medium behind it towards the film (1: air) and the radius of its aperture.
struct LensElement {
    float curvature_radius = 0;
    float thickness = 0;
    float eta = 1;
    float aperture_radius = 0;
};

// The shape of a realistic camera's aperture stop (pbrt-v4's "aperture"): a transmission image over
// the stop's bounding square, row 0 along the stop's -y edge, scaled so that its mean is pi/4 (a
// circle's share of the square: shaped stops pass as much light as the circle). Empty: a circle.
struct ApertureImage {
    int width = 0, height = 0;
    std::vector<float> values;  // row-major
    bool empty() const { return values.empty(); }
};

struct Camera {
    // Spherical: every direction around the eye, as pbrt-v4's spherical camera maps them to the
    // image (`spherical_mapping`); the image's top is the camera's up direction.
    // Realistic: pbrt-v4's camera that traces rays from the film through a system of lenses
    // (render/lens_system.h).
    enum class Projection { Perspective, Orthographic, Spherical, Realistic };
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
    // Realistic: the lens elements from the front (scene side) to the rear (film side), the
    // aperture stop's radius already the smaller of the file's and the scene's; the distance from
    // the film that is in focus (the rear element is moved to focus it) and the film's diagonal,
    // all in scene units.
    std::vector<LensElement> lens_elements;
    float lens_focus_distance = 10.0f;
    float film_diagonal = 0.035f;
    ApertureImage aperture;
    float near_clip = 0.0f;
    float far_clip = kInf;
    // True when the image x axis should be mirrored (pbrt's left-handed screen with `Scale -1 1 1`
    // is handled by the loader; this flag exists for formats that need it explicitly).
    bool flip_x = false;
};

}  // namespace phos::scene
