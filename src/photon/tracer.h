// The photon-tracing pass of the two-pass photon mapper: emits photons (photon_path.h) on all cores
// in fixed batches of photon indices and sorts the non-specular hits into the global (L{S|D|V}*D),
// caustic (LS+D) and indirect (L{S|D|V}*{D|V}D) maps, and the scattering events in media into the
// volume (L{S|D|V}*{D|V}V: multiple scattering) and volume caustic (LS+V) maps, each up to its own
// budget of stored photons. Photons straight from a light (single scattering, LV) are not stored:
// the renderer computes them by light sampling.
//
// With projection maps (the default) the caustic map has its own emission stream: photons leave
// the lights only towards specular objects (projection_map.h); its N counts those emissions.
//
// Determinism: photon i's random numbers depend only on (seed, i); batch b (indices
// [b * batch_size, (b + 1) * batch_size)) writes its own slice, slices are committed to the maps
// in batch order, and a map is cut after the exact emission that met its target, however many
// batches are in flight (the threads') or past the cut. So the maps are bit-identical at any
// thread count (and rank count); the statistics (rays, total emitted) count the batches up to
// the last cut and are identical for a given thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "photon/photon.h"
#include "photon/photon_path.h"

namespace phos::photon {

enum MapKind : int {
    kGlobalMap = 0,
    kCausticMap = 1,
    kIndirectMap = 2,
    kVolumeMap = 3,
    kVolumeCausticMap = 4,
    kMapCount = 5
};
const char* map_name(int kind);  // "global", "caustic", "indirect", "volume", "volume caustic"

struct TraceOptions {
    // Per map: wanted = false leaves the map empty (no photon is stored in it). A wanted map with
    // target > 0 stores photons until it holds `target` of them (the photons of the emission that
    // crossed the target included) and then stops; target == 0 means "every photon of the
    // `emit` emitted ones".
    bool wanted[kMapCount] = {true, true, false, false, false};
    uint64_t target[kMapCount] = {0, 0, 0, 0, 0};
    uint64_t emit = 0;      // photons to emit; 0 = until every target is met
    uint64_t max_emit = 0;  // stop emitting here even if a target is not met (0 = 2^32 - 1)
    int max_depth = 16;     // scattering events per photon path
    uint64_t seed = 0;
    // Emissions per batch (no effect on the maps). A batch's stored photons, their directions and
    // the sort's scratch stay within a core's cache at 2048 (~0.2 MB): 4096 traced 2-3 % slower.
    uint32_t batch_size = 2048;
    // Caustic map through projection maps (projection_map.h): its photons come from a second
    // stream emitted only towards specular objects. Off: one stream fills every map.
    bool caustic_projection = true;
    int projection_resolution = 128;  // cells per side of each light's direction map
    // Also record each stored photon's bounce count (TracedPhotons::bounces; for the photon tools).
    bool record_bounces = false;
    // Trace 16 photons at a time through Embree's packet interface where nothing but surfaces
    // stops a photon (no active media, no interface-only surfaces); the maps are identical to the
    // one-at-a-time tracer's (false: always one at a time; tests compare the two).
    bool packets = true;
};

struct TracedPhotons {
    std::vector<Photon> photons[kMapCount];  // power already divided by emitted[m]
    // With TraceOptions::record_bounces, per photon of photons[m]: the scattering events before it
    // was stored (0 = straight from a light), at most 255. Empty otherwise.
    std::vector<uint8_t> bounces[kMapCount];
    uint64_t emitted[kMapCount] = {};  // N of each map (photon power = flux share / N)
    bool reached[kMapCount] = {};      // the target was met (false if capped by max_emit)
    // Photon paths and rays of the batches committed up to the last map's cut (or the emission
    // cap); batches traced past it are left out.
    uint64_t total_emitted = 0;
    uint64_t rays = 0;
    double caustic_fraction = 1;    // share of the emitted power the projection maps sample
    double projection_seconds = 0;  // building the projection maps
    double caustic_seconds = 0;     // tracing the caustic stream (projection maps only)
    double exchange_seconds = 0;    // under MPI: exchanging the batches between ranks
    // The maps' reserved pages, faulted in on all cores before the photons are written there (part
    // of the tracing time; the first touch of memory is the costliest part of writing it).
    uint64_t faulted_bytes = 0;
    double fault_in_seconds = 0;
    uint64_t exchanged_bytes = 0;  // under MPI: the batches' bytes (every rank receives them all)
    // Where the tracing threads' time went (-v, for scaling): the streams' pipelines (or rounds)
    // from start to end, the batches' own time summed over all threads, and the commits (serial:
    // one thread at a time copies a batch into the maps). batch_seconds / (threads x
    // pipeline_seconds) is how busy the threads were.
    double pipeline_seconds = 0;
    double batch_seconds = 0;
    double commit_seconds = 0;
    int threads = 0;
    uint64_t stored() const {
        uint64_t n = 0;
        for (const auto& p : photons) n += p.size();
        return n;
    }
};

// Traces photons in the calling thread's oneTBB arena. A scene without lights gives empty maps.
TracedPhotons trace_photons(const PhotonScene& ps, const TraceOptions& options);

// The batches in flight at once with `threads` threads on each rank (trace_photons takes every
// rank's most). In one process, 4 per thread (8 to 1024): the pipeline's tokens, batches traced or
// waiting for their commit; a batch stores into the maps still active that many batches earlier,
// so after a map's cut at most that many batches still trace its photons. Under MPI, the most
// batches of a round: 16 per thread and rank (32 to 1024), enough that the exchange after each
// round is rare. Each batch holds its photons until committed (the memory estimate counts them).
uint64_t batches_in_flight(int threads);

}  // namespace phos::photon
