// The integrators phos has, in one typed table: each one's kind, name, what its budget counts, the
// component layers it records, the option struct it reads, what it holds in memory, whether it
// traces pixels, and how to make it. Code that asks "which integrator" asks this table by kind;
// names are parsed into kinds once (--integrator, scene files, checkpoints keep the name as text).
// The algorithms themselves never include it: make() hands them what they need.
#pragma once

#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/option_table.h"
#include "film/block_agreement.h"
#include "integrators/integrator.h"
#include "integrators/photon_map_options.h"
#include "integrators/progressive_options.h"
#include "render/path_radiance.h"
#include "render/render_budget.h"
#include "scene/scene.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

// One per row of the table, in its order (which is --help's and every list's order).
enum class IntegratorKind { Whitted, Path, PhotonMap, Ppm, Sppm, Bdpt, Vcm };

// What an integrator's budget (--spp, --iterations) counts.
enum class Counts {
    SamplesPerPixel,  // samples per pixel, taken in passes over the image (render/sample_passes.h)
    Iterations,       // iterations over the whole image (render/progressive_budget.h)
};

// The option struct an integrator reads besides RenderOptions and its budget.
enum class Reads { Nothing, PhotonMap, Progressive };

// What a render holds besides the scene and the film, as memory_estimate.cpp models it.
enum class RenderMemory {
    Film,           // nothing more (a checkpoint copies the film)
    PhotonMaps,     // the photon maps, their build and caches
    HitPoints,      // PPM: --ppm-eye-samples hit points per pixel, their statistics and grid
    VisiblePoints,  // SPPM: one visible point per pixel (two with media), statistics and grid
    FixedSums,      // fixed-point image sums
    LightVertices,  // fixed-point sums and each iteration's light vertices (merging: their grid)
};

// The per-integrator option structs and the budget; each integrator reads its own.
// How an integrator's image relates to the true one: what the agreement matrix
// (tests/agreement) and `phos agree` compare it with, and how much bias they allow it.
enum class Convergence {
    Unbiased,      // its expectation is the true image at any budget (bdpt; path with --regularize 0)
    Consistent,    // biased by a density-estimation kernel or a regularisation bandwidth that
                   // shrinks as the budget grows (ppm, sppm, vcm; path's --regularize): the bias
                   // vanishes in the limit
    KernelBiased,  // biased by kernels that do not shrink (photonmap: k-nearest estimates of fixed
                   // k, the irradiance cache): close to the true image, never equal
    Inconsistent,  // leaves light transport out by design (whitted: no indirect diffuse light);
                   // never compared
};

struct IntegratorConfig {
    PhotonMapOptions photon_map;
    ProgressiveOptions progressive;
    RenderBudget budget;  // every integrator's time budget, previews and checkpoints
};

struct IntegratorInfo;
using MakeIntegrator = std::unique_ptr<Integrator> (*)(const IntegratorConfig& config,
                                                       const IntegratorInfo& self);

struct IntegratorInfo {
    IntegratorKind kind;
    std::string name;  // --integrator NAME; checkpoints record it
    Counts counts;
    std::vector<Component> layers;  // what --layers records (none: --layers is refused)
    Reads reads;
    RenderMemory memory;
    bool traces;  // --trace-pixel records its camera samples
    Convergence convergence;
    MakeIntegrator make;  // from valid options (make_integrator checks them first)
};

// Every integrator, in kind order.
const std::vector<IntegratorInfo>& integrators();
const IntegratorInfo& integrator(IntegratorKind kind);
// The kind called `name`, if any.
std::optional<IntegratorKind> find_integrator(const std::string& name);
// The same; InputError "unknown integrator 'magic'" when there is none.
IntegratorKind integrator_kind(const std::string& name);
// The names as option choices (--integrator).
options::Choices<IntegratorKind> integrator_choices();

// Option::applies_to over kinds: the set of `kinds`, whether `o` applies to `kind`, and the names
// of a set's integrators joined by `separator` ("ppm/sppm/vcm").
constexpr options::IntegratorSet integrator_set(std::initializer_list<IntegratorKind> kinds) {
    options::IntegratorSet set;
    for (const IntegratorKind k : kinds) set.bits |= 1u << unsigned(k);
    return set;
}
bool applies(const options::Option& o, IntegratorKind kind);
std::string integrator_names(options::IntegratorSet set, const std::string& separator);

// Agreement (tests/agreement, `phos agree`; docs/usage.md "phos agree"): whether `kind` can render
// all of `scene`'s light transport. Whitted never does (it is not consistent). Path tracing with
// next-event estimation cannot sample light from a delta light (point, spot, directional) reaching
// a diffuse surface or a medium through a mirror or sharp glass (L S+ D: the caustic is found
// neither by a light sample, blocked by the delta surface, nor by a BSDF sample, which cannot hit a
// point): path does not claim scenes with both a delta light and a delta lobe. ppm and sppm emit no
// photons from media, so they do not claim scenes whose media glow.
bool claims(IntegratorKind kind, const scene::Scene& scene);
// The integrator the others are compared with: path where it claims the scene and no delta light
// shines through a sharp glossy surface, else bdpt (unbiased, with light tracing for the caustics
// path misses or finds only as fireflies). bdpt, too, misses a delta light's
// caustic seen through a mirror or glass (L S+ D S+ E: no vertex to connect); on such a scene a
// consistent integrator (vcm) is the better reference.
IntegratorKind agreement_reference(const scene::Scene& scene);
// The bias `kind` may show against the true image at a modest budget (block_agreement.h).
film::BiasAllowance agreement_bias(IntegratorKind kind);

// Throws InputError for options outside their tables' ranges (the message names the option:
// "--alpha: 0 is not in (0, 1]").
std::unique_ptr<Integrator> make_integrator(IntegratorKind kind, const IntegratorConfig& config = {});

}  // namespace phos::integrators
