// `phos render`: load the scene, resolve settings (CLI over scene file over defaults), prepare,
// render with the chosen integrator, write the image atomically, print statistics with -v.
#include "app/lib/render_command.h"

#include <tbb/global_control.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/error.h"
#include "core/log.h"
#include "core/progress.h"
#include "core/stats.h"
#include "film/checkpoint.h"
#include "film/film.h"
#include "integrators/factory.h"
#include "integrators/prepared.h"
#include "io/image/image_io.h"
#include "io/load_scene.h"
#include "scene/emission_lights.h"

namespace phos::app {
namespace {

// Checks the output path before any work, so a bad path fails fast and nothing is written.
void check_output(const std::string& out) {
    if (out.empty()) throw InputError("no output file: give -o FILE (.exr, .pfm, .png or .bmp)");
    if (!io::is_writable_image_path(out))
        throw InputError("output '" + out + "': unknown image format (use .exr, .pfm, .png or .bmp)");
    const std::filesystem::path dir = std::filesystem::absolute(out).parent_path();
    if (!std::filesystem::is_directory(dir))
        throw InputError("output '" + out + "': directory '" + dir.string() + "' does not exist");
    if (std::filesystem::is_directory(out)) throw InputError("output '" + out + "' is a directory");
}

// Budgets, previews, checkpoints and resuming of the progressive integrators (ppm, sppm): fills
// the hooks and the render identity that checkpoints carry, and turns --iterations / --time /
// --resume into the iteration count.
void setup_progressive(const RenderCommand& cmd, const std::string& integrator, const std::string& output,
                       integrators::RenderOptions& opt, integrators::ProgressiveOptions& p) {
    const bool progressive = integrator == "ppm" || integrator == "sppm";
    if (!progressive) {
        if (!p.checkpoint_path.empty() || !p.resume_path.empty() || p.time > 0 || p.write_every > 0 ||
            p.iterations > 0)
            throw InputError(
                "--iterations, --time, --write-every, --checkpoint and --resume need --integrator ppm or "
                "sppm");
        return;
    }
    if (p.iterations > 0) {
        if (cmd.spp && *cmd.spp != p.iterations) throw InputError("--spp and --iterations disagree");
        opt.spp = p.iterations;
    }
    const bool count_given = p.iterations > 0 || cmd.spp.has_value() || cmd.aa.has_value();
    if (p.time > 0 && !count_given) opt.spp = 1 << 30;  // the time budget alone decides

    // The render's identity: scene bytes and every option that changes the image.
    film::ProgressiveState& id = p.identity;
    {
        std::ifstream f(cmd.scene_path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
        id.scene_hash = film::hash_bytes(bytes.data(), bytes.size());
    }
    std::ostringstream o;
    o << opt.max_depth << ' ' << opt.dof_samples << ' ' << opt.ambient << ' ' << opt.background_light << ' '
      << cmd.dof_distance << ' ' << cmd.dof_radius << ' ' << cmd.schlick << ' ' << cmd.real << ' '
      << cmd.legacy_attenuation << ' ' << cmd.emission_lights << ' ' << p.alpha << ' '
      << integrators::photons_per_iteration(p) << ' ' << p.radius << ' ' << p.radius_pixels << ' '
      << p.direct_samples << ' ' << p.eye_samples << ' ' << p.radius_photons;
    const std::string ostr = o.str();
    id.options_hash = film::hash_bytes(ostr.data(), ostr.size());
    id.command_line = cmd.command_line;

    if (!p.resume_path.empty()) {
        auto saved = std::make_shared<film::ProgressiveState>(film::load_checkpoint(p.resume_path));
        if (!count_given && p.time <= 0) opt.spp = int(std::min<uint64_t>(saved->target_iterations, 1 << 30));
        p.resume = saved;
    }
    if (!p.checkpoint_path.empty()) {
        const std::string path = p.checkpoint_path;
        p.on_checkpoint = [path](const film::ProgressiveState& s) { film::save_checkpoint(path, s); };
    }
    if (p.write_every > 0) {
        const float exposure = cmd.exposure;
        p.on_preview = [output, exposure](const film::Film& f) {
            io::write_image(output, f.image(), {exposure});
        };
    }
}

}  // namespace

std::string layer_path(const std::string& output, const std::string& layer) {
    const std::filesystem::path p(output);
    return (p.parent_path() / (p.stem().string() + "." + layer + p.extension().string())).string();
}

void run_render(const RenderCommand& cmd) {
    const auto clock_start = std::chrono::steady_clock::now();
    log::set_quiet(cmd.quiet);
    std::optional<tbb::global_control> threads;
    if (cmd.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(cmd.threads));

    Stats stats;
    scene::Scene scene;
    {
        ScopedTimer t(stats, "load");
        scene = io::load_scene(cmd.scene_path, {cmd.real, cmd.legacy_attenuation, cmd.strict});
        if (cmd.emission_lights) {
            const int n = scene::emissive_shapes_to_lights(scene);
            if (n == 0) log::warn("--emission-lights: the scene has no emissive surfaces");
        }
    }

    // Resolve settings: command line, then the scene file, then defaults.
    std::string output = cmd.output;
    if (output.empty() && scene.settings.output) {
        const std::filesystem::path p(*scene.settings.output);
        output = p.is_absolute() ? p.string() : p.filename().string();  // written to the current directory
    }
    check_output(output);

    integrators::RenderOptions opt;
    opt.width = cmd.width.value_or(scene.settings.width.value_or(512));
    opt.height = cmd.height.value_or(scene.settings.height.value_or(512));
    if (cmd.aa)
        opt.spp = 1 << (2 * *cmd.aa);
    else
        opt.spp = cmd.spp.value_or(scene.settings.spp.value_or(16));
    if (cmd.spp && cmd.aa) throw InputError("give either --spp or -aa, not both");
    opt.max_depth = cmd.max_depth.value_or(scene.settings.max_depth.value_or(16));
    opt.seed = cmd.seed;
    opt.ambient = cmd.ambient;
    opt.background_light = cmd.background_light;
    if (cmd.dof_samples) opt.dof_samples = *cmd.dof_samples;
    if (opt.width <= 0 || opt.height <= 0) throw InputError("image size must be positive");
    const std::string integrator_name = cmd.integrator.value_or(scene.settings.integrator.value_or("path"));
    integrators::IntegratorConfig config = cmd.config;
    setup_progressive(cmd, integrator_name, output, opt, config.progressive);
    config.progressive.clock_start = clock_start;
    auto integrator = integrators::make_integrator(integrator_name, config);

    integrators::PrepareOptions prep;
    prep.bsdf.schlick = cmd.schlick;
    prep.lights.legacy_attenuation = cmd.legacy_attenuation;
    if (cmd.dof_samples) {
        prep.lens_radius = cmd.dof_radius;
        prep.focal_distance = cmd.dof_distance;
    }
    std::optional<integrators::Prepared> prepared;
    {
        ScopedTimer t(stats, "prepare");
        prepared.emplace(scene, opt, prep, stats);
    }
    if (prepared->lights.size() == 0 && scene.lights.empty())
        log::warn_once("no-lights", "scene has no lights: the image is black except for emission");

    film::Film film(opt.width, opt.height);
    Progress progress(cmd.progress < 0 ? Progress::stderr_is_terminal() && !cmd.quiet : cmd.progress == 1);
    {
        ScopedTimer t(stats, "render");
        integrator->render(*prepared, film, progress);
    }
    {
        ScopedTimer t(stats, "write");
        io::write_image(output, film.image(), {cmd.exposure});
        if (cmd.layers)
            for (const std::string& name : film.layer_names())
                io::write_image(layer_path(output, name), film.find_layer(name)->image(), {cmd.exposure});
    }
    if (cmd.verbose) {
        stats.add_value("image", std::to_string(opt.width) + "x" + std::to_string(opt.height) + ", " +
                                     std::to_string(opt.spp * opt.dof_samples) + " spp, integrator " +
                                     integrator_name);
        std::fputs(stats.report().c_str(), stderr);
    }
    if (!cmd.quiet) log::info("phos: wrote " + output);
}

}  // namespace phos::app
