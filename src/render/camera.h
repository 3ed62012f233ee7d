// The render-time camera: turns a scene::Camera into primary rays for a given image size —
// pinhole, thin lens (depth of field), orthographic, spherical (pbrt-v4's equal-area or
// equirectangular mapping of all directions) or realistic (a lens system, render/lens_system.h).
// Image x grows to the right, y downwards.
#pragma once

#include <memory>

#include "accel/embree_scene.h"
#include "accel/ray.h"
#include "render/lens_system.h"
#include "render/options.h"
#include "scene/camera.h"
#include "scene/camera_footprint.h"

namespace phos::render {

class CameraModel {
public:
    // The width of one pixel projected into the scene along a camera path of length d (distance
    // travelled from the lens, through mirrors and glass included): offset + slope d. It scales
    // density-estimation radii to the image's resolution.
    struct Footprint {
        float offset = 0, slope = 0;
        float at(float distance) const { return offset + slope * distance; }
    };

    // An image of width x height pixels; with an active `crop`, the image the camera frames is
    // crop.full_width x crop.full_height and width x height is the part rendered, from crop.x0, y0:
    // film positions below are in the rendered part's pixels.
    CameraModel(const scene::Camera& camera, int width, int height, const CropWindow& crop = {});
    // A camera for scenes without one: frames `bounds` from the +z side.
    static scene::Camera frame_bounds(const Bounds& bounds);

    // Ray through film position (fx, fy) in pixels (0..width, 0..height), lens sample `u_lens`.
    // `weight` is the sample's camera weight, which multiplies what the ray finds: 1 except for the
    // realistic camera (pbrt-v4's cos^4 weighting), whose lenses may block the ray: then the weight
    // is 0 and the ray is empty (tmax < tmin, it hits nothing), and the sample counts as black.
    // Integrators use this form; the one without a weight is for geometry (footprints, tests).
    Ray generate_ray(float fx, float fy, Vec2 u_lens, float& weight) const;
    Ray generate_ray(float fx, float fy, Vec2 u_lens) const {
        float weight;
        return generate_ray(fx, fy, u_lens, weight);
    }
    // Projects a world point to film coordinates through the pinhole at eye(); returns false if it
    // is behind the camera or outside the image (always false for a realistic camera). Light tracing
    // (connect), tests and debugging tools.
    bool project(Vec3 p, float& fx, float& fy) const;
    // The pixel footprint measured at the image centre (between the centres of two neighbouring
    // pixels' rays, lens centre): constant offset for orthographic views, slope for perspective.
    Footprint pixel_footprint() const;
    // What pbrt-v4's Camera::Approximate_dp_dxy needs (scene/camera_footprint.h), for a render of
    // `samples_per_pixel` samples: its CameraBase::FindMinimumDifferentials over 512 film
    // positions along the whole image's diagonal, lens centre, rays whose lenses block them
    // skipped. The pixel's neighbour rays are the rays one pixel over for the perspective and
    // orthographic cameras (pbrt-v4's own differentials of them) and finite differences over a
    // twentieth of a pixel (towards +x, +y, else -x, -y) for the spherical and realistic ones
    // (pbrt-v4's CameraBase::GenerateRayDifferential). No valid ray: zero differentials.
    scene::CameraFootprint texture_footprint(int samples_per_pixel) const;

    // Bidirectional methods (Veach 1997, sec. 10.2; pbrt's camera importance): the camera as the
    // end of a light path. With an image plane of area A at distance 1 (the whole film), a ray that
    // leaves the lens at angle theta to the viewing axis has solid-angle density
    // 1 / (A cos^3 theta) per camera sample, whatever the pixel: direction_pdf. 0 for an
    // orthographic camera (its directions form a delta, light paths cannot reach it), a realistic
    // one (as in pbrt-v4, light paths are not traced back through its lenses) or a direction
    // behind the camera.
    float direction_pdf(Vec3 unit_dir) const;
    // Light paths reaching the camera (light tracing, the t = 1 strategy): a point on the lens seen
    // from `ref` (a lens sample for a thin lens) and the film position its ray lands on. A light
    // path with throughput beta at ref adds beta f |cos_ref| T direction_pdf / distance^2 to that
    // pixel's mean over camera samples (the pinhole's and the thin lens's importance; the lens
    // area cancels against the lens sample's density).
    struct Connection {
        float fx = 0, fy = 0;  // film position in pixels
        Vec3 lens;             // the point on the lens
        Vec3 wi;               // unit direction from ref towards `lens`
        float distance = 0;    // from ref to `lens`
        float pdf_dir = 0;     // direction_pdf of the camera ray lens -> ref
    };
    // False when `ref` is behind the camera, outside the image, outside the near and far clip
    // distances, or the camera is orthographic or realistic.
    bool connect(Vec3 ref, Vec2 u_lens, Connection& c) const;

    Vec3 eye() const { return eye_; }
    Vec3 forward() const { return forward_; }

private:
    bool spherical() const { return cam_.projection == scene::Camera::Projection::Spherical; }
    bool realistic() const { return cam_.projection == scene::Camera::Projection::Realistic; }
    Ray realistic_ray(float fx, float fy, Vec2 u_lens, float& weight) const;
    // Spherical camera: the direction of image position (u, v) in [0, 1]^2 of the whole image and
    // back, and the film's density per unit solid angle of a direction.
    Vec3 spherical_direction(float u, float v) const;
    bool spherical_position(Vec3 unit_dir, float& u, float& v) const;
    float spherical_pdf(Vec3 unit_dir) const;
    scene::Camera cam_;
    int width_, height_;               // the image the camera frames
    float crop_x0_ = 0, crop_y0_ = 0;  // film position (0, 0) of the rendered part, in the image's pixels
    int film_w_, film_h_;              // the rendered part
    Vec3 eye_, forward_, right_, up_;
    float half_w_, half_h_;  // image-plane half extents at distance 1 (perspective) or in units
    // Realistic: the lens system (shared by copies) and the film's physical half extents.
    std::shared_ptr<const LensSystem> lenses_;
    float film_half_w_ = 0, film_half_h_ = 0;
};

}  // namespace phos::render
