// pbrt-v4's portal for an infinite light (PortalImageInfiniteLight, PBRT 4th ed. ch. 12; after
// Bitterli et al. 2015, "Portal-masked environment map sampling", with pbrt's angle mapping): the
// environment is resampled once into the portal's own frame (x along p3 - p0, y along p1 - p0,
// z = x × y, the side the sky is on), as an image over the square of angles
//   u = (atan2(w.x, w.z) + pi/2) / pi,   v = (atan2(w.y, w.z) + pi/2) / pi   (w.z > 0),
// whose Jacobian is dw / d(u, v) = pi^2 (1 - w.x^2)(1 - w.y^2) / w.z. Because u and v are monotone
// in w.x / w.z and w.y / w.z, the directions from a point p through the portal rectangle are exactly
// the (u, v) window between the images of p0 - p and p2 - p: sampling a direction through the portal
// is sampling a piecewise-constant distribution (pixel average x Jacobian at its centre) restricted
// to that window, with solid-angle pdf pdf_uv / J. The radiance is the nearest pixel of the
// resampled image (pbrt-v4's lookup).
//
// Photons (the light's emission for photon mapping and light subpaths) start uniformly on the
// portal rectangle and travel into the scene along -w, w drawn over the whole (u, v) square by
// pixel average x Jacobian x cos(theta_portal); the position density in the plane perpendicular to
// w is 1 / (A cos theta_portal), A the portal's area.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "core/frame.h"
#include "core/vec.h"
#include "shading/distribution2d.h"
#include "shading/windowed_distribution2d.h"

namespace phos::shading {

class LightPortal {
public:
    LightPortal() = default;
    // `corners`: pbrt-v4's four world-space points (a rectangle, checked by the loader); `radiance`
    // gives the environment's RGB radiance arriving from a world direction, sampled (once) at the
    // centres of an nu x nv image.
    LightPortal(const std::array<Vec3, 4>& corners, int nu, int nv, const std::function<Rgb(Vec3)>& radiance);

    bool empty() const { return nu_ == 0; }
    Vec3 normal() const { return frame_.n; }
    // (u, v) of a world direction w (unit, towards the sky) and the Jacobian dw/d(u, v); nullopt
    // behind the portal's plane (w . normal <= 0).
    std::optional<Vec2> uv_of(Vec3 w, float* jacobian = nullptr) const;
    Vec3 direction_of(Vec2 uv, float* jacobian = nullptr) const;
    // The resampled radiance at a direction through the portal's plane (0 behind it).
    Rgb radiance(Vec3 w) const;
    // The directions from p through the rectangle as a (u, v) window (nullopt: p is not in front of it).
    std::optional<UvWindow> window(Vec3 p) const;
    // A direction from p through the portal and its solid-angle density (nullopt: none).
    std::optional<Vec3> sample_towards(Vec3 p, Vec2 u, float* pdf) const;
    float pdf_towards(Vec3 p, Vec3 w) const;
    // A photon: its start on the portal, the sky direction w it comes from (it travels along -w), the
    // position density (perpendicular to w) and the solid-angle density of w.
    struct Emission {
        Vec3 origin, w;
        float pdf_pos = 0, pdf_dir = 0;
    };
    std::optional<Emission> sample_emission(Vec2 u_pos, Vec2 u_dir) const;
    // The densities sample_emission has for sky direction w.
    void pdf_emission(Vec3 w, float& pdf_pos, float& pdf_dir) const;
    // The flux through the portal, A * integral of L(w) cos(theta_portal) over the hemisphere (pixel
    // centres), what photons carry on average.
    Rgb flux() const { return flux_; }
    // The integral of the radiance over the portal's hemisphere (pixel centres).
    Rgb integral() const { return integral_; }
    float area() const { return area_; }

private:
    Rgb pixel(Vec2 uv) const;

    std::array<Vec3, 4> corners_{};
    Frame frame_;  // x along p3 - p0, y along p1 - p0, z = x × y
    float area_ = 0;
    int nu_ = 0, nv_ = 0;
    std::vector<Rgb> image_;          // nu x nv, row-major, v = row
    WindowedDistribution2D towards_;  // pixel average x Jacobian (sample_towards)
    Distribution2D emission_;         // pixel average x Jacobian x cos (photons)
    Rgb flux_{0.0f}, integral_{0.0f};
};

}  // namespace phos::shading
