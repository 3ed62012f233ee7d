// Jensen's two-pass photon mapping (--integrator photonmap): pass 1 traces photons into the global,
// caustic and (for --fast-global) indirect maps; pass 2 renders each pixel sample by following
// mirrors and glass from the camera and, at the first non-specular hit, adding direct light (shadow
// rays), caustics (caustic map) and indirect light (final gather into the global map, optionally
// through the precomputed irradiance cache). With --layers the components also go to the film
// layers "direct", "caustic", "indirect" and "specular" (see docs/photon-mapping.md).
#pragma once

#include <memory>

#include "integrators/integrator.h"
#include "integrators/photon_map_options.h"
#include "integrators/render_budget.h"
#include "photon/beam_bvh.h"
#include "photon/irradiance_cache.h"
#include "photon/kdtree.h"
#include "photon/tracer.h"
#include "photon/volume_cache.h"

namespace phos::integrators {

// The photon maps built by pass 1 (kd-trees with powers already divided by their emission count).
struct PhotonMaps {
    photon::PhotonKdTree map[photon::kMapCount];
    uint64_t emitted[photon::kMapCount] = {};
    photon::IrradianceCache cache;  // empty unless --irradiance-cache
    // In-scattered light at volume photons for final-gather rays in media (with --irradiance-cache).
    photon::VolumeCache volume_cache;
    // The volume maps' photons with their kernel radii for --volume-estimate beam (else empty).
    photon::BeamBvh volume_beams, volume_caustic_beams;
    // Only from build_maps(..., record_bounces = true), for the photon tools: per photon of map[m]
    // (tree order), the scattering events before it was stored. Not part of save().
    std::vector<uint8_t> bounces[photon::kMapCount];

    // All of the above as bytes (a checkpoint's payload) and back, exactly: a resumed render reads
    // its maps instead of tracing them again. `what` names the source in errors.
    std::string save() const;
    static PhotonMaps load(const std::string& bytes, const std::string& what);
    const photon::PhotonKdTree& global() const { return map[photon::kGlobalMap]; }
    const photon::PhotonKdTree& caustic() const { return map[photon::kCausticMap]; }
    const photon::PhotonKdTree& indirect() const { return map[photon::kIndirectMap]; }
    const photon::PhotonKdTree& volume() const { return map[photon::kVolumeMap]; }
    const photon::PhotonKdTree& volume_caustic() const { return map[photon::kVolumeCausticMap]; }
};

class PhotonMapIntegrator : public Integrator {
public:
    explicit PhotonMapIntegrator(const PhotonMapOptions& options, RenderBudget budget = {});
    void render(const Prepared& prepared, film::Film& film, Progress& progress) override;

    // Pass 1 alone (photon tracing, k-d trees, irradiance cache), reporting to prepared.stats.
    // Exposed for tests and benchmarks. An interrupt during tracing leaves the maps incomplete:
    // render() then takes no samples.
    // With `record_bounces`, the maps also keep each photon's bounce count (PhotonMaps::bounces).
    PhotonMaps build_maps(const Prepared& prepared, bool record_bounces = false) const;
    // Pass 2 with given maps, in sample passes within the budget (pixel_loop.h).
    // With `store_maps`, each checkpoint also holds the maps (PhotonMaps::save).
    void render_with(const Prepared& prepared, const PhotonMaps& maps, film::Film& film, Progress& progress,
                     bool store_maps = false) const;

    const PhotonMapOptions& options() const { return options_; }

private:
    PhotonMapOptions options_;
    RenderBudget budget_;
};

}  // namespace phos::integrators
