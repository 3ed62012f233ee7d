// Options of the two-pass photon-map integrator (--integrator photonmap): the struct the integrator
// reads and its option table (photon_map_options.cpp: flags, defaults, ranges, help); documented in
// docs/photon-mapping.md and the generated docs/options.md.
#pragma once

#include <cstdint>
#include <string>

#include "core/option_table.h"
#include "photon/filter.h"

namespace phos::integrators {

// How camera rays gather the volume maps' light (docs/media.md): one beam radiance estimate per
// stretch (Jarosz, Zwicker & Jensen 2008) or ray marching with a k-nearest estimate per step.
enum class VolumeEstimate { Beam, March };

// Budget and density-estimate settings of one photon map.
struct PhotonMapSettings {
    uint64_t photons = 0;       // stored photons wanted (0 = all photons of --photons emitted ones)
    uint32_t samples = 0;       // k of the k-nearest-neighbour estimate
    float radius = 0;           // maximum estimate radius in scene units; 0 = automatic (see radius_fraction)
    float radius_fraction = 0;  // automatic radius = this x the scene's bounding-sphere radius
    photon::FilterKind filter = photon::FilterKind::Box;
    float cone_k = 1.1f;
};

struct PhotonMapOptions {
    PhotonMapSettings global{200000, 100, 0, 0.1f, photon::FilterKind::Box, 1.1f};
    PhotonMapSettings caustic{100000, 60, 0, 0.05f, photon::FilterKind::Cone, 1.1f};
    PhotonMapSettings indirect{200000, 100, 0, 0.1f, photon::FilterKind::Box, 1.1f};
    // Participating media (docs/media.md): multiple scattering and volume caustics, box kernel.
    PhotonMapSettings volume{200000, 60, 0, 0.1f, photon::FilterKind::Box, 1.1f};
    PhotonMapSettings volume_caustic{200000, 40, 0, 0.05f, photon::FilterKind::Box, 1.1f};
    VolumeEstimate volume_estimate = VolumeEstimate::Beam;
    float volume_step = 0;            // ray-marching step along camera rays in media (0 = automatic)
    uint64_t photons = 0;             // --photons: photons to emit (0 = until the map budgets are met)
    uint64_t max_emitted = 0;         // stop emitting here even if a budget is unmet (0 = automatic)
    int max_photon_depth = 16;        // scattering events per photon path
    int gather_rays = 8;              // final-gather rays per camera sample
    bool fast_global = false;         // indirect map estimate at the first hit instead of final gather
    bool photon_viz = false;          // debug view: global map's radiance estimate at the first hit
    bool irradiance_cache = true;     // precomputed irradiance for final-gather lookups (Lambertian hits)
    float caustic_min_pixels = 1.0f;  // caustic estimate radius >= this many pixel footprints
    bool projection_maps = true;      // caustic photons emitted only towards specular objects
    uint32_t cache_stride = 4;        // one cache point per this many global photons
    float normal_cos = 0.9f;          // surface test: min cosine between photon and query normals
    float flatness = 0.2f;            // surface test: max |h| / d off the tangent plane
    // Components (the --no-* switches clear them).
    bool direct = true, caustics = true, indirect_light = true, specular = true, transmissive = true;
};

// The "Photon map" option table over PhotonMapOptions.
const options::Table& photon_map_options();

}  // namespace phos::integrators
