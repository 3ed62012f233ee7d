// What `phos render` is told: the run's own options (output, integrator, threads, messages), the
// scene-reading and shading switches, and every integrator's option struct, each with its option
// table. The tables drive the command line, --help, validation, checkpoints, pbrt Integrator
// parameters and docs/options.md (`phos options --markdown`).
#pragma once

#include <set>
#include <string>
#include <vector>

#include "core/option_table.h"
#include "integrators/photon_map_options.h"
#include "integrators/progressive_options.h"
#include "integrators/registry.h"
#include "integrators/transport_options.h"
#include "render/options.h"
#include "render/render_budget.h"

namespace CLI {
class App;
}

namespace phos::app {

// Where `--tev` streams when given without HOST:PORT (tev's own default).
inline constexpr const char* kTevDefault = "127.0.0.1:14158";

// --quality: budget presets (quality_preset).
enum class Quality { Draft, Normal, High };
const options::Choices<Quality>& quality_choices();

// Options of the run itself (none changes the image's radiance).
struct RunOptions {
    std::string output;  // empty: the scene file's Film filename, else a default (render_command.cpp)
    // The scene file's integrator when it names one (pbrt files always do: pbrt's default is
    // volpath), else the photon mapper, as in both seed renderers.
    integrators::IntegratorKind integrator = integrators::IntegratorKind::PhotonMap;
    int threads = 0;  // 0 = all cores
    bool verbose = false;
    bool quiet = false;
    bool progress = false;  // forced on or off (given on the command line), else automatic
    float exposure = 0;
    bool strict = false;
    float max_memory = 0;               // GB the render may take (0 = the memory available)
    Quality quality = Quality::Normal;  // budget preset (quality_preset)
    bool preview = false;               // --preview: a window showing the image as it converges
    bool preview_hold = false;          // keep the window after the render until closed
    std::string preview_screenshot;     // the window's pixels written here when it closes
    std::string tev;                    // --tev HOST:PORT: stream to a tev viewer (empty: no)
    // --trace-pixel X Y: print every camera sample of that pixel (-1: none); --trace-json FILE.
    int trace_x = -1, trace_y = -1;
    std::string trace_json;
};

// How the scene is read and shaded (they change the image).
struct SceneOptions {
    bool schlick = false;
    bool legacy_attenuation = false;
    bool emission_lights = true;     // glowing .scn surfaces are two-sided area lights
    bool real = false;               // the seed's -real: now the default (accepted, no effect)
    bool raw_materials = false;      // keep energy-creating .scn materials as written
    bool no_default_lights = false;  // .scn: no default lights for a scene without lights
    std::string embree_config;       // Embree's device configuration (empty: its own choice)
};

const options::Table& run_options();
const options::Table& scene_options();

// A table and the struct it fills.
struct BoundTable {
    const options::Table* table;
    void* object;
};

// How cli.cpp registers an option table on a (sub)command: the same callbacks, validation and
// --help text as for `phos render`.
using RegisterTable = void (*)(CLI::App&, const BoundTable&, std::set<std::string>&);

struct RenderCommand {
    std::string scene_path;
    RunOptions run;
    SceneOptions scene;
    render::RenderOptions render;
    integrators::PhotonMapOptions photon_map;
    integrators::ProgressiveOptions progressive;
    render::BudgetSettings budget;
    // Names (without dashes) of the options given on the command line.
    std::set<std::string> given;
    // The arguments of this render (for checkpoints: a bare --resume replays them).
    std::vector<std::string> command_line;

    // Every option table with the struct of this command it fills, in --help order.
    std::vector<BoundTable> tables();
    bool was_given(const std::string& name) const { return given.count(name) > 0; }
};

// The options a --quality preset sets, as (option name, value) pairs; options given on the command
// line or by the scene file keep their values.
const std::vector<std::pair<std::string, std::string>>& quality_preset(Quality quality);

// The tables of `phos render` over default structs (for docs and lookups).
std::vector<const options::Table*> all_tables();

// docs/options.md: every option of every table with its default, range, effect and pbrt name.
std::string options_markdown();

}  // namespace phos::app
