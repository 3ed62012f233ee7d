// The `phos` command line (CLI11). Every `phos render` option comes from the option tables
// (render_options.h): registration, validation wording, --help text with defaults. Accepts the seed
// renderer's single-dash long options (-aa, -resolution, -real...) by rewriting them to the
// double-dash form before parsing; suggests the nearest command for a misspelt one.
#include "app/lib/cli.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "accel/version.h"
#include "app/lib/agree_command.h"
#include "app/lib/diff_command.h"
#include "app/lib/image_commands.h"
#include "app/lib/photons_command.h"  // phos photons
#include "app/lib/render_command.h"
#include "app/lib/seed_flags.h"
#include "app/lib/upgrade_command.h"
#include "core/error.h"
#include "core/log.h"
#include "core/spelling.h"
#include "dist/ranks.h"
#include "integrators/registry.h"
#include "render/progressive_checkpoint.h"

namespace phos::app {
namespace {

constexpr const char* kVersion = "0.2.0";
const std::vector<std::string> kCommands{"render",  "diff",  "info",    "montage", "options",
                                         "photons", "agree", "upgrade", "help"};

std::string version_text() {
    std::string s = std::string("phos ") + kVersion + "\n";
#if defined(__clang__)
    s += "compiler: clang " __clang_version__ "\n";
#elif defined(__GNUC__)
    s += "compiler: GCC " __VERSION__ "\n";
#endif
    s += "C++ standard: " + std::to_string(__cplusplus) + "\n";
    s += "Embree " + accel::embree_version() + ", oneTBB " + accel::tbb_version() + "\n";
    return s;
}

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

// --help text of one option: its help, accepted values and default.
std::string describe(const options::Table& t, const options::Option& o) {
    std::string s = o.help;
    if (!o.applies_to.empty()) s = integrators::integrator_names(o.applies_to, "/") + ": " + s;
    if (!o.flag && !o.range_text.empty()) s += "; " + o.range_text;
    std::string def = t.default_text(o);
    if (def.empty()) def = "none";
    return s + " (default: " + def + ")";
}

// Registers every option of `bound` on `render`; each callback stores the value through the table
// (which validates it) and records the option as given.
void register_table(CLI::App& render, const BoundTable& bound, std::set<std::string>& given) {
    const options::Table& t = *bound.table;
    for (const options::Option& o : t.options) {
        std::string names = (o.short_name.empty() ? "" : "-" + o.short_name + ",") + "--" + o.name;
        for (const auto& a : o.aliases) names += ",--" + a;
        const options::Option* opt = &o;
        void* object = bound.object;
        CLI::Option* added = nullptr;
        if (o.flag) {
            if (!o.negation.empty()) names += ",!--" + o.negation;
            added = render.add_flag_function(
                names,
                [opt, object, &given](int64_t count) {
                    const bool on = (count > 0) == opt->flag_value;
                    opt->set(object, {on ? "true" : "false"});
                    given.insert(opt->name);
                },
                describe(t, o));
        } else {
            added = render
                        .add_option_function<std::vector<std::string>>(
                            names,
                            [opt, object, &given](const std::vector<std::string>& v) {
                                if (int(v.size()) != opt->arity)
                                    throw CLI::ValidationError(options::option_error(
                                        *opt, "expects " + std::to_string(opt->arity) + " values (" +
                                                  opt->value_name + "), got " + std::to_string(v.size())));
                                try {
                                    opt->set(object, v);
                                } catch (const options::ValueError& e) {
                                    throw CLI::ValidationError(options::option_error(*opt, e.what()));
                                }
                                given.insert(opt->name);
                            },
                            describe(t, o))
                        ->expected(o.arity)
                        ->type_name(o.value_name)
                        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
        }
        added->group(t.title);
        if (o.hidden) added->group("");
    }
}

bool g_render_command = false;  // the command is `render` (set once parsed)

// Prints `line` (a failure) and returns `code`. Under MPI (docs/distributed.md): a render that
// fails before it starts tells the other ranks (dist::agree_start), and the failure is printed
// once, by rank 0 or by the rank that alone failed; one that fails mid-render (while the others
// wait in a collective) ends the whole job; other failures are identical on every rank and rank 0
// prints them.
int report_failure(const std::string& line, int code) {
    const auto print = [&](bool with_rank) {
        if (with_rank)
            std::fprintf(stderr, "%s (rank %d of %d)\n", line.c_str(), dist::rank(), dist::ranks());
        else
            std::fprintf(stderr, "%s\n", line.c_str());
    };
    if (!dist::distributed()) {
        print(false);
        return code;
    }
    if (g_render_command && !dist::started()) {
        const dist::StartAgreement a = dist::agree_start(false);
        if (dist::root() || !a.root_failed) print(!dist::root());
        return code;
    }
    if (g_render_command && !dist::finished()) {
        print(true);
        std::fflush(stderr);
        dist::abort_all(code);
    }
    if (dist::root()) print(false);
    return code;
}

int print_error(const std::string& message) { return report_failure("phos: " + message, 2); }

}  // namespace

int run_cli(int argc, char** argv) {
    if (!dist::root()) {  // under MPI, rank 0 speaks for all (docs/distributed.md)
        log::silence();
        if (!std::freopen("/dev/null", "w", stdout)) std::fclose(stdout);
    }
    CLI::App app{"phos: a physically based photon-mapping renderer", "phos"};
    app.require_subcommand(1);
    app.set_version_flag("-V,--version", version_text());
    app.footer(
        "Commands: phos render SCENE [options] | phos diff IMAGE REFERENCE | phos agree SCENE | phos upgrade "
        "IN.pbrt OUT.pbrt | phos options | phos help [COMMAND]");

    RenderCommand rc;
    CLI::App* render = app.add_subcommand("render", "render a scene file (.scn, .pbrt, .scene) to an image");
    render->add_option("scene", rc.scene_path,
                       "scene file (.scn, .pbrt or .scene); may be omitted with --resume, which replays the "
                       "checkpointed render's arguments");
    std::string positional_output;
    render->add_option(
        "image", positional_output,
        "output image, as the seed renderer took it (phos render in.scn out.png); the same as -o");
    for (const BoundTable& b : rc.tables()) register_table(*render, b, rc.given);

    DiffCommand dc;
    CLI::App* diff =
        app.add_subcommand("diff", "compare an image with a reference: relMSE, mean ratio, window means");
    diff->add_option("image", dc.image, "rendered image (.exr, .pfm, ...)")->required();
    diff->add_option("reference", dc.reference, "reference image")->required();
    diff->add_option("--window", dc.window, "pixel window x0 x1 y0 y1 (half-open, y from the top)")
        ->expected(4);
    diff->add_option("--block-correlation", dc.block_correlation,
                     "also the correlation of the BxB block mean luminances of the images as displayed "
                     "(sRGB, clamped; they may differ in size by an integer factor, e.g. a 256x256 render "
                     "and a 512x512 reference)")
        ->check(CLI::Range(1, 1 << 16));

    std::vector<std::string> info_paths;
    CLI::App* info = app.add_subcommand(
        "info",
        "per image: size, mean, fraction of black pixels, non-finite values, speckle (firefly) fraction");
    info->add_option("images", info_paths, "images (.exr, .pfm, .png, ...)")->required();
    std::vector<int> info_windows;
    info->add_option("--window", info_windows,
                     "also print the mean luminance in pixel window x0 x1 y0 y1 (half-open, y from the top; "
                     "repeatable)")
        ->expected(4)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    std::string montage_out;
    std::vector<std::string> montage_in;
    int montage_cell = 128;
    CLI::App* mont = app.add_subcommand("montage", "a contact sheet of images in a grid");
    mont->add_option("output", montage_out, "output image")->required();
    mont->add_option("images", montage_in, "images to place, in order")->required();
    mont->add_option("--cell", montage_cell, "cell size in pixels (default 128)");

    // ---- phos photons (photons_command.h): the photon maps as a point cloud ----
    PhotonsCommand photons_cmd;
    CLI::App* photons = add_photons_command(app, photons_cmd, register_table);
    // ---- end phos photons ----

    AgreeCommand agree_cmd;
    CLI::App* agree = add_agree_command(app, agree_cmd, register_table);

    std::string upgrade_in, upgrade_out;
    CLI::App* upgrade = app.add_subcommand(
        "upgrade",
        "write a pbrt scene (pbrt-v3 or pbrt-v4, its includes inlined) as one pbrt-v4 file, as pbrt "
        "--upgrade does (phos also renders pbrt-v3 files directly)");
    upgrade->add_option("input", upgrade_in, "pbrt scene file")->required();
    upgrade->add_option("output", upgrade_out, "the pbrt-v4 file to write (not the input)")->required();

    CLI::App* opts = app.add_subcommand("options", "print every render option (markdown: docs/options.md)");
    bool markdown = false;
    opts->add_flag("--markdown", markdown, "markdown table (the default; kept for scripts)");

    CLI::App* help = app.add_subcommand("help", "help on phos or on one command: phos help render");
    std::string help_topic;
    help->add_option("command", help_topic, "render, diff, agree, upgrade or options");

    std::set<std::string> long_names;
    for (const CLI::Option* o : render->get_options())
        for (const auto& n : o->get_lnames()) long_names.insert(n);
    SeedFlagResult seed = translate_seed_flags(normalise_args(argc, argv, long_names));
    std::vector<std::string> args = std::move(seed.args);

    // A misspelt command: say what was meant instead of "a subcommand is required".
    if (!args.empty() && !args[0].empty() && args[0][0] != '-' &&
        std::find(kCommands.begin(), kCommands.end(), args[0]) == kCommands.end()) {
        const std::string ext = std::filesystem::path(args[0]).extension().string();
        if (ext == ".scn" || ext == ".pbrt" || ext == ".scene") {
            args.insert(args.begin(), "render");  // the seed's `photonmap in.scn out.png`
        } else {
            const std::string guess = nearest_name(args[0], kCommands);
            return print_error(
                "unknown command '" + args[0] + "'" +
                (guess.empty() ? "" : "; did you mean 'phos " + guess + "'?") +
                " (commands: render, diff, info, montage, options, photons, agree, upgrade, help)");
        }
    }

    move_trailing_output(args);
    // `--tev` alone (at the end, or before another option or a scene file): tev's default address.
    for (size_t i = 0; i < args.size(); ++i)
        if (args[i] == "--tev" && (i + 1 == args.size() || args[i + 1].find(':') == std::string::npos))
            args.insert(args.begin() + long(i) + 1, kTevDefault);

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
            std::string what = e.what();
            // CLI11: "The following argument was not expected: --sp" -> suggest the option meant.
            if (const size_t at = what.find("expected: "); at != std::string::npos) {
                std::istringstream words(what.substr(at + 10));
                for (std::string word; words >> word;) {
                    if (word.rfind("--", 0) != 0) continue;
                    const std::string guess =
                        nearest_name(word.substr(2, word.find('=') - 2),
                                     std::vector<std::string>(long_names.begin(), long_names.end()));
                    if (!guess.empty()) what += " (did you mean --" + guess + "?)";
                    break;
                }
            }
            return report_failure(
                "phos: " + what + "\nRun 'phos help' or 'phos help render' for the options.", 2);
        }
    };
    if (const int code = parse(args); code >= 0) return code;
    // Under MPI the ranks share a render; any other command runs on rank 0 alone.
    g_render_command = render->parsed();
    if (dist::distributed() && !g_render_command) {
        if (!dist::root()) return 0;
        dist::go_solo();
    }

    try {
        if (help->parsed()) {
            if (help_topic.empty()) {
                // app.help() would describe the `help` command itself once it is selected.
                std::fputs(app.get_formatter()->make_help(&app, "phos", CLI::AppFormatMode::Normal).c_str(),
                           stdout);
            } else if (CLI::App* sub =
                           std::find(kCommands.begin(), kCommands.end(), help_topic) != kCommands.end()
                               ? app.get_subcommand(help_topic)
                               : nullptr) {
                std::fputs(sub->help().c_str(), stdout);
            } else {
                const std::string guess = nearest_name(help_topic, kCommands);
                return print_error("no help on '" + help_topic + "'" +
                                   (guess.empty() ? "" : "; did you mean 'phos help " + guess + "'?"));
            }
            return 0;
        }
        if (photons->parsed()) return run_photons(photons_cmd);  // phos photons
        if (agree->parsed()) return run_agree(agree_cmd);
        if (upgrade->parsed()) {
            run_upgrade(upgrade_in, upgrade_out);
            return 0;
        }
        if (opts->parsed()) {
            std::fputs(options_markdown().c_str(), stdout);
            return 0;
        }
        if (render->parsed()) {
            const auto render_at = std::find(args.begin(), args.end(), "render");
            std::vector<std::string> render_args(render_at + 1, args.end());
            if (rc.scene_path.empty()) {
                // A bare `phos render --resume FILE [overrides]`: replay the checkpointed arguments.
                const std::string resume = rc.budget.resume_path;
                if (resume.empty())
                    throw InputError(
                        "render: give a scene file (or --resume CHECKPOINT to continue a render)");
                const render::ProgressiveState saved = render::load_checkpoint(resume);
                if (saved.command_line.empty())
                    throw InputError("checkpoint " + resume + ": it does not record its render's arguments");
                render_args = merge_arguments(*render, saved.command_line, render_args);
                std::vector<std::string> replay{"render"};
                replay.insert(replay.end(), render_args.begin(), render_args.end());
                rc.run = {};
                rc.scene = {};
                rc.render = {};
                rc.photon_map = {};
                rc.progressive = {};
                rc.budget = {};
                rc.given.clear();
                positional_output.clear();
                if (const int code = parse(replay); code >= 0) return code;
            }
            if (!positional_output.empty()) {
                if (rc.was_given("output"))
                    throw InputError("give the output image either after the scene or with -o, not both");
                rc.run.output = positional_output;
                rc.given.insert("output");
            }
            if (rc.was_given("spp") && rc.was_given("aa"))
                throw InputError("give either --spp or --aa, not both");
            if (rc.was_given("resolution") && (rc.was_given("width") || rc.was_given("height")))
                throw InputError("give either --resolution or --width/--height, not both");
            rc.command_line = checkpoint_arguments(render_args, rc.scene_path);
            log::set_quiet(rc.run.quiet);
            for (const std::string& w : seed.warnings) log::warn(w);
            if (const int code = run_render(rc); code != 0) return code;
        }
        if (diff->parsed()) run_diff(dc);
        if (info->parsed()) run_info(info_paths, info_windows);
        if (mont->parsed()) run_montage(montage_out, montage_in, montage_cell);
        return 0;
    } catch (const ParseError& e) {
        return report_failure(e.what(), 2);
    } catch (const InputError& e) {
        return print_error(e.what());
    } catch (const std::bad_alloc&) {
        return report_failure("phos: out of memory", 1);
    } catch (const std::exception& e) {
        return report_failure(std::string("phos: internal error: ") + e.what(), 1);
    }
}

}  // namespace phos::app
