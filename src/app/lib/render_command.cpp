// `phos render`: load the scene, resolve settings (command line, then the scene file, then the
// option tables' defaults) and say where each came from, prepare, render with the chosen
// integrator, write the image (and layers, AOVs) atomically, print statistics with -v.
#include "app/lib/render_command.h"

#include <fcntl.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "app/lib/memory_check.h"
#include "app/lib/scene_defaults.h"
#include "app/lib/trace_output.h"
#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "core/progress.h"
#include "core/stats.h"
#include "core/threads.h"
#include "display/live_image.h"
#include "display/preview_window.h"
#include "display/tev_stream.h"
#include "dist/ranks.h"
#include "film/film.h"
#include "integrators/registry.h"
#include "io/image/image_io.h"
#include "io/load_scene.h"
#include "render/aov.h"
#include "render/prepared.h"
#include "render/progressive_checkpoint.h"
#include "spectrum/color.h"

namespace phos::app {
namespace {

// Checks that a file can be created beside `path` (by creating and removing an empty one), so a
// read-only directory fails before any work rather than after it.
void check_writable(const std::string& path, const std::string& what) {
    const std::filesystem::path dir = std::filesystem::absolute(path).parent_path();
    const std::string probe = (dir / (".phos-write-test-" + std::to_string(::getpid()))).string();
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0)
        throw InputError(what + " '" + path + "': cannot create files in '" + dir.string() +
                         "': " + std::strerror(errno));
    ::close(fd);
    ::unlink(probe.c_str());
}

// The scene's film response applied to an image of radiance: pbrt-v4's Film "rgb" with the
// "cie1931" sensor scales by the imaging ratio (shutter time x ISO / 100) and, with `whitebalance`,
// adapts that temperature's white to the output's (spectrum::white_balance). Identity by default.
Image with_film_response(Image img, const scene::FilmResponse& r) {
    if (r.exposure == 1 && r.white_balance_kelvin <= 0) return img;
    const spectrum::Mat3 m = r.white_balance_kelvin > 0 ? spectrum::white_balance(r.white_balance_kelvin)
                                                        : spectrum::Mat3{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    for (Rgb& c : img.pixels) {
        const Vec3 v = spectrum::apply(m, Vec3(c.r, c.g, c.b)) * r.exposure;
        c = Rgb(v.x, v.y, v.z);
    }
    return img;
}

// A film layer's image as written: radiance layers with the film response, AOVs as they are.
Image layer_output(const film::Film& film, const std::string& name, const scene::FilmResponse& r) {
    const Image img = film.find_layer(name)->image();
    const std::vector<std::string>& aovs = render::aov_names();
    return std::find(aovs.begin(), aovs.end(), name) != aovs.end() ? img : with_film_response(img, r);
}

// Writes the image and its layers (each atomically). If that fails (disk full, file size limit),
// the previous files are intact and the image is saved to the temporary directory instead, so the
// work is not lost; the error says both.
void write_images(const std::string& output, const film::Film& film, const std::vector<std::string>& layers,
                  float exposure, const scene::FilmResponse& response) {
    std::string failure;
    const Image image = with_film_response(film.image(), response);
    try {
        io::write_image(output, image, {exposure});
        for (const std::string& name : layers)
            io::write_image(layer_path(output, name), layer_output(film, name, response), {exposure});
        return;
    } catch (const InputError& e) {
        failure = e.what();
    }
    std::string rescued;
    try {
        std::error_code ec;
        const std::filesystem::path tmp = std::filesystem::temp_directory_path(ec);
        const std::string stem = std::filesystem::path(output).stem().string();
        rescued = ((ec ? std::filesystem::path("/tmp") : tmp) /
                   ("phos-rescued-" + std::to_string(::getpid()) + "-" + stem + ".exr"))
                      .string();
        io::write_image(rescued, image, {exposure});
    } catch (const InputError&) {
        rescued.clear();
    }
    throw InputError(failure + " (a previous file there is intact); " +
                     (rescued.empty() ? "the image could not be saved elsewhere either"
                                      : "the rendered image was saved to " + rescued + " instead"));
}

// Checks the output path before any work, so a bad path fails fast and nothing is written.
void check_output(const std::string& out) {
    if (out.empty()) throw InputError("no output file: give -o FILE (.exr, .pfm, .png or .bmp)");
    if (!io::is_writable_image_path(out))
        throw InputError("output '" + out + "': unknown image format (use .exr, .pfm, .png or .bmp)");
    const std::filesystem::path dir = std::filesystem::absolute(out).parent_path();
    if (!std::filesystem::is_directory(dir))
        throw InputError("output '" + out + "': directory '" + dir.string() + "' does not exist");
    if (std::filesystem::is_directory(out)) throw InputError("output '" + out + "' is a directory");
    check_writable(out, "output");
}

using integrators::IntegratorKind;

const std::string& name_of(IntegratorKind kind) { return integrators::integrator(kind).name; }

// The integrator the scene file names, if any (loaders name only integrators phos has).
std::optional<IntegratorKind> scene_integrator(const scene::RenderSettings& st) {
    if (!st.integrator) return std::nullopt;
    return integrators::integrator_kind(*st.integrator);
}

// Where the sample count came from when the scene file's count was written for another integrator.
std::string spp_for_another_integrator(int scene_spp, const std::string& its_integrator) {
    return "default; the scene file's " + std::to_string(scene_spp) + " are for its " + its_integrator +
           " integrator";
}

// Where the effective settings came from, for the start-up line.
struct Sources {
    std::string integrator, size, spp, output;
    bool default_integrator = false;  // neither the command line nor the scene file chose it
};

// The image to write: -o (or the seed's positional output), else the scene file's own (pbrt's Film
// "filename", written to the current directory), else a default: pbrt's own, pbrt.exr, for a pbrt
// file; for .scn and .scene scenes, which cannot name one, the scene's name with .png beside it.
std::string choose_output(const RenderCommand& cmd, const scene::Scene& scene, std::string& source) {
    if (!cmd.run.output.empty()) {
        source = "command line";
        return cmd.run.output;
    }
    if (scene.settings.output) {
        source = "scene file";
        const std::filesystem::path p(*scene.settings.output);
        return p.is_absolute() ? p.string() : p.filename().string();  // written to the current directory
    }
    std::string ext = std::filesystem::path(cmd.scene_path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".pbrt") {
        source = "default: pbrt's Film filename";
        return "pbrt.exr";
    }
    source = "default: beside the scene; -o FILE chooses another";
    return std::filesystem::path(cmd.scene_path).replace_extension(".png").string();
}

// The integrator, image size and sample count: the command line, else the scene file, else the
// defaults. A single --width or --height keeps the scene's aspect ratio. The scene file's sample
// count is a budget for its own integrator; another integrator chosen on the command line starts
// from the default instead.
Sources resolve_settings(RenderCommand& cmd, const scene::Scene& scene) {
    const scene::RenderSettings& st = scene.settings;
    const std::optional<IntegratorKind> own = scene_integrator(st);
    Sources src;
    if (cmd.was_given("integrator")) {
        src.integrator = "command line";
    } else if (own && st.integrator_implied) {
        cmd.run.integrator = *own;
        src.integrator = "pbrt's default";
        src.default_integrator = true;
    } else if (own) {
        cmd.run.integrator = *own;
        src.integrator = "scene file";
        if (!st.unavailable_integrator.empty())
            log::warn(st.integrator_location + ": Integrator \"" + st.unavailable_integrator +
                      "\" is not available in phos; using " + name_of(*own) +
                      " (choose another with --integrator)");
    } else {
        src.integrator = "default";
        src.default_integrator = true;
    }

    const int sw = st.width.value_or(512), sh = st.height.value_or(512);
    const char* file_or_default = st.width || st.height ? "scene file" : "default";
    const char* aspect =
        st.width || st.height ? "the scene file's aspect ratio" : "the default square aspect";
    render::RenderOptions& r = cmd.render;
    const bool w = cmd.was_given("width"), h = cmd.was_given("height");
    if (cmd.was_given("resolution") || (w && h)) {
        src.size = "command line";
    } else if (w) {
        r.height = keep_aspect(r.width, sw, sh);
        src.size = std::string("command line; height keeps ") + aspect;
    } else if (h) {
        r.width = keep_aspect(r.height, sh, sw);
        src.size = std::string("command line; width keeps ") + aspect;
    } else {
        r.width = sw;
        r.height = sh;
        src.size = file_or_default;
    }
    if (!cmd.was_given("aov") && !st.aovs.empty()) r.aovs = st.aovs;
    // A crop of that image: the command line's, else the scene file's.
    if (!cmd.was_given("crop-window") && !cmd.was_given("pixel-bounds")) {
        r.crop_window = st.crop_window;
        r.pixel_bounds = st.pixel_bounds;
    }
    try {
        const int full_w = r.width, full_h = r.height;
        r.crop = render::resolve_crop(full_w, full_h, r.crop_window, r.pixel_bounds, r.width, r.height);
    } catch (const options::ValueError& e) {
        throw InputError(std::string(cmd.was_given("crop-window") || cmd.was_given("pixel-bounds")
                                         ? "--crop-window/--pixel-bounds: "
                                         : "the scene file's Film cropwindow/pixelbounds: ") +
                         e.what());
    }
    if (r.crop.active())
        src.size += ", cropped to " + std::to_string(r.width) + " x " + std::to_string(r.height) + " from (" +
                    std::to_string(r.crop.x0) + ", " + std::to_string(r.crop.y0) + ")";

    const bool progressive =
        integrators::integrator(cmd.run.integrator).counts == integrators::Counts::Iterations;
    if (cmd.was_given("spp") || cmd.was_given("aa")) {
        src.spp = "command line";
    } else if (progressive && cmd.was_given("iterations")) {
        r.spp = cmd.progressive.iterations;
        src.spp = "--iterations";
    } else if (cmd.was_given("time")) {
        src.spp = "--time";  // the time budget alone decides (setup_budget)
    } else if (st.spp && (!own || *own == cmd.run.integrator)) {
        r.spp = *st.spp;
        src.spp = "scene file";
    } else if (st.spp) {
        src.spp = spp_for_another_integrator(*st.spp, st.unavailable_integrator.empty()
                                                          ? st.integrator.value_or("path")
                                                          : st.unavailable_integrator);
    } else {
        src.spp = "default";
    }
    return src;
}

// The --quality preset (see apply_quality in render_command.h), saying where the sample count came from.
void apply_quality(RenderCommand& cmd, const std::set<std::string>& from_scene, Sources& src) {
    apply_quality(cmd, from_scene, src.spp);
}

// Every table's values checked (values from tests or scene files included), and options given on
// the command line that the chosen integrator does not use: budgets are refused (work would
// silently not be bounded: --iterations on path), the rest warn once.
void check_options(RenderCommand& cmd) {
    for (const BoundTable& b : cmd.tables()) {
        try {
            options::validate(*b.table, b.object);
        } catch (const options::ValueError& e) {
            throw InputError(e.what());
        }
    }
    std::string refused;
    for (const BoundTable& b : cmd.tables())
        for (const options::Option& o : b.table->options) {
            if (!cmd.was_given(o.name) || integrators::applies(o, cmd.run.integrator)) continue;
            const std::string who = integrators::integrator_names(o.applies_to, "/");
            if (o.effect != options::Effect::Image)
                refused +=
                    (refused.empty() ? "" : "; ") + o.flag_name() + " is for the " + who + " integrators";
            else
                log::warn(o.flag_name() + " has no effect on the " + name_of(cmd.run.integrator) +
                          " integrator (" + who + " only)");
        }
    if (!refused.empty())
        throw InputError(refused + " (this render uses " + name_of(cmd.run.integrator) +
                         "; --spp and --time bound any render)");
}

// The image-changing options of this render as (flag, value) pairs: what a checkpoint records to
// refuse resuming a different render.
std::vector<std::pair<std::string, std::string>> image_options(RenderCommand& cmd) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const BoundTable& b : cmd.tables()) {
        if (b.table == &run_options()) continue;  // the integrator is recorded by name
        const auto v =
            options::values(*b.table, b.object, options::Effect::Image, unsigned(cmd.run.integrator));
        out.insert(out.end(), v.begin(), v.end());
    }
    return out;
}

// Budgets, previews, checkpoints and resuming, for every integrator: turns --iterations / --time /
// --resume into the sample or iteration count, and returns the observers (checkpoints, previews,
// the state resumed) and the render identity that checkpoints carry.
render::RenderObservers setup_budget(RenderCommand& cmd, const std::string& output, bool progressive,
                                     const scene::FilmResponse& response) {
    const render::BudgetSettings& p = cmd.budget;
    render::RenderObservers watch;
    render::RenderOptions& opt = cmd.render;
    const int iterations = cmd.progressive.iterations;
    if (iterations > 0 && (cmd.was_given("spp") || cmd.was_given("aa")) && opt.spp != iterations)
        throw InputError("--spp and --iterations disagree");
    const bool count_given = cmd.was_given("iterations") || cmd.was_given("spp") || cmd.was_given("aa");
    if (p.time > 0 && !count_given) opt.spp = 1 << 30;  // the time budget alone decides

    // The render's identity: scene bytes and every option that changes the image.
    render::ProgressiveState& id = watch.identity;
    {
        std::ifstream f(cmd.scene_path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
        id.scene_hash = render::hash_bytes(bytes.data(), bytes.size());
    }
    id.options = image_options(cmd);  // named in the message when a resume does not match
    id.command_line = cmd.command_line;

    if (!p.resume_path.empty()) {
        auto saved = std::make_shared<render::ProgressiveState>(render::load_checkpoint(p.resume_path));
        if (!count_given && p.time <= 0) {  // continue to the saved render's own count
            uint64_t target = saved->target_iterations;
            if (!progressive) target /= uint64_t(std::max(1, opt.dof_samples));  // saved in camera samples
            opt.spp = int(std::clamp<uint64_t>(target, 1, 1 << 30));
        }
        watch.resume = saved;
    }
    if (!p.checkpoint_path.empty()) {
        const std::string path = p.checkpoint_path;
        if (std::filesystem::is_directory(path)) throw InputError("checkpoint '" + path + "' is a directory");
        if (!std::filesystem::is_directory(std::filesystem::absolute(path).parent_path()))
            throw InputError("checkpoint '" + path + "': its directory does not exist");
        if (dist::root()) check_writable(path, "checkpoint");
        // A checkpoint that cannot be written (disk full, read-only) leaves the previous one intact
        // and the render goes on: its image may still be written at the end.
        watch.on_checkpoint = [path](const render::ProgressiveState& s) {
            try {
                render::save_checkpoint(path, s);
            } catch (const InputError& e) {
                log::warn(std::string(e.what()) +
                          "; the checkpoint was not saved (the previous one is intact)");
            }
        };
    }
    if (p.write_every > 0) {
        const float exposure = cmd.run.exposure;
        watch.on_preview = [output, exposure, response](const film::Film& f) {
            try {
                io::write_image(output, with_film_response(f.image(), response), {exposure});
            } catch (const InputError& e) {
                log::warn(std::string(e.what()) +
                          "; the preview was not written (the previous file is intact)");
            }
        };
    }
    return watch;
}

// The film layers to write: the integrator's components with --layers, the AOVs asked for.
std::vector<std::string> written_layers(const film::Film& film, const render::RenderOptions& opt) {
    std::vector<std::string> out;
    for (const std::string& name : film.layer_names()) {
        const auto& aovs = render::aov_names();
        const bool is_aov = std::find(aovs.begin(), aovs.end(), name) != aovs.end();
        if (is_aov ? std::find(opt.aovs.begin(), opt.aovs.end(), name) != opt.aovs.end() : opt.layers)
            out.push_back(name);
    }
    return out;
}

// What a render completed, for -v and the interrupt warning: "12 of 64 iterations", "37.5 of 64
// samples per pixel (59 %)".
std::string work_done(const render::RenderDone& done, bool progressive, size_t pixels) {
    const bool counted = done.target < render::kUnboundedIterations;
    if (progressive)
        return std::to_string(done.units) + (counted ? " of " + std::to_string(done.target) : "") +
               " iterations";
    const double mean = pixels > 0 ? double(done.samples) / double(pixels) : 0.0;
    if (counted && mean < double(done.target))
        return printf_string("%.4g of %llu samples per pixel, %.0f %%", mean, (unsigned long long)done.target,
                             100.0 * mean / double(done.target));
    return printf_string("%.4g samples per pixel", mean);
}

bool output_exists(const std::string& path) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}

}  // namespace

int keep_aspect(int side, int scene_side, int scene_other) {
    return std::max(1, int(std::lround(double(side) * scene_other / scene_side)));
}

// The scene file's integrator parameters (pbrt `Integrator "sppm" "float radius" ...`) mapped onto
// the option tables by name, for options the command line did not give. A value outside the
// option's range is an error at the parameter; a parameter no option takes is a warning (an error
// with --strict).
std::set<std::string> apply_scene_parameters(RenderCommand& cmd, const scene::Scene& scene) {
    std::set<std::string> applied;
    const scene::RenderSettings& st = scene.settings;
    const std::optional<IntegratorKind> named = scene_integrator(st);
    const bool own = !named || *named == cmd.run.integrator;
    for (const scene::IntegratorParameter& p : st.integrator_parameters) {
        const std::string what = "Integrator parameter \"" + p.type + " " + p.name + "\"";
        const options::Option* opt = nullptr;
        void* object = nullptr;
        for (const BoundTable& b : cmd.tables())
            if (const options::Option* o = b.table->find_pbrt(p.name)) opt = o, object = b.object;
        if (!opt) {
            // An integrator phos substitutes already had one warning for the whole directive.
            if (!st.unavailable_integrator.empty()) continue;
            const std::string msg = what + " is not used by phos";
            if (cmd.run.strict) throw ParseError(p.file, p.line, p.column, msg, p.included_from);
            if (own) log::warn(ParseError::format(p.file, p.line, p.column, msg + " (ignored)"));
            continue;
        }
        if (cmd.was_given(opt->name)) continue;  // the command line wins
        // A value meaning "pbrt's default" (photonsperiteration -1) keeps phos's default.
        if (!opt->pbrt_unset.empty() && p.values == std::vector<std::string>{opt->pbrt_unset}) continue;
        if (int(p.values.size()) != opt->arity)
            throw ParseError(
                p.file, p.line, p.column,
                what + ": expected " + std::to_string(opt->arity) + " value(s) for " + opt->flag_name(),
                p.included_from);
        try {
            opt->set(object, p.values);
            applied.insert(opt->name);
        } catch (const options::ValueError& e) {
            throw ParseError(p.file, p.line, p.column, what + " (" + opt->flag_name() + "): " + e.what(),
                             p.included_from);
        }
        if (opt->name == "iterations" && !cmd.was_given("spp") && !cmd.was_given("aa"))
            cmd.render.spp = cmd.progressive.iterations;
    }
    return applied;
}

// The --quality preset: its options, except those given on the command line or by the scene file
// (the sample count only where it is still the default).
void apply_quality(RenderCommand& cmd, const std::set<std::string>& from_scene, std::string& spp_source) {
    for (const auto& [name, value] : quality_preset(cmd.run.quality)) {
        if (cmd.was_given(name) || from_scene.count(name)) continue;
        if (name == "spp") {
            if (spp_source.rfind("default", 0) != 0 || cmd.was_given("aa") || cmd.was_given("iterations") ||
                cmd.was_given("time"))
                continue;
            spp_source = "--quality " + options::choice_name(quality_choices(), cmd.run.quality);
        }
        for (const BoundTable& b : cmd.tables())
            if (const options::Option* o = b.table->find(name)) o->set(b.object, {value});
    }
}

scene::Scene load_render_scene(const RenderCommand& cmd) {
    return io::load_scene(cmd.scene_path, {.raw_materials = cmd.scene.raw_materials,
                                           .legacy_attenuation = cmd.scene.legacy_attenuation,
                                           .strict = cmd.run.strict,
                                           .no_default_lights = cmd.scene.no_default_lights,
                                           .emission_lights = cmd.scene.emission_lights});
}

render::PrepareOptions prepare_options(const RenderCommand& cmd) {
    render::PrepareOptions prep;
    prep.bsdf.schlick = cmd.scene.schlick;
    prep.lights.legacy_attenuation = cmd.scene.legacy_attenuation;
    prep.lens_radius = cmd.render.lens_radius;
    prep.focal_distance = cmd.render.focal_distance;
    prep.embree_config = cmd.scene.embree_config;
    return prep;
}

std::string layer_path(const std::string& output, const std::string& layer) {
    const std::filesystem::path p(output);
    return (p.parent_path() / (p.stem().string() + "." + layer + p.extension().string())).string();
}

int run_render(const RenderCommand& command, const RenderHooks& hooks) {
    const auto clock_start = std::chrono::steady_clock::now();
    RenderCommand cmd = command;
    const bool to_memory = hooks.result != nullptr;
    log::set_quiet(cmd.run.quiet);
    if (hooks.signal_handlers) interrupt::install_handlers(!dist::root(), dist::distributed());
    if (const std::vector<int> pids = dist::pids_on_this_machine(); dist::root() && !pids.empty())
        interrupt::watch_ranks(pids.data(), int(pids.size()));  // to name a rank that dies
    std::optional<tbb::global_control> threads;
    if (cmd.run.threads > 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(cmd.run.threads));
    else if (const int t = dist::default_threads(); t > 0)  // ranks sharing a machine share its cores
        threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(t));

    Stats stats;
    scene::Scene loaded;
    if (!hooks.scene) {
        ScopedTimer t(stats, "load");
        loaded = load_render_scene(cmd);
    }
    const scene::Scene& scene = hooks.scene ? *hooks.scene : loaded;

    // Resolve settings: command line, then the scene file, then defaults.
    std::string output_source;
    const std::string output = choose_output(cmd, scene, output_source);
    if (dist::root() && !to_memory) check_output(output);  // under MPI rank 0 alone writes
    Sources sources = resolve_settings(cmd, scene);
    sources.output = output_source;
    const std::set<std::string> from_scene = apply_scene_parameters(cmd, scene);
    apply_quality(cmd, from_scene, sources);
    check_options(cmd);
    check_trace_options(cmd.run, cmd.render.width, cmd.render.height);  // --trace-pixel, before any work
    if (!cmd.run.trace_json.empty() && dist::root()) check_writable(cmd.run.trace_json, "--trace-json");
    // The default integrator may still change with the scene (fit_defaults_to_light_paths), but
    // only between integrators that count samples per pixel, as the default ones do.
    const bool progressive =
        integrators::integrator(cmd.run.integrator).counts == integrators::Counts::Iterations;
    if (cmd.render.layers && integrators::integrator(cmd.run.integrator).layers.empty())
        throw InputError("--layers: the " + name_of(cmd.run.integrator) +
                         " integrator has no component layers");
    render::RenderObservers watch = setup_budget(cmd, output, progressive, scene.film_response);
    cmd.budget.clock_start = clock_start;
    if (!dist::root()) {  // rank 0 alone writes, shows and streams (docs/distributed.md)
        watch.on_checkpoint = nullptr;
        watch.on_preview = nullptr;
        cmd.run.preview = false;
        cmd.run.tev.clear();
    }
    // Watching the render (--preview, --tev): the render copies finished tiles and frames into the
    // live image, which the window's and the stream's threads read.
    std::unique_ptr<display::LiveImage> live;
    std::optional<display::TevAddress> tev_address;
    if (!cmd.run.tev.empty()) tev_address = display::parse_tev_address(cmd.run.tev);  // a bad one: exit 2 now
    if (cmd.run.preview || tev_address) {
        live = std::make_unique<display::LiveImage>(cmd.render.width, cmd.render.height);
        display::LiveImage* l = live.get();
        watch.on_tile = [l](const film::Film& f, const film::Tile& t) { l->update_tile(f, t); };
        watch.on_frame = [l](const film::Film& f) { l->update_frame(f); };
    }

    const render::RenderOptions& opt = cmd.render;
    check_memory(cmd, scene, stats);  // refuses before any work when the memory would not do

    const render::PrepareOptions prep = prepare_options(cmd);
    std::optional<render::Prepared> prepared;
    {
        ScopedTimer t(stats, "prepare");
        prepared.emplace(scene, opt, prep, stats);
    }
    // A scene lit mostly through glass gets the defaults made for it (docs/usage.md).
    if (const std::optional<double> share =
            sources.default_integrator ? lit_through_interfaces(*prepared) : std::nullopt) {
        const IntegratorKind before = cmd.run.integrator;
        // The scene file's sample count was for its own integrator (resolve_settings' rule): the
        // photon mapper starts from the default (and the --quality preset's) instead.
        if (before != IntegratorKind::PhotonMap && sources.spp == "scene file" && !watch.resume) {
            sources.spp = spp_for_another_integrator(cmd.render.spp, name_of(before));
            cmd.render.spp = render::RenderOptions{}.spp;
            apply_quality(cmd, from_scene, sources.spp);
            prepared->options.spp = cmd.render.spp;
        }
        sources.integrator = fit_defaults_to_light_paths(cmd, before, *share, from_scene);
        check_options(cmd);
        check_memory(cmd, scene, stats);
        watch.identity.options = image_options(cmd);
    }
    // (--layers was checked above: the scene's defaults only ever choose photonmap, which has them.)
    const std::string& integrator_name = name_of(cmd.run.integrator);
    integrators::IntegratorConfig config{cmd.photon_map, cmd.progressive, {cmd.budget, watch}};
    auto integrator = integrators::make_integrator(cmd.run.integrator, config);
    if (prepared->lights.size() == 0) {
        bool glows = false;
        for (const scene::Material& m : scene.materials) glows |= m.emission.max() > 0;
        log::warn_once("no-lights",
                       cmd.scene_path +
                           ": the scene has no lights; the image is black except for emission "
                           "and the background" +
                           (glows && !cmd.scene.emission_lights
                                ? " (its glowing surfaces light nothing with --no-emission-lights)"
                                : ""));
    }

    {
        std::string budget = std::to_string(opt.spp) + (progressive ? " iterations" : " spp");
        if (cmd.budget.time > 0)
            budget = opt.spp >= (1 << 30) ? std::string(progressive ? "iterations" : "samples") + " until " +
                                                options::format_number(cmd.budget.time) + " s"
                                          : budget + " or " + options::format_number(cmd.budget.time) + " s";
        if (opt.dof_samples > 1) budget += " x " + std::to_string(opt.dof_samples) + " lens samples";
        log::info("phos: " + std::filesystem::path(cmd.scene_path).filename().string() + ": " +
                  integrator_name + " (" + sources.integrator + "), " + std::to_string(opt.width) + "x" +
                  std::to_string(opt.height) + " (" + sources.size + "), " + budget + " (" + sources.spp +
                  "), seed " + std::to_string(opt.seed) +
                  (to_memory ? "" : ", output " + output + " (" + sources.output + ")"));
    }

    display::PreviewWindow window;
    if (cmd.run.preview) {
        display::PreviewOptions po;
        po.title = "phos: " + std::filesystem::path(cmd.scene_path).filename().string();
        po.exposure = cmd.run.exposure;
        po.hold = cmd.run.preview_hold;
        const std::filesystem::path out_path(output);
        po.snapshot_stem = (out_path.parent_path() / out_path.stem()).string();
        po.screenshot_path = cmd.run.preview_screenshot;
        std::string why;
        if (!window.start(*live, po, why)) log::warn("--preview: " + why + "; rendering without the window");
    }
    display::TevStream tev;
    if (tev_address)
        tev.start(*live, *tev_address,
                  "phos: " + std::filesystem::path(cmd.scene_path).filename().string() + " (" +
                      std::to_string(::getpid()) + ")");
    // The stream sends the final image and the window closes (or, with --preview-hold, waits to be
    // closed) however the render ends.
    struct CloseLive {
        display::LiveImage* live;
        display::TevStream& tev;
        display::PreviewWindow& window;
        ~CloseLive() {
            if (live) live->finish();
            tev.finish();
            window.finish();
        }
    } close_live{live.get(), tev, window};

    film::Film film(opt.width, opt.height);
    const bool bar = cmd.was_given("progress") ? cmd.run.progress : Progress::stderr_is_terminal();
    Progress own_progress(Progress::mode_for(bar, cmd.was_given("progress"), cmd.run.quiet || !dist::root()));
    Progress& progress = hooks.progress ? *hooks.progress : own_progress;
    // --trace-pixel: the integrator records that pixel's camera samples (render/path_recorder.h).
    std::optional<render::PathRecorder> trace;
    if (cmd.run.trace_x >= 0) trace.emplace(cmd.run.trace_x, cmd.run.trace_y);
    // Under MPI: every rank has set up without error, or none renders (a failing rank said why).
    if (dist::distributed() && dist::agree_start(true).any_failed) return 2;
    std::vector<std::string> rank_lines;  // -v under MPI: each rank's render time and rays
    render::RenderDone done;
    double render_seconds = 0;
    {
        ScopedTimer t(stats, "render");
        const render::TraceRequest request(trace ? &*trace : nullptr);
        const auto t0 = std::chrono::steady_clock::now();
        done = integrator->render(*prepared, film, progress);
        render_seconds = seconds_since(t0);
        if (dist::distributed()) {
            const RayCounts rays = stats.rays();
            rank_lines = dist::gather(printf_string(
                "%d threads, render %.3f s, %.4g M rays, %.3g MB exchanged", worker_threads(), render_seconds,
                double(rays.camera + rays.shadow + rays.bounce + rays.photon) * 1e-6,
                double(dist::bytes_exchanged()) * 1e-6));
        }
        dist::mark_finished();
    }
    if (!dist::root())
        return interrupt::requested() || done.interrupted ? interrupt::exit_status(interrupt::signal_number())
                                                          : 0;
    const bool interrupted = done.interrupted || interrupt::requested();
    const int status = interrupted ? interrupt::exit_status(interrupt::signal_number()) : 0;
    if (to_memory) hooks.result->interrupted = interrupted;
    if (interrupted && !done.started) {
        log::warn("interrupted before any " + std::string(progressive ? "iteration" : "sample") +
                  " was complete: no image written" +
                  (output_exists(output) ? " ('" + output + "' is unchanged)" : ""));
        return status;
    }
    if (!opt.aovs.empty() && !interrupted) {
        ScopedTimer t(stats, "aov");
        render::render_aovs(*prepared, film);
    } else if (!opt.aovs.empty()) {
        log::warn("interrupted: the auxiliary images (--aov) are not written");
    }
    if (live) live->update_frame(film);  // the final image, with the AOVs
    const std::vector<std::string> layers = written_layers(film, opt);
    if (to_memory) {
        RenderResult& r = *hooks.result;
        r.image = with_film_response(film.image(), scene.film_response);
        r.layers.clear();
        for (const std::string& name : layers)
            r.layers.emplace_back(name, layer_output(film, name, scene.film_response));
        r.integrator = cmd.run.integrator;
        r.done = done;
        r.seconds = render_seconds;
        r.rays = stats.rays();
        r.photons = stats.photons_emitted();  // r.interrupted is set above
    } else {
        ScopedTimer t(stats, "write");
        write_images(output, film, layers, cmd.run.exposure, scene.film_response);
    }
    if (trace)  // --trace-pixel: printed, and written with --trace-json
        report_trace(*trace, {integrator_name, film.main().value(trace->x(), trace->y())},
                     cmd.run.trace_json);
    const std::string so_far = work_done(done, progressive, size_t(opt.width) * size_t(opt.height));
    if (cmd.run.verbose) {
        stats.add_value("image", std::to_string(opt.width) + "x" + std::to_string(opt.height) + ", " +
                                     so_far + ", integrator " + integrator_name);
        const uint64_t dropped = film.rejected_samples() + stats.dropped_samples();
        stats.add_value("samples dropped (NaN or infinite)", std::to_string(dropped));
        for (size_t r = 0; r < rank_lines.size(); ++r)
            stats.add_value("rank " + std::to_string(r) + " of " + std::to_string(rank_lines.size()),
                            rank_lines[r]);
        add_peak_memory(stats);
        std::fputs(stats.report().c_str(), stderr);
    }
    std::string also;
    for (const std::string& name : layers) also += (also.empty() ? "" : ", ") + name;
    if (!to_memory) log::info("phos: wrote " + output + (also.empty() ? "" : " (and layers " + also + ")"));
    if (interrupted)
        log::warn("interrupted: the image holds the work done so far (" + so_far + ")" +
                  (cmd.budget.checkpoint_path.empty()
                       ? ""
                       : "; continue it with phos render --resume " + cmd.budget.checkpoint_path));
    return status;
}

}  // namespace phos::app
