// A realistic camera's lens system: rays traced from the film through spherical lens interfaces
// and the aperture stop into the scene (Kolb, Mitchell and Hanrahan, "A Realistic Camera Model for
// Computer Graphics", SIGGRAPH 1995; Pharr, Jakob and Humphreys, "Physically Based Rendering", 4th
// ed., sec. 5.4: pbrt-v4's RealisticCamera).
#pragma once

#include <vector>

#include "core/vec.h"
#include "scene/camera.h"

namespace phos::render {

// Lens-system space is pbrt-v4's camera space: the film in the plane z = 0, the lenses in front of
// it at z > 0, looking along +z; x and y as the camera's right and up.
class LensSystem {
public:
    // A ray in lens-system space, in double precision (interfaces with long radii and small sags).
    struct Point {
        double x = 0, y = 0, z = 0;
    };
    struct LensRay {
        Point o, d;
        Point at(double t) const { return {o.x + d.x * t, o.y + d.y * t, o.z + d.z * t}; }
    };

    // The elements front to rear (scene::Camera::lens_elements). The rear element's distance to the
    // film is chosen so that the plane `focus_distance` from the film is in focus, by pbrt-v4's
    // thick-lens approximation (sec. 5.4.4). Throws InputError when the system passes no paraxial
    // ray or cannot focus that close. A non-empty `aperture` shapes the stop: its transmission
    // over the stop's bounding square replaces the circle. With film_radius > 0 (half the film's
    // diagonal) rays are sampled over bounds of the exit pupil precomputed for 64 rings of the
    // film, as pbrt-v4 does (sec. 5.4.6); with 0, over the whole rear element's disk.
    LensSystem(std::vector<scene::LensElement> elements, double focus_distance,
               scene::ApertureImage aperture = {}, double film_radius = 0);

    // Traces a ray leaving the film (origin at z = 0, heading to +z) through every interface and
    // returns the stop's transmission (1 for a circular stop); 0 when an element's aperture or the
    // stop blocks it, it misses an interface or is totally internally reflected. `out` is the ray
    // leaving the front element.
    double trace_from_film(const LensRay& in, LensRay* out) const;
    // The same from the scene towards the film (the thick-lens approximation's rays; the stop is a
    // circle here, as in pbrt-v4): false when blocked.
    bool trace_from_scene(const LensRay& in, LensRay* out) const;

    // The camera ray of film point (x, y) (z = 0) through the point of the rear element's plane
    // that lens sample `u` picks uniformly in the exit pupil's bounds of the film point's ring
    // (rotated to the film point's direction), or on the rear element's disk. Returns its weight (0:
    // blocked), pbrt-v4's transmission x cos^4(theta) / (pdf(rear point) rear_z^2), with theta the
    // angle of the film-to-rear segment to the axis: the film's measurement equation (sec. 5.4.5).
    double generate(Vec2 film, Vec2 u, LensRay& out) const;

    // z of the rear element's vertex (its distance from the film) and of the front element's.
    double rear_z() const { return elements_.back().thickness; }
    double front_z() const;
    double rear_radius() const { return elements_.back().aperture_radius; }
    // The effective focal length of the thick-lens approximation.
    double focal_length() const { return focal_length_; }
    const std::vector<scene::LensElement>& elements() const { return elements_; }

private:
    // Cardinal points of the thick-lens approximation: principal planes pz and focal points fz,
    // [0] on the film side and [1] on the scene side, as z in lens-element space (film at 0, lenses
    // at z < 0), as pbrt-v4 computes them.
    void thick_lens(double pz[2], double fz[2]) const;

    // An axis-aligned rectangle of the rear element's plane.
    struct PupilBounds {
        double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
        bool empty() const { return !(x1 > x0 && y1 > y0); }
    };
    // trace_from_film; `bounding` lets every ray within the stop's bounding circle (of a shaped
    // stop's whole square) pass: the exit pupil's bounds hold for every rotation of the stop.
    double trace(const LensRay& in, LensRay* out, bool bounding) const;
    // Bounds of the rear-plane points that rays from film points (x, 0), x in [x0, x1], pass
    // through (pbrt-v4's BoundExitPupil, with fewer rays and its widening by their spacing).
    PupilBounds bound_exit_pupil(double x0, double x1) const;

    // The shaped stop's transmission at (x, y) of the stop of radius r: the image bilinearly
    // interpolated, black outside it (pbrt-v4's Image::Bilerp with WrapMode::Black).
    double aperture_transmission(double x, double y, double r) const;

    std::vector<scene::LensElement> elements_;
    scene::ApertureImage aperture_;
    double focal_length_ = 0;
    double film_radius_ = 0;
    std::vector<PupilBounds> pupil_bounds_;  // per ring of the film, out to film_radius_
};

}  // namespace phos::render
