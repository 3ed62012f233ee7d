// Jensen's two-pass photon mapping (--integrator photonmap): pass 1 traces photons into the global,
// caustic and (for --fast-global) indirect maps; pass 2 renders each pixel sample by following
// mirrors and glass from the camera and, at the first non-specular hit, adding direct light (shadow
// rays), caustics (caustic map) and indirect light (final gather into the global map, optionally
// through the precomputed irradiance cache). With --layers the components also go to the film
// layers "direct", "caustic", "indirect" and "specular" (see docs/photon-mapping.md).
#pragma once

#include <memory>
#include <vector>

#include "integrators/integrator.h"
#include "integrators/photon_map_options.h"
#include "photon/photon_maps.h"
#include "photon/tracer.h"
#include "render/path_radiance.h"
#include "render/render_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

// The maps pass 1 builds (photon/photon_maps.h).
using photon::PhotonMaps;

class PhotonMapIntegrator : public Integrator {
public:
    // `layers`: the components recorded with --layers (the registry gives all four).
    explicit PhotonMapIntegrator(const PhotonMapOptions& options, RenderBudget budget = {},
                                 std::vector<Component> layers = {});
    RenderDone render(const Prepared& prepared, film::Film& film, Progress& progress) override;

    // Pass 1 alone (photon tracing, k-d trees, irradiance cache), reporting to prepared.stats.
    // Exposed for tests and benchmarks. An interrupt during tracing leaves the maps incomplete:
    // render() then takes no samples.
    // With `record_bounces`, the maps also keep each photon's bounce count (PhotonMaps::bounces).
    PhotonMaps build_maps(const Prepared& prepared, bool record_bounces = false) const;
    // Pass 2 with given maps, in sample passes within the budget (pixel_loop.h).
    // With `store_maps`, each checkpoint also holds the maps (PhotonMaps::save).
    RenderDone render_with(const Prepared& prepared, const PhotonMaps& maps, film::Film& film,
                           Progress& progress, bool store_maps = false) const;

    const PhotonMapOptions& options() const { return options_; }

private:
    PhotonMapOptions options_;
    RenderBudget budget_;
    std::vector<Component> layers_;
};

}  // namespace phos::integrators
