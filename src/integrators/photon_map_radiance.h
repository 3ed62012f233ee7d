// Pass 2 of the photon mapper, per camera ray: the split of the radiance into direct, caustic,
// indirect and specular components (Jensen 2001, ch. 9), and final gathering.
#pragma once

#include "core/rng.h"
#include "core/stats.h"
#include "integrators/photon_map.h"
#include "photon/beam_estimate.h"
#include "photon/estimate.h"
#include "photon/volume_estimate.h"
#include "render/pixel_loop.h"
#include "render/prepared.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class PhotonMapRadiance {
public:
    PhotonMapRadiance(const Prepared& P, const PhotonMapOptions& o, const PhotonMaps& maps);
    // Spectra: a camera ray draws its wavelengths (render::camera_wavelengths) and carries its
    // throughput at them; light sampling and emission are evaluated there, while a photon estimate
    // is a colour (each photon at its own wavelengths), which meets the throughput as
    // spectrum::colour_through says. The image's colour is returned.
    RadianceParts camera_ray(Ray ray, Sampler& sampler, RayCounts& rays) const;

    // Indirect radiance reflected at a non-specular hit towards wo by final gathering, times the
    // path's throughput `beta` at `lambda`, as colour.
    Rgb final_gather(const accel::SurfaceHit& hit, const shading::Bsdf& bsdf, Vec3 wo, int medium,
                     const Spectrum& beta, const Wavelengths& lambda, Sampler& sampler,
                     RayCounts& rays) const;
    // Radiance along `ray` (starting in `medium`) as the global map sees it, times `beta`, as
    // colour: follows delta bounces, then takes the global estimate (or the irradiance cache) at
    // each non-specular hit; emitters give nothing. In media it samples a free flight and, where
    // the ray scatters, takes the light in-scattered there (light sampling plus the volume maps).
    Rgb gather_ray(Ray ray, int medium, Spectrum beta, Wavelengths lambda, Sampler& sampler,
                   RayCounts& rays) const;

    // Light scattered towards the camera along one stretch of a camera ray in a medium (Jensen &
    // Christensen 1998, eq. 12: by the beam radiance estimate or by ray marching, as
    // --volume-estimate says), split as the surface radiance is, and the stretch's transmittance:
    // single scattering (with the medium's emission) and T at the path's wavelengths, the volume
    // maps' estimates as colours (attenuated along the stretch by the colour of sigma_t).
    struct MediumStretch {
        Spectrum single, T{1.0f};
        Rgb caustic, multiple;
    };
    MediumStretch march(const shading::Medium& medium, int medium_index, Vec3 o, Vec3 d, float t_end,
                        const Wavelengths& lambda, Sampler& sampler, RayCounts& rays) const;

    const photon::EstimateOptions& estimate_options(int map) const { return est_[map]; }
    // Map m's density estimate at q (global, caustic or indirect), a lookup --trace-pixel records.
    Rgb estimate(int m, const photon::SurfaceQuery& q, Vec3 wo, const shading::Bsdf& bsdf) const;

private:
    const Prepared& P_;
    const PhotonMapOptions& o_;
    const PhotonMaps& maps_;
    photon::EstimateOptions est_[photon::kMapCount];
    photon::VolumeEstimateOptions volume_est_, volume_caustic_est_;
    // The caustic estimate's minimum radius at distance d along a camera path: offset + slope d
    // (pixel footprints measured at the image centre, times the option's pixel count).
    float footprint_offset_ = 0, footprint_slope_ = 0;
};

}  // namespace phos::integrators
