// The `phos` command line (CLI11). Accepts the seed renderer's single-dash long options (-aa,
// -resolution, -real...) by rewriting them to the double-dash form before parsing.
#include "app/lib/cli.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "app/lib/diff_command.h"
#include "app/lib/photon_map_cli.h"
#include "app/lib/progressive_cli.h"
#include "app/lib/render_command.h"
#include "core/error.h"
#include "film/checkpoint.h"
#include "integrators/factory.h"

namespace phos::app {
namespace {

std::vector<std::string> normalise_args(int argc, char** argv, const std::set<std::string>& long_names) {
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a.size() > 2 && a[0] == '-' && a[1] != '-' && long_names.count(a.substr(1))) a = "-" + a;
        args.push_back(a);
    }
    return args;
}

// `saved` arguments overridden by `user` ones: every option the user gives replaces the saved
// occurrences of the same option (with their values).
std::vector<std::string> merge_arguments(CLI::App& render, const std::vector<std::string>& saved,
                                         const std::vector<std::string>& user) {
    auto option_of = [&](const std::string& token) -> const CLI::Option* {
        if (token.size() < 2 || token[0] != '-' || (token[1] >= '0' && token[1] <= '9') || token[1] == '.')
            return nullptr;
        return render.get_option_no_throw(token.substr(0, token.find('=')));
    };
    std::set<const CLI::Option*> overridden;
    for (const std::string& t : user)
        if (const CLI::Option* o = option_of(t)) overridden.insert(o);
    std::vector<std::string> out;
    for (size_t i = 0; i < saved.size(); ++i) {
        const CLI::Option* o = option_of(saved[i]);
        if (o && overridden.count(o)) {
            if (saved[i].find('=') == std::string::npos)
                i += size_t(std::max(0, o->get_items_expected_max()));
            continue;
        }
        out.push_back(saved[i]);
    }
    out.insert(out.end(), user.begin(), user.end());
    return out;
}

// What a checkpoint records of this render's arguments: without --resume, the scene made absolute.
std::vector<std::string> checkpoint_arguments(const std::vector<std::string>& render_args,
                                              const std::string& scene) {
    std::vector<std::string> out;
    bool scene_done = false;
    for (size_t i = 0; i < render_args.size(); ++i) {
        const std::string& a = render_args[i];
        if (a == "--resume") {
            ++i;
            continue;
        }
        if (a.rfind("--resume=", 0) == 0) continue;
        if (!scene_done && a == scene) {
            out.push_back(std::filesystem::absolute(a).string());
            scene_done = true;
            continue;
        }
        out.push_back(a);
    }
    return out;
}

}  // namespace

int run_cli(int argc, char** argv) {
    CLI::App app{"phos: a physically based photon-mapping renderer", "phos"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "phos 0.1");

    RenderCommand rc;
    CLI::App* render = app.add_subcommand("render", "render a scene file (.scn, .pbrt) to an image");
    render->add_option("scene", rc.scene_path,
                       "scene file (.scn or .pbrt); may be omitted with --resume, which replays the "
                       "checkpointed render's arguments");
    render->add_option("-o,--output", rc.output,
                       "output image: .exr (linear float), .pfm (linear), .png / .bmp (sRGB 8-bit); "
                       "default: the scene file's Film filename");
    auto* w = render->add_option("--width", rc.width, "image width in pixels")->check(CLI::Range(1, 65536));
    auto* h =
        render->add_option("--height", rc.height, "image height in pixels")->check(CLI::Range(1, 65536));
    std::vector<int> resolution;
    auto* res = render->add_option("--resolution", resolution, "image size W H (the seed's -resolution)")
                    ->expected(2)
                    ->check(CLI::Range(1, 65536));
    res->excludes(w)->excludes(h);
    auto* spp = render->add_option("--spp", rc.spp, "samples per pixel (iterations for ppm/sppm)")
                    ->check(CLI::Range(1, 1 << 20));
    render->add_option("--aa", rc.aa, "anti-aliasing level N: 4^N samples per pixel (the seed's -aa)")
        ->check(CLI::Range(0, 8))
        ->excludes(spp);
    render->add_option("--threads", rc.threads, "worker threads (0 = all cores)")->check(CLI::Range(0, 4096));
    render->add_option("--seed", rc.seed, "random seed (same seed -> identical image)");
    std::string names;
    for (const auto& n : integrators::integrator_names()) names += (names.empty() ? "" : "|") + n;
    render->add_option("--integrator", rc.integrator, "rendering algorithm: " + names)
        ->check(CLI::IsMember(integrators::integrator_names()));
    render->add_option("--max-depth", rc.max_depth, "maximum number of bounces (pbrt's maxdepth)")
        ->check(CLI::Range(0, 100000));
    render->add_flag("-v,--verbose", rc.verbose, "print statistics: rays by kind, time per phase");
    render->add_flag("-q,--quiet", rc.quiet, "no warnings or messages");
    render->add_option("--exposure", rc.exposure, "exposure in stops for .png/.bmp output")
        ->check(CLI::Range(-64.0f, 64.0f));
    render->add_flag("--schlick", rc.schlick, "Schlick's approximation instead of exact Fresnel");
    std::vector<float> dof;
    render
        ->add_option("--dof", dof,
                     "depth of field: SAMPLES DISTANCE RADIUS (lens samples per pixel sample, focal "
                     "distance, aperture radius)")
        ->expected(3);
    render->add_flag(
        "--emission-lights", rc.emission_lights,
        ".scn: surfaces with emission e become area lights (they light the scene and emit photons)");
    render->add_flag("--legacy-attenuation", rc.legacy_attenuation,
                     ".scn: honour (ca, la, qa) light attenuation in direct light");
    render->add_flag("--real", rc.real, ".scn: scale material lobes so kd + ks + kt <= 1 (the seed's -real)");
    render->add_flag("--ambient", rc.ambient, ".scn: add the non-physical ka * ambient term");
    render->add_flag("--background-light", rc.background_light,
                     "the background radiance also lights diffuse surfaces");
    render->add_flag("--strict", rc.strict, "pbrt: unused scene parameters are errors");
    render->add_flag("--layers", rc.layers,
                     "also write each layer (direct, indirect, caustic, specular) as OUT.<layer>.<ext>");
    add_photon_map_options(*render, rc.config.photon_map);
    add_progressive_options(*render, rc.config.progressive);
    bool progress_on = false, progress_off = false;
    render->add_flag("--progress", progress_on, "always draw the progress bar");
    render->add_flag("--no-progress", progress_off, "never draw the progress bar");

    DiffCommand dc;
    CLI::App* diff =
        app.add_subcommand("diff", "compare an image with a reference: relMSE, mean ratio, window means");
    diff->add_option("image", dc.image, "rendered image (.exr, .pfm, ...)")->required();
    diff->add_option("reference", dc.reference, "reference image")->required();
    diff->add_option("--window", dc.window, "pixel window x0 x1 y0 y1 (half-open, y from the top)")
        ->expected(4);

    std::set<std::string> long_names;
    for (const CLI::Option* o : render->get_options())
        for (const auto& n : o->get_lnames()) long_names.insert(n);
    const std::vector<std::string> args = normalise_args(argc, argv, long_names);
    // Returns -1 when parsing succeeded, else the exit code.
    auto parse = [&](std::vector<std::string> a) {
        std::reverse(a.begin(), a.end());  // CLI11 takes the arguments reversed
        try {
            app.parse(a);
            return -1;
        } catch (const CLI::CallForHelp& e) {
            return app.exit(e);
        } catch (const CLI::CallForAllHelp& e) {
            return app.exit(e);
        } catch (const CLI::CallForVersion& e) {
            return app.exit(e);
        } catch (const CLI::ParseError& e) {
            std::fprintf(stderr, "phos: %s\n", e.what());
            std::fprintf(stderr, "Run 'phos --help' or 'phos render --help' for the options.\n");
            return 2;
        }
    };
    if (const int code = parse(args); code >= 0) return code;

    try {
        if (render->parsed()) {
            const auto render_at = std::find(args.begin(), args.end(), "render");
            std::vector<std::string> render_args(render_at + 1, args.end());
            if (rc.scene_path.empty()) {
                // A bare `phos render --resume FILE [overrides]`: replay the checkpointed arguments.
                const std::string& resume = rc.config.progressive.resume_path;
                if (resume.empty())
                    throw InputError(
                        "render: give a scene file (or --resume CHECKPOINT to continue a render)");
                const film::ProgressiveState saved = film::load_checkpoint(resume);
                if (saved.command_line.empty())
                    throw InputError("checkpoint " + resume + ": it does not record its render's arguments");
                render_args = merge_arguments(*render, saved.command_line, render_args);
                std::vector<std::string> replay{"render"};
                replay.insert(replay.end(), render_args.begin(), render_args.end());
                if (const int code = parse(replay); code >= 0) return code;
            }
            rc.command_line = checkpoint_arguments(render_args, rc.scene_path);
            if (!resolution.empty()) rc.width = resolution[0], rc.height = resolution[1];
            if (!dof.empty()) {
                if (!(dof[0] >= 1 && dof[0] <= 4096 && dof[0] == float(int(dof[0]))))
                    throw InputError("--dof: SAMPLES must be a whole number >= 1");
                if (!(dof[1] > 0)) throw InputError("--dof: DISTANCE must be > 0");
                if (!(dof[2] >= 0)) throw InputError("--dof: RADIUS must be >= 0");
                rc.dof_samples = int(dof[0]);
                rc.dof_distance = dof[1];
                rc.dof_radius = dof[2];
            }
            if (progress_on) rc.progress = 1;
            if (progress_off) rc.progress = 0;
            run_render(rc);
        }
        if (diff->parsed()) run_diff(dc);
        return 0;
    } catch (const ParseError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    } catch (const InputError& e) {
        std::fprintf(stderr, "phos: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "phos: out of memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "phos: internal error: %s\n", e.what());
        return 1;
    }
}

}  // namespace phos::app
