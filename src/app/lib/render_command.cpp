// `phos render`: load the scene, resolve settings (CLI over scene file over defaults), prepare,
// render with the chosen integrator, write the image atomically, print statistics with -v.
#include "app/lib/render_command.h"

#include <tbb/global_control.h>

#include <filesystem>

#include "core/error.h"
#include "core/log.h"
#include "core/progress.h"
#include "core/stats.h"
#include "film/film.h"
#include "integrators/factory.h"
#include "integrators/prepared.h"
#include "io/image/image_io.h"
#include "io/load_scene.h"

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

}  // namespace

std::string layer_path(const std::string& output, const std::string& layer) {
    const std::filesystem::path p(output);
    return (p.parent_path() / (p.stem().string() + "." + layer + p.extension().string())).string();
}

void run_render(const RenderCommand& cmd) {
    log::set_quiet(cmd.quiet);
    std::optional<tbb::global_control> threads;
    if (cmd.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(cmd.threads));

    Stats stats;
    scene::Scene scene;
    {
        ScopedTimer t(stats, "load");
        scene = io::load_scene(cmd.scene_path, {cmd.real, cmd.legacy_attenuation, cmd.strict});
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
    auto integrator = integrators::make_integrator(integrator_name, cmd.config);

    if (cmd.dof_samples) {
        if (!scene.camera) scene.camera.emplace();  // replaced below by the framing camera if absent
        scene.camera->lens_radius = cmd.dof_radius;
        scene.camera->focal_distance = cmd.dof_distance;
    }

    integrators::PrepareOptions prep;
    prep.bsdf.schlick = cmd.schlick;
    prep.lights.legacy_attenuation = cmd.legacy_attenuation;
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
