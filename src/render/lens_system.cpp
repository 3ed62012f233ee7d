// Tracing through a realistic camera's lens system, as pbrt-v4's RealisticCamera defines it (PBR 4th
// ed., sec. 5.4.2-5.4.6; Kolb et al. 1995): interfaces are intersected in the lens-element space of
// the book (film at z = 0, lenses at z < 0, the scene towards -z), refracted by Snell's law, and
// blocked by their apertures; the rear element is placed by the thick-lens approximation, and rays
// are sampled over bounds of the exit pupil.
#include "render/lens_system.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/format.h"
#include "core/low_discrepancy.h"
#include "core/warp.h"

namespace phos::render {

namespace {

using Point = LensSystem::Point;
using LensRay = LensSystem::LensRay;

double dot(const Point& a, const Point& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Point scaled(const Point& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
Point normalized(const Point& a) { return scaled(a, 1 / std::sqrt(dot(a, a))); }
// Camera space and lens-element space differ by the sign of z.
LensRay flip_z(const LensRay& r) { return {{r.o.x, r.o.y, -r.o.z}, {r.d.x, r.d.y, -r.d.z}}; }

// The interface of curvature `radius` whose sphere is centred at z_center on the axis: the hit the
// ray meets on the side of the sphere the lens uses (the vertex's side), and its normal facing the
// ray's origin (PBR 4th ed., sec. 5.4.2).
bool intersect_spherical(double radius, double z_center, const LensRay& r, double& t, Point& n) {
    const Point o{r.o.x, r.o.y, r.o.z - z_center};
    const double a = dot(r.d, r.d), b = 2 * dot(r.d, o), c = dot(o, o) - radius * radius;
    const double disc = b * b - 4 * a * c;
    if (!(disc >= 0) || !(a > 0)) return false;
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    double t0 = q / a, t1 = q != 0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    // The vertex faces the scene (-z) for a positive radius: a ray heading to -z leaves the sphere
    // there (the far hit), one heading to +z enters it (the near hit); the other way round for a
    // negative radius.
    const bool closer = (r.d.z > 0) != (radius < 0);
    t = closer ? t0 : t1;
    if (!(t >= 0)) return false;
    n = normalized({o.x + t * r.d.x, o.y + t * r.d.y, o.z + t * r.d.z});
    if (dot(n, r.d) > 0) n = scaled(n, -1);
    return true;
}

// Snell's law: the direction transmitted from unit wi (pointing away from the surface, on n's
// side) into a medium `eta` times as dense; false for total internal reflection.
bool refract(const Point& wi, const Point& n, double eta, Point& wt) {
    const double cos_i = dot(n, wi);
    const double sin2_t = std::max(0.0, 1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return false;
    const double cos_t = std::sqrt(1 - sin2_t);
    wt = {-wi.x / eta + (cos_i / eta - cos_t) * n.x, -wi.y / eta + (cos_i / eta - cos_t) * n.y,
          -wi.z / eta + (cos_i / eta - cos_t) * n.z};
    return true;
}

// The ray r meets interface `e` with its vertex at z_vertex (lens-element space); false when it
// misses or is outside the aperture (a circle unless `shaped`). Moves r's origin to the hit; n is
// the normal there.
bool hit_interface(const scene::LensElement& e, double z_vertex, LensRay& r, Point& n, bool shaped = false) {
    double t = 0;
    if (e.curvature_radius == 0) {
        t = (z_vertex - r.o.z) / r.d.z;
        if (!(t >= 0)) return false;
    } else if (!intersect_spherical(e.curvature_radius, z_vertex + e.curvature_radius, r, t, n)) {
        return false;
    }
    const Point p = r.at(t);
    if (!shaped && p.x * p.x + p.y * p.y > double(e.aperture_radius) * double(e.aperture_radius))
        return false;
    r.o = p;
    return true;
}

}  // namespace

LensSystem::LensSystem(std::vector<scene::LensElement> elements, double focus_distance,
                       scene::ApertureImage aperture, double film_radius)
    : elements_(std::move(elements)), aperture_(std::move(aperture)), film_radius_(film_radius) {
    if (!aperture_.empty() && (aperture_.width <= 0 || aperture_.height <= 0 ||
                               aperture_.values.size() != size_t(aperture_.width) * size_t(aperture_.height)))
        throw InputError("Camera \"realistic\": the aperture image's size does not match its values");
    if (elements_.empty()) throw InputError("Camera \"realistic\": the lens system has no elements");
    for (scene::LensElement& e : elements_) {
        if (!(e.aperture_radius > 0))
            throw InputError("Camera \"realistic\": a lens element has no aperture (diameter 0)");
        if (e.eta == 0) e.eta = 1;  // pbrt-v4's lens files write air as 0 or 1
    }
    // Focusing (PBR 4th ed., sec. 5.4.4): with the thick lens's focal length f and principal planes
    // pz, moving the lens by delta images the plane z = -focus_distance onto the film when
    // 1/(pz[1] - z) + 1/(pz[0] + delta) = 1/f, solved for delta.
    double pz[2], fz[2];
    thick_lens(pz, fz);
    focal_length_ = fz[0] - pz[0];
    const double f = focal_length_, z = -focus_distance;
    const double c = (pz[1] - z - pz[0]) * (pz[1] - z - 4 * f - pz[0]);
    if (!(c > 0) || !(f > 0))
        throw InputError(printf_string(
            "Camera \"realistic\": the lens system (focal length %g) cannot focus at focusdistance %g", f,
            focus_distance));
    const double delta = 0.5 * (pz[1] - z + pz[0] - std::sqrt(c));
    const double rear = double(elements_.back().thickness) + delta;
    if (!(rear > 0))
        throw InputError(printf_string(
            "Camera \"realistic\": focusing at focusdistance %g moves the lens through the film",
            focus_distance));
    elements_.back().thickness = float(rear);
    if (film_radius_ > 0) {
        constexpr int kRings = 64;
        pupil_bounds_.resize(kRings);
        for (int i = 0; i < kRings; ++i)
            pupil_bounds_[size_t(i)] =
                bound_exit_pupil(film_radius_ * i / kRings, film_radius_ * (i + 1) / kRings);
    }
}

LensSystem::PupilBounds LensSystem::bound_exit_pupil(double x0, double x1) const {
    // Rays from film points spread over [x0, x1] to points of a square 1.5 times the rear
    // element's radius on each side, placed by the (2, 3) Halton sequence; the bounds of those that
    // pass, widened by twice the points' spacing to cover what passes between them.
    constexpr uint32_t kRays = 4096;
    const double half = 1.5 * rear_radius();
    const auto radical_inverse_3 = [](uint32_t i) {
        double r = 0, f = 1.0 / 3;
        for (; i > 0; i /= 3, f /= 3) r += f * double(i % 3);
        return r;
    };
    PupilBounds b{kInf, -kInf, kInf, -kInf};
    for (uint32_t i = 0; i < kRays; ++i) {
        const double fx = x0 + (x1 - x0) * (double(i) + 0.5) / kRays;
        const double px = -half + 2 * half * double(radical_inverse_bits(i)) * 0x1p-32;
        const double py = -half + 2 * half * radical_inverse_3(i);
        if (px >= b.x0 && px <= b.x1 && py >= b.y0 && py <= b.y1) continue;  // already inside
        if (trace({{fx, 0, 0}, {px - fx, py, rear_z()}}, nullptr, true) > 0) {
            b.x0 = std::min(b.x0, px), b.x1 = std::max(b.x1, px);
            b.y0 = std::min(b.y0, py), b.y1 = std::max(b.y1, py);
        }
    }
    if (b.x0 > b.x1) return {};  // no ray passes from this ring
    const double widen = 2 * (2 * half * std::sqrt(2.0)) / std::sqrt(double(kRays));
    return {b.x0 - widen, b.x1 + widen, b.y0 - widen, b.y1 + widen};
}

double LensSystem::front_z() const {
    double z = 0;
    for (const scene::LensElement& e : elements_) z += double(e.thickness);
    return z;
}

double LensSystem::aperture_transmission(double x, double y, double r) const {
    const double fx = (x / r + 1) / 2 * aperture_.width - 0.5, fy = (y / r + 1) / 2 * aperture_.height - 0.5;
    const double x0 = std::floor(fx), y0 = std::floor(fy), dx = fx - x0, dy = fy - y0;
    const auto at = [&](double px, double py) {
        if (px < 0 || py < 0 || px >= aperture_.width || py >= aperture_.height) return 0.0;
        return double(aperture_.values[size_t(py) * size_t(aperture_.width) + size_t(px)]);
    };
    return (1 - dx) * (1 - dy) * at(x0, y0) + dx * (1 - dy) * at(x0 + 1, y0) +
           (1 - dx) * dy * at(x0, y0 + 1) + dx * dy * at(x0 + 1, y0 + 1);
}

double LensSystem::trace_from_film(const LensRay& in, LensRay* out) const { return trace(in, out, false); }

double LensSystem::trace(const LensRay& in, LensRay* out, bool bounding) const {
    LensRay r = flip_z(in);
    double z = 0, weight = 1;
    for (int i = int(elements_.size()) - 1; i >= 0; --i) {
        const scene::LensElement& e = elements_[size_t(i)];
        z -= double(e.thickness);
        Point n;
        const bool stop = e.curvature_radius == 0;
        if (!hit_interface(e, z, r, n, stop && !aperture_.empty())) return 0;
        if (stop) {  // the stop only blocks, or passes a share of the light where it is shaped
            if (!aperture_.empty() && bounding) {
                const double ra = double(e.aperture_radius);
                if (r.o.x * r.o.x + r.o.y * r.o.y > 2 * ra * ra) return 0;  // beyond the square's corners
            } else if (!aperture_.empty()) {
                weight = aperture_transmission(r.o.x, r.o.y, double(e.aperture_radius));
                if (!(weight > 0)) return 0;
            }
            continue;
        }
        // From the medium behind the interface (towards the film) into the one in front of it.
        const double eta_i = e.eta, eta_t = i > 0 ? elements_[size_t(i) - 1].eta : 1.0;
        Point w;
        if (!refract(normalized(scaled(r.d, -1)), n, eta_t / eta_i, w)) return 0;
        r.d = w;
    }
    if (out) *out = flip_z(r);
    return weight;
}

bool LensSystem::trace_from_scene(const LensRay& in, LensRay* out) const {
    LensRay r = flip_z(in);
    double z = -front_z();
    for (size_t i = 0; i < elements_.size(); ++i) {
        const scene::LensElement& e = elements_[i];
        Point n;
        if (!hit_interface(e, z, r, n)) return false;
        if (e.curvature_radius != 0) {
            const double eta_i = i > 0 ? elements_[i - 1].eta : 1.0, eta_t = e.eta;
            Point w;
            if (!refract(normalized(scaled(r.d, -1)), n, eta_t / eta_i, w)) return false;
            r.d = w;
        }
        z += double(e.thickness);
    }
    if (out) *out = flip_z(r);
    return true;
}

void LensSystem::thick_lens(double pz[2], double fz[2]) const {
    // Rays parallel to the axis at a small height x: where the refracted ray crosses the axis is
    // the focal point, where it reaches height x again the principal plane (sec. 5.4.3).
    const double x = 0.001 * front_z();
    const auto cardinal = [](const LensRay& in, const LensRay& out, double& p, double& f) {
        const double tf = -out.o.x / out.d.x, tp = (in.o.x - out.o.x) / out.d.x;
        f = -(out.o.z + tf * out.d.z);
        p = -(out.o.z + tp * out.d.z);
        return std::isfinite(f) && std::isfinite(p);
    };
    LensRay scene_ray{{x, 0, front_z() + 1}, {0, 0, -1}}, film_ray;
    if (!trace_from_scene(scene_ray, &film_ray) || !cardinal(scene_ray, film_ray, pz[0], fz[0]))
        throw InputError(
            "Camera \"realistic\": no paraxial ray passes the lens system from the scene "
            "(is the aperture stop closed?)");
    film_ray = {{x, 0, rear_z() - 1}, {0, 0, 1}};
    if (!(trace_from_film(film_ray, &scene_ray) > 0) || !cardinal(film_ray, scene_ray, pz[1], fz[1]))
        throw InputError(
            "Camera \"realistic\": no paraxial ray passes the lens system from the film "
            "(is the aperture stop closed?)");
}

double LensSystem::generate(Vec2 film, Vec2 u, LensRay& out) const {
    // The rear-plane point and the area of the region it is uniform over (1 / its pdf).
    double px, py, area;
    if (pupil_bounds_.empty()) {
        const Vec2 d = warp::concentric_disk(u);
        const double r = rear_radius();
        px = d.x * r, py = d.y * r, area = kPi * r * r;
    } else {
        // The bounds of the film point's ring, found along +x, turned to the film point's angle.
        const double rf = std::sqrt(double(film.x) * film.x + double(film.y) * film.y);
        const size_t ring =
            std::min(pupil_bounds_.size() - 1, size_t(rf / film_radius_ * double(pupil_bounds_.size())));
        const PupilBounds& b = pupil_bounds_[ring];
        if (b.empty()) return 0;
        const double lx = b.x0 + (b.x1 - b.x0) * u.x, ly = b.y0 + (b.y1 - b.y0) * u.y;
        const double s = rf > 0 ? film.y / rf : 0, c = rf > 0 ? film.x / rf : 1;
        px = c * lx - s * ly, py = s * lx + c * ly, area = (b.x1 - b.x0) * (b.y1 - b.y0);
    }
    const LensRay from_film{{film.x, film.y, 0}, {px - film.x, py - film.y, rear_z()}};
    const double transmission = trace_from_film(from_film, &out);
    if (!(transmission > 0)) return 0;
    out.d = normalized(out.d);
    const double cos_theta = from_film.d.z / std::sqrt(dot(from_film.d, from_film.d));
    const double c2 = cos_theta * cos_theta;
    return transmission * c2 * c2 * area / (rear_z() * rear_z());
}

}  // namespace phos::render
