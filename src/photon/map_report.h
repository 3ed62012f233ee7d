// The -v statistics of a photon-map build (pass 1 of --integrator photonmap): what each map holds
// and from how many emissions, the tracing's and the k-d trees' rates and thread time, pages
// faulted in, the MPI exchange; and the warning for a map the emission cap stopped short.
#pragma once

#include <cstdint>

#include "core/stats.h"
#include "photon/kdtree.h"
#include "photon/photon_maps.h"
#include "photon/tracer.h"

namespace phos::photon {

// How long pass 1 took, beside the counters the tracing keeps itself (TracedPhotons).
struct MapBuildTimes {
    uint64_t stored = 0;  // photons stored in all maps
    double trace_seconds = 0, build_seconds = 0;
    KdBuildStats build;  // the k-d trees' thread time by level, summed over the maps
};

// Adds the build's lines to `stats`: the beam BVH's memory (when built), the photons emitted, each
// map `to` wanted, the caustic projection maps, bytes per photon, the MPI exchange, pages faulted
// in, how busy the tracing threads were, and the tracing and build rates. Warns once per map whose
// target the emission cap (--max-emitted) cut short, unless the scene has no lights (the app warns
// of that).
void report_map_build(Stats& stats, const TraceOptions& to, const TracedPhotons& traced,
                      const PhotonMaps& maps, const MapBuildTimes& times, bool has_lights);

}  // namespace phos::photon
