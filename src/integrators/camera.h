// The render-time camera: turns a scene::Camera into primary rays for a given image size —
// pinhole, thin lens (depth of field) or orthographic. Image x grows to the right, y downwards.
#pragma once

#include "accel/embree_scene.h"
#include "accel/ray.h"
#include "scene/camera.h"

namespace phos::integrators {

class CameraModel {
public:
    // The width of one pixel projected into the scene along a camera path of length d (distance
    // travelled from the lens, through mirrors and glass included): offset + slope d. It scales
    // density-estimation radii to the image's resolution.
    struct Footprint {
        float offset = 0, slope = 0;
        float at(float distance) const { return offset + slope * distance; }
    };

    CameraModel(const scene::Camera& camera, int width, int height);
    // A camera for scenes without one: frames `bounds` from the +z side.
    static scene::Camera frame_bounds(const accel::Bounds& bounds);

    // Ray through film position (fx, fy) in pixels (0..width, 0..height), lens sample `u_lens`.
    accel::Ray generate_ray(float fx, float fy, Vec2 u_lens) const;
    // Projects a world point to film coordinates; returns false if it is behind the camera or
    // outside the image. Used by tests and debugging tools.
    bool project(Vec3 p, float& fx, float& fy) const;
    // The pixel footprint measured at the image centre (between the centres of two neighbouring
    // pixels' rays, lens centre): constant offset for orthographic views, slope for perspective.
    Footprint pixel_footprint() const;

    Vec3 eye() const { return eye_; }
    Vec3 forward() const { return forward_; }

private:
    scene::Camera cam_;
    int width_, height_;
    Vec3 eye_, forward_, right_, up_;
    float half_w_, half_h_;  // image-plane half extents at distance 1 (perspective) or in units
};

}  // namespace phos::integrators
