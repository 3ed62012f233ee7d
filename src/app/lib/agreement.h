// Rendering one scene with several integrators to see whether they agree (`phos agree`, the
// agreement matrix in tests/agreement): the scene loaded and its settings resolved once as `phos
// render` resolves them, renders in process by integrator, budget and seed, each integrator's two
// seeds compared block by block with the reference's (film/block_agreement.h), and the table.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "app/lib/render_options.h"
#include "core/image.h"
#include "film/block_agreement.h"
#include "integrators/registry.h"
#include "scene/scene.h"

namespace phos::app {

// How much one render does: `units` samples per pixel or iterations (whichever the integrator
// counts), else `seconds` of wall time.
struct AgreementBudget {
    int units = 0;
    double seconds = 0;
};

struct AgreementRender {
    Image image;
    double seconds = 0;  // the render's wall time (loading and preparing not counted)
    uint64_t units = 0;  // samples per pixel or iterations completed
};

// ppm's hit points per pixel in agreement renders unless --ppm-eye-samples is given (see
// agreement.cpp).
inline constexpr int kAgreementPpmEyeSamples = 4;

class AgreementScene {
public:
    // Loads `settings.scene_path` as `phos render` does and applies the scene file's integrator
    // parameters and the --quality preset to `settings`' option structs; ppm takes
    // kAgreementPpmEyeSamples hit points per pixel unless --ppm-eye-samples was given. The image: `settings`'
    // width and height where given on the command line (one alone keeps the scene's aspect ratio),
    // else the scene file's (512 x 512 without one) scaled down to at most `max_size` pixels on its
    // longer side. Throws ParseError / InputError for bad input.
    AgreementScene(const RenderCommand& settings, int max_size);

    const scene::Scene& scene() const { return scene_; }
    const RenderCommand& settings() const { return cmd_; }
    int width() const { return cmd_.render.width; }
    int height() const { return cmd_.render.height; }

    // One render with `kind` (its options as resolved, the memory checked first). A reference
    // render (`reference`) leaves out path's regularisation unless the command line set it: the
    // reference is then unbiased at any budget.
    AgreementRender render(integrators::IntegratorKind kind, const AgreementBudget& budget, uint64_t seed,
                           bool reference = false) const;

private:
    RenderCommand cmd_;
    scene::Scene scene_;
};

struct AgreementRequest {
    struct Entry {
        integrators::IntegratorKind kind;
        AgreementBudget budget;
    };
    std::vector<Entry> tested;  // the reference may be among them (at a smaller budget)
    Entry reference;
    uint64_t seed = 0;  // each tested integrator renders with seeds seed and seed + 1, the
                        // reference with seed + 2 and seed + 3
    // Block size and floor; sigmas <= 0: from the number of comparisons (tolerance_sigmas).
    film::BlockSettings blocks{8, 0, 1e-3};
    // Called before each render ("sppm seed 1"), for messages.
    std::function<void(const std::string& what)> on_render;
};

struct AgreementRow {
    integrators::IntegratorKind kind;
    AgreementBudget budget;
    double seconds = 0;  // per seed (their mean)
    uint64_t units = 0;  // completed by the first seed
    bool claims = true;  // whether it claims the scene (integrators::claims)
    film::Agreement agreement;
};

struct AgreementReport {
    std::string scene;
    int width = 0, height = 0;
    uint64_t seed = 0;           // the request's
    AgreementRow reference;      // its budget, time and units (its agreement is unused)
    film::BlockSettings blocks;  // with the sigmas used
    std::vector<AgreementRow> rows;
    bool agrees() const;
};

// Renders every tested integrator and the reference twice and compares them.
AgreementReport run_agreement(const AgreementScene& scene, const AgreementRequest& request);

// A line saying what was compared, the markdown table (integrator | budget per seed | mean /
// reference mean | allowed | worst block | its ratio | tolerances off | blocks beyond tolerance |
// noise inflation | verdict), then at most `max_blocks` of each integrator's disagreeing blocks,
// the worst first.
std::string agreement_text(const AgreementReport& report, size_t max_blocks = 10);

}  // namespace phos::app
