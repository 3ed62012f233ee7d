// Primary ray generation. The field of view spans the shorter image side; the longer side extends
// proportionally, so changing the aspect ratio never crops the shorter dimension.
#include "render/camera.h"

#include <cmath>

#include "core/error.h"
#include "core/warp.h"

namespace phos::render {

CameraModel::CameraModel(const scene::Camera& camera, int width, int height)
    : cam_(camera), width_(width), height_(height) {
    if (!(length(camera.forward) > 0)) throw InputError("camera: zero viewing direction");
    eye_ = camera.eye;
    forward_ = normalize(camera.forward);
    Vec3 r = cross(forward_, camera.up);
    if (!(length(r) > 1e-8f)) {
        // Up parallel to the view: pick any perpendicular.
        r = cross(forward_, std::fabs(forward_.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0));
    }
    right_ = normalize(r);
    up_ = cross(right_, forward_);
    if (camera.flip_x) right_ = -right_;
    const float half_short = camera.projection == scene::Camera::Projection::Perspective
                                 ? std::tan(0.5f * camera.fov)
                                 : camera.ortho_half_size;
    if (width >= height ||
        (camera.fov_vertical && camera.projection == scene::Camera::Projection::Perspective)) {
        half_h_ = half_short;
        half_w_ = half_short * float(width) / float(height);
    } else {
        half_w_ = half_short;
        half_h_ = half_short * float(height) / float(width);
    }
}

scene::Camera CameraModel::frame_bounds(const Bounds& bounds) {
    scene::Camera cam;
    const Vec3 c = bounds.empty() ? Vec3(0.0f) : bounds.center();
    const Vec3 e = bounds.empty() ? Vec3(1.0f) : bounds.extent();
    const float radius = std::max(0.5f * length(e), 1e-3f);
    cam.fov = 40.0f * kPi / 180.0f;
    const float dist = radius / std::sin(0.5f * cam.fov);
    cam.eye = c + Vec3(0, 0, dist);
    cam.forward = Vec3(0, 0, -1);
    cam.up = Vec3(0, 1, 0);
    return cam;
}

Ray CameraModel::generate_ray(float fx, float fy, Vec2 u_lens) const {
    const float sx = (2.0f * fx / float(width_) - 1.0f) * half_w_;
    const float sy = (1.0f - 2.0f * fy / float(height_)) * half_h_;
    Ray ray;
    if (cam_.projection == scene::Camera::Projection::Orthographic) {
        ray.origin = eye_ + right_ * sx + up_ * sy;
        ray.dir = forward_;
        ray.tmin = cam_.near_clip;
        ray.tmax = cam_.far_clip;
        return ray;
    }
    Vec3 dir = normalize(forward_ + right_ * sx + up_ * sy);
    const float cos_axis = dot(dir, forward_);
    ray.origin = eye_;
    if (cam_.lens_radius > 0) {
        // Thin lens: all rays through the pixel meet on the plane at focal_distance.
        const Vec3 focus = eye_ + dir * (cam_.focal_distance / cos_axis);
        const Vec2 d = warp::concentric_disk(u_lens) * cam_.lens_radius;
        ray.origin = eye_ + right_ * d.x + up_ * d.y;
        dir = normalize(focus - ray.origin);
    }
    ray.dir = dir;
    // Clip distances are measured along the viewing axis.
    const float c = std::max(dot(dir, forward_), 1e-6f);
    ray.tmin = cam_.near_clip / c;
    ray.tmax = cam_.far_clip >= kInf ? kInf : cam_.far_clip / c;
    return ray;
}

CameraModel::Footprint CameraModel::pixel_footprint() const {
    const float cx = 0.5f * float(width_), cy = 0.5f * float(height_);
    const Ray a = generate_ray(cx, cy, {0.5f, 0.5f});
    const Ray b = generate_ray(cx + 1, cy, {0.5f, 0.5f});
    Footprint f;
    f.offset = length(a.origin - b.origin);
    f.slope = length(normalize(a.dir) - normalize(b.dir));
    return f;
}

float CameraModel::direction_pdf(Vec3 unit_dir) const {
    if (cam_.projection == scene::Camera::Projection::Orthographic) return 0;
    const float c = dot(unit_dir, forward_);
    if (!(c > 0)) return 0;
    const float area = 4 * half_w_ * half_h_;
    return 1 / (area * c * c * c);
}

bool CameraModel::connect(Vec3 ref, Vec2 u_lens, Connection& c) const {
    if (cam_.projection == scene::Camera::Projection::Orthographic) return false;
    c.lens = eye_;
    if (cam_.lens_radius > 0) {
        const Vec2 d = warp::concentric_disk(u_lens) * cam_.lens_radius;
        c.lens = eye_ + right_ * d.x + up_ * d.y;
    }
    const Vec3 to_ref = ref - c.lens;
    const float dist = length(to_ref);
    if (!(dist > 0)) return false;
    const Vec3 dir = to_ref / dist;
    const float cos_axis = dot(dir, forward_);
    if (!(cos_axis > 0)) return false;
    // Near and far clip distances are measured along the viewing axis, as for camera rays.
    const float depth = dist * cos_axis;
    if (depth < cam_.near_clip || depth > cam_.far_clip) return false;
    // The film position: for a thin lens the ray meets the focal plane where the pixel's pinhole
    // ray does.
    Vec3 through = c.lens + dir;
    if (cam_.lens_radius > 0) through = c.lens + dir * (cam_.focal_distance / cos_axis);
    if (!project(through, c.fx, c.fy)) return false;
    c.wi = -dir;
    c.distance = dist;
    c.pdf_dir = direction_pdf(dir);
    return c.pdf_dir > 0;
}

bool CameraModel::project(Vec3 p, float& fx, float& fy) const {
    const Vec3 d = p - eye_;
    const float z = dot(d, forward_);
    if (z <= 0) return false;
    const float sx = dot(d, right_) / z, sy = dot(d, up_) / z;
    fx = (sx / half_w_ + 1.0f) * 0.5f * float(width_);
    fy = (1.0f - sy / half_h_) * 0.5f * float(height_);
    return fx >= 0 && fx < float(width_) && fy >= 0 && fy < float(height_);
}

}  // namespace phos::render
