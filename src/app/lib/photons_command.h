// `phos photons SCENE -o photons.ply`: traces the photon maps exactly as `phos render
// --integrator photonmap` would with the same options (same seed, same records) and writes them as
// a point cloud: PLY (binary, or --ascii) or the dissertation viewer's text format; with --view
// (output optional then) it also shows them in the 3-D photon viewer.
#pragma once

#include <string>
#include <vector>

#include "app/lib/render_options.h"
#include "core/stats.h"
#include "integrators/photon_map.h"
#include "io/mesh/point_cloud.h"
#include "scene/scene.h"

namespace phos::app {

struct PhotonsCommand {
    std::string scene_path;
    std::string output;
    std::string format = "ply";    // ply | text
    bool ascii = false;            // ASCII PLY instead of binary little-endian
    std::string maps;              // comma-separated map names; empty: every traced map
    bool view = false;             // --view: the 3-D photon viewer (display/photon_viewer.h)
    std::string screenshot;        // --screenshot FILE: the viewer draws one frame, writes it, closes
    std::string colour = "power";  // --colour power|map|bounces: the viewer's first colouring
    // The options phos render takes for the photon maps, under the same names: the photon-map and
    // scene tables, --seed, and --threads, -v, -q, --strict, --quality of the run table.
    RenderCommand settings;
};

// Adds the `photons` subcommand to `app`, filling `cmd` when parsed.
CLI::App* add_photons_command(CLI::App& app, PhotonsCommand& cmd, RegisterTable register_table);

// The photon maps of `scene` (loaded from settings.scene_path) traced as `phos render --integrator
// photonmap` traces them with `settings`' options, and the maps `kinds` (empty: every map traced)
// as a point cloud (photon_cloud.h); `bounces`: with each photon's bounce count. Throws InputError
// for bad options or a requested map that stays empty. Interrupted (interrupt::requested), the
// cloud is left empty.
struct PhotonTrace {
    integrators::PhotonMaps maps;
    std::vector<int> kinds;
    io::PointCloud cloud;
    bool interrupted = false;
};
PhotonTrace trace_photon_maps(const RenderCommand& settings, const scene::Scene& scene,
                              std::vector<int> kinds, bool bounces, Stats& stats);

// Runs it; throws ParseError / InputError for bad input (nothing is written). Returns the exit
// status: 0, or 128 + the signal when an interrupt stopped the tracing (nothing written).
int run_photons(const PhotonsCommand& cmd);

}  // namespace phos::app
