// Options shared by every integrator (image size, sampling budget, seed, depth, shading switches),
// filled from the command line and the scene file's render settings (the CLI wins).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace phos::integrators {

struct RenderOptions {
    int width = 512;
    int height = 512;
    int spp = 16;  // samples per pixel (iterations for progressive integrators)
    uint64_t seed = 0;
    int max_depth = 16;             // path segments from the camera
    int dof_samples = 1;            // lens samples per pixel sample (--dof)
    bool ambient = false;           // add ka * ambient at the first hit (.scn legacy look)
    bool background_light = false;  // the background lights diffuse surfaces too
    bool layers = false;            // --layers: integrators record their component layers
    std::vector<std::string> aovs;  // --aov: auxiliary images (albedo, normal, depth)
};

}  // namespace phos::integrators
