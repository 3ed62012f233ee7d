// `phos agree`: the command line (its own budget and choice of integrators, plus the render option
// tables that shape the image), then the agreement renders (app/lib/agreement.h) and the table.
#include "app/lib/agree_command.h"

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <optional>
#include <sstream>

#include "app/lib/agreement.h"
#include "core/error.h"
#include "core/format.h"
#include "core/log.h"
#include "integrators/progressive_options.h"
#include "integrators/transport_options.h"

namespace phos::app {
namespace {

using integrators::IntegratorKind;

bool one_of(const std::string& name, std::initializer_list<const char*> names) {
    return std::any_of(names.begin(), names.end(), [&](const char* n) { return name == n; });
}

const options::Table& agree_run_options() {
    static const options::Table t = options::subset(run_options(), [](const std::string& n) {
        return one_of(n, {"threads", "quiet", "strict", "max-memory", "quality"});
    });
    return t;
}

const options::Table& agree_sampling_options() {
    static const options::Table t = options::subset(render::sampling_options(), [](const std::string& n) {
        return one_of(n, {"max-depth", "ambient", "background-light"});
    });
    return t;
}

// The progressive options without --iterations (the budget is --time).
const options::Table& agree_progressive_options() {
    static const options::Table t = options::subset(integrators::progressive_options(),
                                                    [](const std::string& n) { return n != "iterations"; });
    return t;
}

// "ppm,sppm" as kinds; InputError naming the option for an unknown name.
std::vector<IntegratorKind> parse_integrators(const std::string& list) {
    std::vector<IntegratorKind> out;
    std::stringstream in(list);
    for (std::string name; std::getline(in, name, ',');) {
        const std::optional<IntegratorKind> kind = integrators::find_integrator(name);
        if (!kind)
            throw InputError("--integrators: unknown integrator '" + name + "' (integrators: " +
                             integrators::integrator_names(options::IntegratorSet{~0u}, ", ") + ")");
        if (std::find(out.begin(), out.end(), *kind) == out.end()) out.push_back(*kind);
    }
    if (out.empty()) throw InputError("--integrators: name at least one integrator");
    return out;
}

}  // namespace

CLI::App* add_agree_command(CLI::App& app, AgreeCommand& cmd, RegisterTable register_table) {
    CLI::App* sub = app.add_subcommand(
        "agree",
        "render a scene with every integrator at equal time and compare each with a reference block by "
        "block: a table of mean ratios and the blocks that disagree (exit 1 if any)");
    sub->add_option("scene", cmd.scene_path, "scene file (.scn, .pbrt, .scene)")->required();
    const std::string group = "Agreement";
    sub->add_option("--time", cmd.time,
                    printf_string("seconds per integrator and seed; the reference gets %g times as long "
                                  "(default: 5)",
                                  kReferenceTimeFactor))
        ->check(CLI::PositiveNumber)
        ->type_name("SECONDS")
        ->group(group);
    RenderCommand& s = cmd.settings;
    for (const char* side : {"width", "height"})
        sub->add_option_function<int>(
               std::string("--") + side,
               [&s, side](int v) {
                   (std::string(side) == "width" ? s.render.width : s.render.height) = v;
                   s.given.insert(side);
               },
               printf_string(
                   "image %s in pixels; given alone, the other follows the scene's aspect ratio "
                   "(default: the scene's size scaled down to at most %d pixels on its longer side)",
                   side, kAgreeMaxSize))
            ->check(CLI::Range(1, scene::RenderSettings::kMaxResolution))
            ->type_name("N")
            ->group(group);
    sub->add_option(
           "--integrators", cmd.integrators,
           "integrators to compare, comma-separated (default: every integrator that claims the scene; "
           "see docs/usage.md)")
        ->type_name("LIST")
        ->group(group);
    sub->add_option("--reference", cmd.reference,
                    "the integrator the others are compared with (default: path, or bdpt where path cannot "
                    "render the scene's caustics)")
        ->type_name("NAME")
        ->group(group);
    sub->add_option("--block", cmd.block, "block side in pixels (default: 8)")
        ->check(CLI::PositiveNumber)
        ->type_name("N")
        ->group(group);
    sub->add_option(
           "--seed", cmd.seed,
           "first seed: each integrator renders with seeds S and S+1, the reference with S+2 and S+3 "
           "(default: 0)")
        ->type_name("S")
        ->group(group);
    for (const BoundTable& b : std::vector<BoundTable>{{&agree_run_options(), &s.run},
                                                       {&agree_sampling_options(), &s.render},
                                                       {&integrators::transport_options(), &s.render},
                                                       {&scene_options(), &s.scene},
                                                       {&integrators::photon_map_options(), &s.photon_map},
                                                       {&agree_progressive_options(), &s.progressive}})
        register_table(*sub, b, s.given);
    return sub;
}

int run_agree(const AgreeCommand& command) {
    RenderCommand settings = command.settings;
    settings.scene_path = command.scene_path;
    log::set_quiet(settings.run.quiet);
    std::optional<tbb::global_control> threads;
    if (settings.run.threads > 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(settings.run.threads));

    const AgreementScene scene(settings, kAgreeMaxSize);
    AgreementRequest request;
    request.seed = command.seed;
    request.blocks.block = command.block;
    const AgreementBudget budget{0, command.time};
    const std::vector<IntegratorKind> tested = [&] {
        if (!command.integrators.empty()) return parse_integrators(command.integrators);
        std::vector<IntegratorKind> out;
        for (const integrators::IntegratorInfo& i : integrators::integrators())
            if (integrators::claims(i.kind, scene.scene())) out.push_back(i.kind);
        return out;
    }();
    for (const IntegratorKind k : tested) request.tested.push_back({k, budget});
    IntegratorKind reference = integrators::agreement_reference(scene.scene());
    if (!command.reference.empty()) {
        const std::optional<IntegratorKind> kind = integrators::find_integrator(command.reference);
        if (!kind) throw InputError("--reference: unknown integrator '" + command.reference + "'");
        reference = *kind;
        if (!integrators::claims(reference, scene.scene()))
            log::warn("--reference " + command.reference +
                      ": this integrator cannot render all of the scene's light transport (docs/usage.md)");
    }
    request.reference = {reference, {0, command.time * kReferenceTimeFactor}};
    const double total = command.time * 2 * (double(tested.size()) + kReferenceTimeFactor);
    log::info(printf_string("phos agree: %s at %dx%d, %zu integrators against %s: about %.0f s",
                            command.scene_path.c_str(), scene.width(), scene.height(), tested.size(),
                            integrators::integrator(reference).name.c_str(), total));
    request.on_render = [](const std::string& what) { log::info("phos agree: rendering " + what); };

    const AgreementReport report = run_agreement(scene, request);
    std::fputs(agreement_text(report).c_str(), stdout);
    std::fflush(stdout);
    return report.agrees() ? 0 : 1;
}

}  // namespace phos::app
