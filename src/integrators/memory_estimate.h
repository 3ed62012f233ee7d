// The peak memory a render will need, estimated before any work from the loaded scene and the
// options: the largest of the render's phases (BVH build, photon tracing, k-d tree build, caches,
// the pixel loop or progressive iterations, writing), each the sum of what it holds. The bytes per
// item model what the code allocates, with constants measured on this code (docs/usage.md,
// "Memory"); phos render refuses a render whose estimate exceeds the memory available.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "integrators/photon_map_options.h"
#include "integrators/progressive_options.h"
#include "integrators/registry.h"
#include "render/options.h"
#include "scene/scene.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

struct MemoryItem {
    std::string name;  // "photon maps", "scene", "accelerator", "film"...
    uint64_t bytes = 0;
};

struct MemoryEstimate {
    uint64_t total = 0;             // the estimated peak resident memory, bytes
    std::string phase;              // the phase at the peak ("photon map build", "render"...)
    std::vector<MemoryItem> items;  // what that phase holds, largest first
    // "photon maps 30.0 GB, scene 1.20 GB, accelerator 420 MB" (the `max_items` largest).
    std::string breakdown(size_t max_items = 4) const;
};

// What the estimate reads besides the scene.
struct MemoryEstimateInputs {
    IntegratorKind integrator = IntegratorKind::PhotonMap;
    RenderOptions render;
    PhotonMapOptions photon_map;
    ProgressiveOptions progressive;
    int threads = 0;          // worker threads (0 = all cores)
    bool checkpoint = false;  // checkpoints are saved (an encoded copy of the state)
};

MemoryEstimate estimate_memory(const scene::Scene& scene, const MemoryEstimateInputs& inputs);

}  // namespace phos::integrators
