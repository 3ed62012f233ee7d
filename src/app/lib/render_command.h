// `phos render`: the function that runs a render from its options (render_options.h).
#pragma once

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "app/lib/render_options.h"
#include "core/image.h"
#include "core/progress.h"
#include "core/stats.h"
#include "render/prepared.h"
#include "scene/scene.h"

namespace phos::app {

// The scene of `cmd` loaded as the render loads it (reading switches, --no-emission-lights).
scene::Scene load_render_scene(const RenderCommand& cmd);
// The scene file's integrator parameters (pbrt `Integrator "sppm" "float radius" ...`) mapped onto
// the option tables by name, for options the command line did not give; returns the names set. A
// value outside the option's range is an error at the parameter; a parameter no option takes is a
// warning for the scene's own integrator (an error with --strict).
std::set<std::string> apply_scene_parameters(RenderCommand& cmd, const scene::Scene& scene);
// The --quality preset's options, except those given on the command line or set by the scene file
// (`from_scene`); the sample count only while `spp_source` (where it came from) is still a default,
// which then names the preset.
void apply_quality(RenderCommand& cmd, const std::set<std::string>& from_scene, std::string& spp_source);
// The image side that was not given, from the one that was (`side`), keeping the scene's aspect
// ratio `scene_other` : `scene_side` (at least 1 pixel).
int keep_aspect(int side, int scene_side, int scene_other);
// How the scene is prepared for rendering (shading switches, --dof lens).
render::PrepareOptions prepare_options(const RenderCommand& cmd);

// Where layer `layer` of `output` is written: out.png -> out.caustic.png.
std::string layer_path(const std::string& output, const std::string& layer);

// What a render made, for a caller that keeps it in memory (the Python module).
struct RenderResult {
    Image image;                                        // the final image (linear RGB)
    std::vector<std::pair<std::string, Image>> layers;  // --layers' components and the --aov images
    integrators::IntegratorKind integrator{};           // the one that rendered
    render::RenderDone done;
    double seconds = 0;  // the render's wall time (loading and preparing not counted)
    RayCounts rays;
    uint64_t photons = 0;  // photons emitted (photon-based integrators)
    bool interrupted = false;
};

// How a caller running renders in process changes run_render.
struct RenderHooks {
    const scene::Scene* scene = nullptr;  // the scene already loaded from cmd.scene_path, else loaded
    RenderResult* result = nullptr;       // set: the images land here and nothing is written
    Progress* progress = nullptr;         // set: progress is reported here instead of on stderr
    bool signal_handlers = true;          // false: the caller stops the render (interrupt::request)
};

// Runs the render; throws ParseError / InputError for bad input. Returns the exit status: 0, or
// 128 + the signal (130 SIGINT, 143 SIGTERM) when an interrupt stopped it (the image so far, and
// the checkpoint with --checkpoint, are written first).
int run_render(const RenderCommand& cmd, const RenderHooks& hooks = {});

}  // namespace phos::app
