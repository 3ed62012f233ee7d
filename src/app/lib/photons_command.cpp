// `phos photons`: the command line (the render option tables that bear on the photon maps, plus
// the output options), then load and prepare the scene as `phos render` does, trace the maps with
// the photon mapper's own pass 1 and write the chosen maps as a point cloud, atomically.
#include "app/lib/photons_command.h"

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include "app/lib/memory_check.h"
#include "app/lib/photon_cloud.h"
#include "app/lib/photon_view.h"
#include "app/lib/render_command.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "core/stats.h"
#include "display/photon_viewer.h"
#include "integrators/photon_map.h"
#include "io/image/atomic_write.h"
#include "render/prepared.h"

namespace phos::app {
namespace {

// `table` with only the options named in `keep`.
options::Table only(const options::Table& table, const std::vector<std::string>& keep) {
    return options::subset(table, [&](const std::string& name) {
        return std::find(keep.begin(), keep.end(), name) != keep.end();
    });
}

const options::Table& photons_run_options() {
    static const options::Table t =
        only(run_options(), {"threads", "verbose", "quiet", "strict", "max-memory", "quality"});
    return t;
}

const options::Table& photons_sampling_options() {
    static const options::Table t = only(render::sampling_options(), {"seed"});
    return t;
}

// Checks everything that can be checked before any work: output path, format, map names.
std::vector<int> check_request(const PhotonsCommand& cmd) {
    const std::string& out = cmd.output;
    if (!cmd.screenshot.empty() && !cmd.view) throw InputError("--screenshot is for --view");
    if (out.empty() && !cmd.view)
        throw InputError(
            "photons: no output file: give -o FILE (.ply, or .txt with --format text), or --view");
    if (cmd.ascii && cmd.format != "ply") throw InputError("--ascii is for --format ply");
    if (out.empty()) return cmd.maps.empty() ? std::vector<int>{} : parse_photon_maps(cmd.maps);
    const std::filesystem::path dir = std::filesystem::absolute(out).parent_path();
    if (!std::filesystem::is_directory(dir))
        throw InputError("output '" + out + "': directory '" + dir.string() + "' does not exist");
    if (std::filesystem::is_directory(out)) throw InputError("output '" + out + "' is a directory");
    return cmd.maps.empty() ? std::vector<int>{} : parse_photon_maps(cmd.maps);
}

// Why map `m` may hold no photons, for the error when --maps asks for it.
std::string empty_map_hint(int m, size_t lights) {
    if (lights == 0) return "the scene has no lights";
    switch (m) {
        case photon::kGlobalMap:
            return "--fast-global traces the indirect map instead";
        case photon::kCausticMap:
            return "only scenes with mirrors or glass have caustic photons; --no-caustic leaves it out";
        case photon::kIndirectMap:
            return "it is traced with --fast-global";
        default:
            return "only scenes with participating media have volume photons";
    }
}

}  // namespace

CLI::App* add_photons_command(CLI::App& app, PhotonsCommand& cmd, RegisterTable register_table) {
    CLI::App* sub = app.add_subcommand(
        "photons",
        "the photon maps of 'phos render --integrator photonmap' (same options) as a point cloud: PLY "
        "for MeshLab / CloudCompare, or the viewer's text format");
    sub->add_option("scene", cmd.scene_path, "scene file (.scn, .pbrt, .scene)")->required();
    sub->add_option("-o,--output", cmd.output, "point cloud to write (.ply; .txt with --format text)")
        ->type_name("FILE")
        ->group("Output");
    sub->add_option(
           "--format", cmd.format,
           "ply: x y z, red green blue, power_r power_g power_b (W), dx dy dz, nx ny nz, map, "
           "bounces per photon; text: the dissertation viewer's format (the count, then per photon position, "
           "power, direction) (default: ply)")
        ->check(CLI::IsMember({"ply", "text"}))
        ->type_name("FORMAT")
        ->group("Output");
    sub->add_flag("--ascii", cmd.ascii, "ASCII PLY instead of binary little-endian")->group("Output");
    sub->add_flag("--view", cmd.view,
                  "show the maps in the 3-D viewer: drag orbits (right: pans), wheel zooms, click prints a "
                  "photon; keys 1-5 toggle maps, c colouring, + - point size, r reset, q quit")
        ->group("Output");
    sub->add_option("--screenshot", cmd.screenshot, "with --view: draw one frame, write it to FILE, close")
        ->type_name("FILE")
        ->group("Output");
    sub->add_option("--colour", cmd.colour,
                    "with --view: the first colouring (c cycles them): power, map, or bounces (white: "
                    "straight from a light, then red, orange, yellow, green, cyan, blue, violet; magenta 8+)")
        ->check(CLI::IsMember({"power", "map", "bounces"}))
        ->type_name("COLOURING")
        ->group("Output");
    sub->add_option("--maps", cmd.maps,
                    "maps to write, comma-separated: global, caustic, indirect, volume, volume-caustic "
                    "(default: every map the photon mapper traces for this scene and these options)")
        ->type_name("LIST")
        ->group("Output");
    RenderCommand& s = cmd.settings;
    for (const BoundTable& b : std::vector<BoundTable>{{&photons_run_options(), &s.run},
                                                       {&photons_sampling_options(), &s.render},
                                                       {&scene_options(), &s.scene},
                                                       {&integrators::photon_map_options(), &s.photon_map}})
        register_table(*sub, b, s.given);
    return sub;
}

PhotonTrace trace_photon_maps(const RenderCommand& settings, const scene::Scene& scene,
                              std::vector<int> kinds, bool bounces, Stats& stats) {
    RenderCommand cmd = settings;
    cmd.run.integrator = integrators::IntegratorKind::PhotonMap;
    std::string spp_source = "default";  // the sample count plays no part here
    apply_quality(cmd, apply_scene_parameters(cmd, scene), spp_source);
    for (const BoundTable& b : cmd.tables()) {
        try {
            options::validate(*b.table, b.object);
        } catch (const options::ValueError& e) {
            throw InputError(e.what());
        }
    }
    // The irradiance cache and the beam BVH are built from the maps after tracing; they change no
    // photon record, so they are skipped here.
    integrators::PhotonMapOptions pm = cmd.photon_map;
    pm.irradiance_cache = false;
    pm.volume_estimate = integrators::VolumeEstimate::March;
    {
        RenderCommand estimate = cmd;  // the render's estimate, without its image
        estimate.photon_map = pm;
        estimate.render.width = estimate.render.height = 1;
        check_memory(estimate, scene, stats);
    }

    const render::RenderOptions& opt = cmd.render;
    const render::PrepareOptions prep = prepare_options(cmd);
    std::optional<render::Prepared> prepared;
    {
        ScopedTimer t(stats, "prepare");
        prepared.emplace(scene, opt, prep, stats);
    }
    if (prepared->lights.size() == 0)
        log::warn(cmd.scene_path + ": the scene has no lights; the photon maps are empty");
    log::info("phos: " + std::filesystem::path(cmd.scene_path).filename().string() +
              ": tracing the photonmap integrator's photon maps, seed " + std::to_string(opt.seed));

    PhotonTrace out;
    out.maps = integrators::PhotonMapIntegrator(pm).build_maps(*prepared, bounces);
    const integrators::PhotonMaps& maps = out.maps;
    if (interrupt::requested()) {
        out.interrupted = true;
        return out;
    }
    if (kinds.empty()) {
        for (int m = 0; m < photon::kMapCount; ++m)
            if (maps.emitted[m] > 0 || !maps.map[m].empty()) kinds.push_back(m);
    } else {
        for (const int m : kinds)
            if (maps.map[m].empty())
                throw InputError(std::string("--maps: the ") + photon_map_label(m) +
                                 " map holds no photons for this scene and these options (" +
                                 empty_map_hint(m, prepared->lights.size()) + ")");
    }
    out.kinds = std::move(kinds);
    out.cloud = photon_cloud(maps, out.kinds);
    return out;
}

int run_photons(const PhotonsCommand& command) {
    RenderCommand cmd = command.settings;
    log::set_quiet(cmd.run.quiet);
    const std::vector<int> requested = check_request(command);
    interrupt::install_handlers();
    std::optional<tbb::global_control> threads;
    if (cmd.run.threads > 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(cmd.run.threads));

    // As run_render (render_command.cpp): load, resolve options, prepare.
    Stats stats;
    scene::Scene scene;
    {
        ScopedTimer t(stats, "load");
        cmd.scene_path = command.scene_path;
        scene = load_render_scene(cmd);
    }
    // Bounce counts (5 more bytes per photon) only for what shows them: the PLY file and the viewer.
    const bool bounces = command.view || command.format != "text";
    const PhotonTrace traced = trace_photon_maps(cmd, scene, requested, bounces, stats);
    if (traced.interrupted) {
        log::warn("interrupted while tracing photons: nothing written" +
                  std::string(std::filesystem::exists(command.output)
                                  ? " ('" + command.output + "' is unchanged)"
                                  : ""));
        return interrupt::exit_status(interrupt::signal_number());
    }
    const integrators::PhotonMaps& maps = traced.maps;
    const std::vector<int>& kinds = traced.kinds;

    const io::PointCloud& cloud = traced.cloud;
    if (command.view) {
        std::vector<std::string> names;
        for (int m = 0; m < photon::kMapCount; ++m) names.push_back(photon_map_label(m));
        display::ViewerOptions vo;
        vo.title = "phos photons: " + std::filesystem::path(command.scene_path).filename().string();
        vo.screenshot_path = command.screenshot;
        vo.colouring = command.colour == "map"       ? display::ViewerColouring::Map
                       : command.colour == "bounces" ? display::ViewerColouring::Bounces
                                                     : display::ViewerColouring::Power;
        std::string why;
        if (!display::run_photon_viewer(viewer_scene(cloud, scene, names), vo, why))
            log::warn("--view: " + why + (command.output.empty() ? "" : "; writing the file only"));
    }
    if (command.output.empty()) return 0;
    {
        ScopedTimer t(stats, "write");
        io::atomic_write(command.output, [&](const std::string& temp) {
            std::ofstream f(temp, std::ios::binary);
            if (!f) throw InputError("cannot open the temporary file");
            if (command.format == "text")
                io::write_point_text(f, cloud, photon_text_columns());
            else
                io::write_ply_points(f, cloud, !command.ascii);
            f.close();
            if (!f) throw InputError("write failed");
        });
    }
    if (cmd.run.verbose) {
        add_peak_memory(stats);
        std::fputs(stats.report().c_str(), stderr);
    }
    std::string counts;
    for (const int m : kinds)
        counts += (counts.empty() ? "" : ", ") + std::string(photon_map_label(m)) + " " +
                  std::to_string(maps.map[m].size());
    log::info("phos: wrote " + command.output + " (" + std::to_string(cloud.size()) + " photons" +
              (counts.empty() ? "" : ": " + counts) + ")");
    return 0;
}

}  // namespace phos::app
