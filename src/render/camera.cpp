// Primary ray generation. The field of view spans the shorter image side; the longer side extends
// proportionally, so changing the aspect ratio never crops the shorter dimension.
#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include "core/equal_area.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/warp.h"

namespace phos::render {

CameraModel::CameraModel(const scene::Camera& camera, int width, int height, const CropWindow& crop)
    : cam_(camera),
      width_(crop.active() ? crop.full_width : width),
      height_(crop.active() ? crop.full_height : height),
      crop_x0_(float(crop.x0)),
      crop_y0_(float(crop.y0)),
      film_w_(width),
      film_h_(height) {
    if (crop.active() && (crop.x0 < 0 || crop.y0 < 0 || crop.x0 + width > crop.full_width ||
                          crop.y0 + height > crop.full_height))
        throw InputError("camera: the crop window is outside the image");
    width = width_;
    height = height_;
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
    if (camera.projection == scene::Camera::Projection::Realistic) {
        // pbrt-v4's film: a rectangle of the image's aspect ratio with the given diagonal.
        if (!(camera.film_diagonal > 0)) throw InputError("camera: the film's diagonal must be positive");
        const float aspect = float(height) / float(width);
        const float x = std::sqrt(camera.film_diagonal * camera.film_diagonal / (1 + aspect * aspect));
        film_half_w_ = 0.5f * x;
        film_half_h_ = 0.5f * aspect * x;
        lenses_ = std::make_shared<const LensSystem>(camera.lens_elements, double(camera.lens_focus_distance),
                                                     camera.aperture, 0.5 * double(camera.film_diagonal));
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

Ray CameraModel::generate_ray(float fx, float fy, Vec2 u_lens, float& weight) const {
    fx += crop_x0_;
    fy += crop_y0_;
    weight = 1;
    if (realistic()) return realistic_ray(fx, fy, u_lens, weight);
    if (spherical()) {
        Ray ray;
        ray.origin = eye_;
        ray.dir = spherical_direction(fx / float(width_), fy / float(height_));
        ray.tmin = cam_.near_clip;
        ray.tmax = cam_.far_clip;
        return ray;
    }
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

// pbrt-v4's RealisticCamera::GenerateRay (PBR 4th ed., sec. 5.4.5): the film point of (fx, fy) on
// the sensor, mirrored in x (the lens turns the image over), a ray from it through the lens system,
// and the camera-space ray turned to world space.
Ray CameraModel::realistic_ray(float fx, float fy, Vec2 u_lens, float& weight) const {
    const float px = -film_half_w_ + 2 * film_half_w_ * fx / float(width_);
    const float py = -film_half_h_ + 2 * film_half_h_ * fy / float(height_);
    LensSystem::LensRay out;
    weight = float(lenses_->generate(Vec2(-px, py), u_lens, out));
    Ray ray;
    if (!(weight > 0)) {
        weight = 0;
        ray.origin = eye_;
        ray.dir = forward_;
        ray.tmin = 0;
        ray.tmax = -1;  // empty: the lenses blocked it
        return ray;
    }
    ray.origin = eye_ + right_ * float(out.o.x) + up_ * float(out.o.y) + forward_ * float(out.o.z);
    ray.dir = normalize(right_ * float(out.d.x) + up_ * float(out.d.y) + forward_ * float(out.d.z));
    ray.tmin = 0;
    ray.tmax = kInf;
    return ray;
}

CameraModel::Footprint CameraModel::pixel_footprint() const {
    const float cx = 0.5f * float(width_) - crop_x0_, cy = 0.5f * float(height_) - crop_y0_;
    float wa = 1, wb = 1;
    const Ray a = generate_ray(cx, cy, {0.5f, 0.5f}, wa);
    const Ray b = generate_ray(cx + 1, cy, {0.5f, 0.5f}, wb);
    Footprint f;
    if (!(wa > 0 && wb > 0)) {
        // A realistic camera whose centre rays are blocked: one pixel of film over the focal length.
        f.slope = float(2 * double(film_half_w_) / double(width_) / lenses_->focal_length());
        return f;
    }
    f.offset = length(a.origin - b.origin);
    f.slope = length(normalize(a.dir) - normalize(b.dir));
    return f;
}

scene::CameraFootprint CameraModel::texture_footprint(int samples_per_pixel) const {
    scene::CameraFootprint f;
    f.eye = eye_;
    f.right = right_;
    f.up = up_;
    f.forward = forward_;
    f.spp_scale = std::max(0.125f, 1 / std::sqrt(float(std::max(samples_per_pixel, 1))));
    const auto to_camera = [&](Vec3 v) { return Vec3(dot(v, right_), dot(v, up_), dot(v, forward_)); };
    const bool projective = cam_.projection == scene::Camera::Projection::Perspective ||
                            cam_.projection == scene::Camera::Projection::Orthographic;
    const Vec2 lens_centre(0.5f, 0.5f);
    // The change of the ray at film (fx, fy) per pixel along (ex, ey): origin and direction.
    const auto differential = [&](const Ray& r, float fx, float fy, float ex, float ey, Vec3& d_origin,
                                  Vec3& d_dir) {
        for (const float eps : {projective ? 1.0f : 0.05f, -0.05f}) {
            float w = 0;
            const Ray s = generate_ray(fx + ex * eps, fy + ey * eps, lens_centre, w);
            if (!(w > 0)) continue;
            d_origin = (s.origin - r.origin) / eps;
            d_dir = (s.dir - r.dir) / eps;
            return true;
        }
        return false;
    };
    Vec3 min_pos[2] = {Vec3(kInf), Vec3(kInf)}, min_dir[2] = {Vec3(kInf), Vec3(kInf)};
    const int n = 512;
    for (int i = 0; i < n; ++i) {
        // Film positions of the whole image (generate_ray takes the rendered part's).
        const float fx = float(i) / float(n - 1) * float(width_) - crop_x0_;
        const float fy = float(i) / float(n - 1) * float(height_) - crop_y0_;
        float w = 0;
        const Ray r = generate_ray(fx, fy, lens_centre, w);
        if (!(w > 0)) continue;
        Vec3 d_origin[2], d_dir[2];
        if (!differential(r, fx, fy, 1, 0, d_origin[0], d_dir[0]) ||
            !differential(r, fx, fy, 0, 1, d_origin[1], d_dir[1]))
            continue;
        const Vec3 d = normalize(r.dir);
        const Frame frame(d);
        const Vec3 d_local = frame.to_local(d);  // (0, 0, 1) up to rounding
        for (int k = 0; k < 2; ++k) {
            const Vec3 dox = to_camera(d_origin[k]);
            if (length(dox) < length(min_pos[k])) min_pos[k] = dox;
            const Vec3 neighbour = normalize(frame.to_local(normalize(r.dir + d_dir[k])));
            if (length(neighbour - d_local) < length(min_dir[k])) min_dir[k] = neighbour - d_local;
        }
    }
    const auto finite_or_zero = [](Vec3 v) { return is_finite(v) ? v : Vec3(0.0f); };
    f.min_pos_dx = finite_or_zero(min_pos[0]);
    f.min_pos_dy = finite_or_zero(min_pos[1]);
    f.min_dir_dx = finite_or_zero(min_dir[0]);
    f.min_dir_dy = finite_or_zero(min_dir[1]);
    return f;
}

float CameraModel::direction_pdf(Vec3 unit_dir) const {
    if (cam_.projection == scene::Camera::Projection::Orthographic || realistic()) return 0;
    if (spherical()) return spherical_pdf(unit_dir);
    const float c = dot(unit_dir, forward_);
    if (!(c > 0)) return 0;
    // The film the camera samples: the whole image plane, or the rendered part of it.
    const float area =
        4 * half_w_ * half_h_ * ((float(film_w_) * float(film_h_)) / (float(width_) * float(height_)));
    return 1 / (area * c * c * c);
}

bool CameraModel::connect(Vec3 ref, Vec2 u_lens, Connection& c) const {
    if (cam_.projection == scene::Camera::Projection::Orthographic || realistic()) return false;
    c.lens = eye_;
    if (cam_.lens_radius > 0) {
        const Vec2 d = warp::concentric_disk(u_lens) * cam_.lens_radius;
        c.lens = eye_ + right_ * d.x + up_ * d.y;
    }
    const Vec3 to_ref = ref - c.lens;
    const float dist = length(to_ref);
    if (!(dist > 0)) return false;
    const Vec3 dir = to_ref / dist;
    if (spherical()) {
        // Clip distances along the ray; every direction reaches the film.
        if (dist < cam_.near_clip || dist > cam_.far_clip || !project(ref, c.fx, c.fy)) return false;
        c.wi = -dir;
        c.distance = dist;
        c.pdf_dir = spherical_pdf(dir);
        return c.pdf_dir > 0;
    }
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
    if (realistic()) return false;  // no pinhole: the lenses decide where a point lands
    const Vec3 d = p - eye_;
    if (spherical()) {
        float u, v;
        if (!spherical_position(d, u, v)) return false;
        fx = u * float(width_) - crop_x0_;
        fy = v * float(height_) - crop_y0_;
        return fx >= 0 && fx < float(film_w_) && fy >= 0 && fy < float(film_h_);
    }
    const float z = dot(d, forward_);
    if (z <= 0) return false;
    const float sx = dot(d, right_) / z, sy = dot(d, up_) / z;
    fx = (sx / half_w_ + 1.0f) * 0.5f * float(width_) - crop_x0_;
    fy = (1.0f - sy / half_h_) * 0.5f * float(height_) - crop_y0_;
    return fx >= 0 && fx < float(film_w_) && fy >= 0 && fy < float(film_h_);
}

// pbrt-v4's spherical camera: equirectangular theta = pi v from the camera's up axis and
// phi = 2 pi u around it from its +x axis towards +z (the viewing direction at u = 1/4), or the
// equal-area octahedral map (core/equal_area.h) with camera space's y and z exchanged, so the
// map's centre looks up. Positions beyond the image (a wide pixel filter's samples) fold back
// onto the sphere as pbrt-v4 wraps them.
Vec3 CameraModel::spherical_direction(float u, float v) const {
    Vec3 d;  // in camera space (x right, y up, z forward) before the exchange of y and z
    if (cam_.spherical_mapping == scene::Camera::SphericalMapping::Equirectangular) {
        const float theta = kPi * v, phi = 2 * kPi * u;
        d = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    } else {
        if (u < 0)
            u = -u, v = 1 - v;
        else if (u > 1)
            u = 2 - u, v = 1 - v;
        if (v < 0)
            u = 1 - u, v = -v;
        else if (v > 1)
            u = 1 - u, v = 2 - v;
        d = equal_area_square_to_sphere(Vec2(std::clamp(u, 0.0f, 1.0f), std::clamp(v, 0.0f, 1.0f)));
    }
    return normalize(right_ * d.x + up_ * d.z + forward_ * d.y);
}

bool CameraModel::spherical_position(Vec3 dir, float& u, float& v) const {
    const float len = length(dir);
    if (!(len > 0)) return false;
    dir = dir / len;
    const Vec3 d(dot(dir, right_), dot(dir, forward_), dot(dir, up_));  // y and z exchanged back
    if (cam_.spherical_mapping == scene::Camera::SphericalMapping::Equirectangular) {
        const float theta = std::acos(std::clamp(d.z, -1.0f, 1.0f));
        float phi = std::atan2(d.y, d.x);
        if (phi < 0) phi += 2 * kPi;
        u = phi / (2 * kPi);
        v = theta / kPi;
    } else {
        const Vec2 uv = equal_area_sphere_to_square(d);
        u = uv.x;
        v = uv.y;
    }
    return true;
}

float CameraModel::spherical_pdf(Vec3 unit_dir) const {
    // Film positions are uniform over the rendered part of the image: per unit solid angle,
    // 1 / (4 pi) for the equal-area map, 1 / (2 pi^2 sin theta) for the equirectangular one, over
    // the part's share of the image.
    const float share = (float(film_w_) * float(film_h_)) / (float(width_) * float(height_));
    if (cam_.spherical_mapping == scene::Camera::SphericalMapping::EqualArea) return 1 / (4 * kPi * share);
    const float cos_theta = dot(unit_dir, up_);
    const float sin_theta = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
    if (!(sin_theta > 1e-6f)) return 0;
    return 1 / (2 * kPi * kPi * sin_theta * share);
}

}  // namespace phos::render
