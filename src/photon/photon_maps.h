// The photon maps a photon-mapping render reads in its second pass (k-d trees with powers already
// divided by their emission count, the irradiance and volume caches, the volume beams), and their
// byte form: a checkpoint stores them so that a resumed render need not trace them again. Built by
// integrators/photon_map.cpp; the photon tools (app/lib/photon_cloud.h) read them too.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "photon/beam_bvh.h"
#include "photon/irradiance_cache.h"
#include "photon/kdtree.h"
#include "photon/tracer.h"
#include "photon/volume_cache.h"

namespace phos::photon {

struct PhotonMaps {
    PhotonKdTree map[kMapCount];
    uint64_t emitted[kMapCount] = {};
    IrradianceCache cache;  // empty unless --irradiance-cache
    // In-scattered light at volume photons for final-gather rays in media (with --irradiance-cache).
    VolumeCache volume_cache;
    // The volume maps' photons with their kernel radii for --volume-estimate beam (else empty).
    BeamBvh volume_beams, volume_caustic_beams;
    // Only from build_maps(..., record_bounces = true), for the photon tools: per photon of map[m]
    // (tree order), the scattering events before it was stored. Not part of save().
    std::vector<uint8_t> bounces[kMapCount];

    // All of the above as bytes (a checkpoint's payload) and back, exactly. load() refuses bytes
    // that are not a consistent set of maps (InputError naming `what`): whatever it returns can be
    // queried safely, even if the bytes did not come from save().
    std::string save() const;
    static PhotonMaps load(const std::string& bytes, const std::string& what);
    const PhotonKdTree& global() const { return map[kGlobalMap]; }
    const PhotonKdTree& caustic() const { return map[kCausticMap]; }
    const PhotonKdTree& indirect() const { return map[kIndirectMap]; }
    const PhotonKdTree& volume() const { return map[kVolumeMap]; }
    const PhotonKdTree& volume_caustic() const { return map[kVolumeCausticMap]; }
};

}  // namespace phos::photon
