// Photon density estimates at a surface point (Jensen 2001, eq. 7.6): the k nearest photons within
// a maximum radius, each weighted by the BSDF (or 1 for irradiance) and a kernel filter, divided by
// the area of the disk they cover. A surface test keeps only photons from the query's own surface:
// the stored normal must agree with the query normal and the photon must lie close to the tangent
// plane (a flattened search region), so light does not leak through thin walls or into corners.
#pragma once

#include <cstdint>

#include "core/vec.h"
#include "photon/filter.h"
#include "photon/kdtree.h"
#include "shading/bsdf.h"

namespace phos::photon {

struct EstimateOptions {
    uint32_t k = 50;          // photons per estimate
    float max_radius = 0.1f;  // scene units; a query that finds fewer than k photons uses this radius
    KernelFilter filter;      // box / cone / Gauss
    float normal_cos = 0.9f;  // minimum cosine between the photon's normal and the query's
    // Maximum |dot(p - x, n)| / |p - x| (sine of the angle between the tangent plane and the
    // direction to the photon): rejects photons above or below the plane, e.g. on a parallel
    // surface a few millimetres away. 0.2 ~ 11.5 degrees; <= 0 disables the test.
    float flatness = 0.2f;
};

// Where and how the estimate is taken.
struct SurfaceQuery {
    Vec3 p;                    // the surface point
    Vec3 n;                    // geometric normal, oriented towards the side light is reflected to (wo)
    bool accept_back = false;  // also accept photons that arrived on the other side (diffuse transmission)
    // The estimate's radius never shrinks below this (capped at max_radius): where photons are
    // very dense (a caustic's focus) k photons fit in a disk far smaller than a pixel, and the
    // estimate becomes a narrow spike that a few pixel samples hit or miss. Gathering every photon
    // within about a pixel footprint instead averages the spike over the pixel, as the film does.
    float min_radius = 0;
};

// Builds the query for a hit seen from direction wo (unit, pointing away from the surface).
SurfaceQuery make_query(Vec3 p, Vec3 ng, Vec3 wo, const shading::Bsdf& bsdf);

// True if photon `ph` passes the surface test of `q` (normal agreement, near the tangent plane).
bool accept_photon(const Photon& ph, const SurfaceQuery& q, const EstimateOptions& o);

// Reflected radiance towards wo, as linear sRGB: sum f(wo, wi_p) Phi_p w_p / (mean_w pi r^2) over
// the accepted neighbours, f = the non-delta BSDF lobes, each photon's term evaluated at its own
// wavelengths and taken to colour there. Lambertian-only BSDFs take a fast path (kd / pi at the
// photon's wavelengths, no per-photon BSDF evaluation). `n_used` (optional) receives the photon count,
// `radius_used` (optional) the disc's radius (the search radius when no photon was found).
Rgb radiance_estimate(const PhotonKdTree& map, const EstimateOptions& o, const SurfaceQuery& q, Vec3 wo,
                      const shading::Bsdf& bsdf, uint32_t* n_used = nullptr, float* radius_used = nullptr);

// Irradiance sum Phi_p w_p / (mean_w pi r^2) at q, as linear sRGB.
Rgb irradiance_estimate(const PhotonKdTree& map, const EstimateOptions& o, const SurfaceQuery& q,
                        uint32_t* n_used = nullptr);

}  // namespace phos::photon
