// Agreement renders and their table (see agreement.h): the scene is loaded and its options
// resolved with `phos render`'s own functions (render_command.h), each render is the integrator
// made from the registry over a fresh Prepared and Film, exactly as `phos render` would make it.
#include "app/lib/agreement.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "app/lib/memory_check.h"
#include "app/lib/render_command.h"
#include "core/error.h"
#include "core/format.h"
#include "core/progress.h"
#include "core/stats.h"
#include "film/film.h"
#include "render/prepared.h"
#include "render/render_budget.h"

namespace phos::app {
namespace {

using integrators::IntegratorKind;

// The image size (see AgreementScene's constructor).
void choose_size(RenderCommand& cmd, const scene::Scene& scene, int max_size) {
    const int sw = scene.settings.width.value_or(512), sh = scene.settings.height.value_or(512);
    render::RenderOptions& r = cmd.render;
    const bool w = cmd.was_given("width"), h = cmd.was_given("height");
    if (w && h) return;
    if (w) {
        r.height = keep_aspect(r.width, sw, sh);
    } else if (h) {
        r.width = keep_aspect(r.height, sh, sw);
    } else {
        const double scale = std::min(1.0, double(max_size) / std::max(sw, sh));
        r.width = std::max(1, int(std::lround(sw * scale)));
        r.height = std::max(1, int(std::lround(sh * scale)));
    }
}

const std::string& name_of(IntegratorKind kind) { return integrators::integrator(kind).name; }

// "5 s (812 spp)", "64 iterations".
std::string budget_text(const AgreementRow& row) {
    const bool iterations = integrators::integrator(row.kind).counts == integrators::Counts::Iterations;
    const std::string units = std::to_string(row.units) + (iterations ? " iterations" : " spp");
    if (row.budget.units > 0) return units;
    return printf_string("%.3g s (%s)", row.seconds, units.c_str());
}

const char* const kChannels[3] = {"red", "green", "blue"};

}  // namespace

AgreementScene::AgreementScene(const RenderCommand& settings, int max_size) : cmd_(settings) {
    scene_ = load_render_scene(cmd_);
    choose_size(cmd_, scene_, max_size);
    std::string spp_source = "default";  // the budgets are the agreement's own
    apply_quality(cmd_, apply_scene_parameters(cmd_, scene_), spp_source);
    // ppm's one eye sample per pixel goes through the pixel's centre, so it converges to the
    // point-sampled image, not to the pixel's box integral that the others estimate; several
    // jittered ones (a new jitter per seed) estimate the integral, their error showing as noise
    // between the seeds.
    if (!cmd_.was_given("ppm-eye-samples")) cmd_.progressive.eye_samples = kAgreementPpmEyeSamples;
    for (const BoundTable& b : cmd_.tables()) {
        try {
            options::validate(*b.table, b.object);
        } catch (const options::ValueError& e) {
            throw InputError(e.what());
        }
    }
}

AgreementRender AgreementScene::render(IntegratorKind kind, const AgreementBudget& budget, uint64_t seed,
                                       bool reference) const {
    if (budget.units <= 0 && budget.seconds <= 0) throw InputError("agreement: a render needs a budget");
    RenderCommand cmd = cmd_;
    cmd.run.integrator = kind;
    cmd.render.seed = seed;
    cmd.render.spp = budget.units > 0 ? budget.units : int(render::kUnboundedIterations);
    cmd.budget.time = budget.units > 0 ? 0 : budget.seconds;
    if (reference && !cmd.was_given("regularize")) cmd.render.regularize = 0;
    Stats stats;
    check_memory(cmd, scene_, stats);
    const integrators::IntegratorConfig config{cmd.photon_map, cmd.progressive, {cmd.budget, {}}};
    const std::unique_ptr<integrators::Integrator> integrator = integrators::make_integrator(kind, config);
    const render::Prepared prepared(scene_, cmd.render, prepare_options(cmd), stats);
    film::Film film(cmd.render.width, cmd.render.height);
    Progress progress(false);
    const auto t0 = std::chrono::steady_clock::now();
    const render::RenderDone done = integrator->render(prepared, film, progress);
    return {film.image(), seconds_since(t0), done.units};
}

bool AgreementReport::agrees() const {
    return std::all_of(rows.begin(), rows.end(), [](const AgreementRow& r) { return r.agreement.agrees(); });
}

AgreementReport run_agreement(const AgreementScene& scene, const AgreementRequest& request) {
    AgreementReport report;
    report.scene = std::filesystem::path(scene.settings().scene_path).filename().string();
    report.width = scene.width();
    report.height = scene.height();
    report.seed = request.seed;
    report.blocks = request.blocks;
    if (report.blocks.sigmas <= 0)
        report.blocks.sigmas = film::tolerance_sigmas(
            double(request.tested.size()) *
            film::block_comparisons(scene.width(), scene.height(), report.blocks.block));

    // Two renders of `e`, seeds `seed` and `seed` + 1, into `row`.
    auto render_pair = [&](const AgreementRequest::Entry& e, uint64_t seed, AgreementRow& row,
                           bool reference) {
        row.kind = e.kind;
        row.budget = e.budget;
        row.claims = integrators::claims(e.kind, scene.scene());
        std::pair<AgreementRender, AgreementRender> out;
        for (int i = 0; i < 2; ++i) {
            if (request.on_render)
                request.on_render(name_of(e.kind) + " seed " + std::to_string(seed + uint64_t(i)));
            (i == 0 ? out.first : out.second) = scene.render(e.kind, e.budget, seed + uint64_t(i), reference);
        }
        row.seconds = (out.first.seconds + out.second.seconds) / 2;
        row.units = out.first.units;
        return out;
    };
    const auto reference = render_pair(request.reference, request.seed + 2, report.reference, true);
    // A path reference renders without regularisation (AgreementScene::render): unbiased.
    const bool plain_path =
        request.reference.kind == IntegratorKind::Path &&
        !(scene.settings().was_given("regularize") && scene.settings().render.regularize > 0);
    const film::BiasAllowance reference_bias =
        plain_path ? film::BiasAllowance{} : integrators::agreement_bias(request.reference.kind);
    for (const AgreementRequest::Entry& e : request.tested) {
        AgreementRow row;
        const auto tested = render_pair(e, request.seed, row, false);
        row.agreement = film::compare_blocks(
            {tested.first.image, tested.second.image}, integrators::agreement_bias(e.kind),
            {reference.first.image, reference.second.image}, reference_bias, report.blocks);
        report.rows.push_back(std::move(row));
    }
    return report;
}

std::string agreement_text(const AgreementReport& report, size_t max_blocks) {
    const AgreementRow& ref = report.reference;
    const unsigned long long seed = report.seed;
    std::string out = printf_string(
        "%s, %dx%d: reference %s at %s per seed (seeds %llu, %llu), each integrator at seeds %llu, %llu; "
        "%dx%d blocks, tolerance %.2f sigma (widened per block to Student's t)\n\n",
        report.scene.c_str(), report.width, report.height, name_of(ref.kind).c_str(),
        budget_text(ref).c_str(), seed + 2, seed + 3, seed, seed + 1, report.blocks.block,
        report.blocks.block, report.blocks.sigmas);
    out +=
        "| integrator | budget per seed | mean / reference mean | allowed | worst block | its ratio | "
        "tolerances off | blocks beyond tolerance | noise inflation | verdict |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const AgreementRow& row : report.rows) {
        const film::Agreement& a = row.agreement;
        const film::BlockComparison& w = a.worst;
        const char* verdict = a.agrees()          ? "agrees"
                              : a.mean_agrees()   ? "blocks differ"
                              : a.failing.empty() ? "mean differs"
                                                  : "mean and blocks differ";
        out += printf_string(
            "| %s%s | %s | %.4f | ±%.4f | (%d, %d) %s | %.4f | %.2f | %zu of %zu | %.3g | %s |\n",
            name_of(row.kind).c_str(), row.claims ? "" : " (does not claim the scene)",
            budget_text(row).c_str(), a.mean_ratio, a.mean_tolerance, w.x, w.y, kChannels[w.channel],
            w.ratio(), w.excess(), a.failing.size(), a.blocks.size(), a.inflation, verdict);
    }
    std::string blocks;
    for (const AgreementRow& row : report.rows) {
        std::vector<film::BlockComparison> failing = row.agreement.failing;
        std::stable_sort(failing.begin(), failing.end(),
                         [](const film::BlockComparison& a, const film::BlockComparison& b) {
                             return a.excess() > b.excess();
                         });
        for (size_t i = 0; i < failing.size() && i < max_blocks; ++i)
            blocks += "- " + name_of(row.kind) + ": " + film::describe(failing[i]) + "\n";
        if (failing.size() > max_blocks)
            blocks += "- " + name_of(row.kind) + ": and " + std::to_string(failing.size() - max_blocks) +
                      " more blocks\n";
    }
    if (!blocks.empty()) out += "\nBlocks that disagree (x, y of the block's top-left pixel):\n" + blocks;
    return out;
}

}  // namespace phos::app
