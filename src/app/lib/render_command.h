// `phos render`: the options it takes and the function that runs a render from them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "integrators/factory.h"
#include "integrators/options.h"

namespace phos::app {

struct RenderCommand {
    std::string scene_path;
    std::string output;
    std::optional<int> width, height, spp, aa, max_depth;
    std::optional<std::string> integrator;
    int threads = 0;  // 0 = all cores
    uint64_t seed = 0;
    bool verbose = false;
    bool quiet = false;
    float exposure = 0;
    bool schlick = false;
    bool legacy_attenuation = false;
    bool emission_lights = false;  // glowing .scn surfaces become area lights
    bool real = false;
    bool ambient = false;
    bool background_light = false;
    bool strict = false;
    // --dof SAMPLES DISTANCE RADIUS
    std::optional<int> dof_samples;
    float dof_distance = 1, dof_radius = 0;
    // also write every film layer (direct, indirect, caustic, specular...) next to the output
    bool layers = false;
    integrators::IntegratorConfig config;
    // The arguments of this render (for checkpoints: a bare --resume replays them).
    std::vector<std::string> command_line;
    // progress bar: -1 auto (when stderr is a terminal), 0 off, 1 on
    int progress = -1;
};

// Where layer `layer` of `output` is written: out.png -> out.caustic.png.
std::string layer_path(const std::string& output, const std::string& layer);

// Runs the render; throws ParseError / InputError for bad input.
void run_render(const RenderCommand& cmd);

}  // namespace phos::app
