// Options shared by every integrator (image size, sampling budget, seed, depth, lens, shading
// switches, layers), filled from the command line and the scene file's render settings (the CLI
// wins). Their flags, defaults, ranges and help are in the option tables below (options.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/option_table.h"

namespace phos::render {

// The default --sharp-glossy exponent (see RenderOptions::sharp_glossy and docs/photon-mapping.md).
inline constexpr float kDefaultSharpGlossy = 10;
// The default --regularize exponent (see RenderOptions::regularize and docs/usage.md).
inline constexpr float kDefaultRegularize = 30;

struct RenderOptions {
    int width = 512;
    int height = 512;
    int spp = 16;  // samples per pixel (iterations for progressive integrators)
    uint64_t seed = 0;
    int max_depth = 16;  // path segments from the camera
    // Glossy lobes at least as sharp as a modified-Phong lobe of this exponent are followed by
    // camera paths like mirrors and glass, and photons scattered by them stay caustic photons
    // (Bsdf::split_lobes); photonmap, ppm and sppm read it (integrators/transport_options.h).
    float sharp_glossy = kDefaultSharpGlossy;
    // Path regularisation (path): after a rough bounce, lobes sharper than a Phong lobe of exponent
    // regularize x (s + 1)^(1/3) at camera sample s are widened to it (Bsdf::regularized); 0 = off.
    float regularize = kDefaultRegularize;
    int dof_samples = 1;       // lens samples per pixel sample (--dof)
    float lens_radius = -1;    // --dof aperture radius; < 0: the scene camera's own lens
    float focal_distance = 1;  // --dof focal distance (with lens_radius >= 0)
    bool ambient =
        false;  // ka * ambient seen, like the glow e, by camera rays and after mirror/glass bounces
    bool background_light = false;  // the background lights diffuse surfaces too
    bool layers = false;            // --layers: integrators record their component layers
    std::vector<std::string> aovs;  // --aov: auxiliary images (albedo, normal, depth)
};

// The option tables over RenderOptions: "Image" (size, layers, AOVs) and "Sampling" (samples,
// seed, depth, lens, shading switches).
const options::Table& image_options();
const options::Table& sampling_options();

// The auxiliary images --aov accepts.
const std::vector<std::string>& aov_names();

}  // namespace phos::render
