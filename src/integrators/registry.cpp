// The integrator registry (see registry.h): the table, lookups by kind and name, and make.
#include "integrators/registry.h"

#include <algorithm>

#include "core/error.h"
#include "integrators/bdpt.h"
#include "integrators/path.h"
#include "integrators/photon_map.h"
#include "integrators/ppm.h"
#include "integrators/sppm.h"
#include "integrators/vcm.h"
#include "integrators/whitted.h"
#include "photon/projection_map.h"
#include "render/options.h"

namespace phos::integrators {
namespace {

using enum Component;
using K = IntegratorKind;

// The component layers `c...`.
template <class... C>
std::vector<Component> layers(C... c) {
    return {c...};
}

// make() of an integrator built from the budget and its layers (the sample-based ones).
template <class I>
std::unique_ptr<Integrator> from_budget(const IntegratorConfig& c, const IntegratorInfo& self) {
    return std::make_unique<I>(c.budget, self.layers);
}
// make() of an integrator built from the progressive options and the budget.
template <class I>
std::unique_ptr<Integrator> progressive(const IntegratorConfig& c, const IntegratorInfo&) {
    return std::make_unique<I>(c.progressive, c.budget);
}

}  // namespace

const std::vector<IntegratorInfo>& integrators() {
    using enum Counts;
    using enum RenderMemory;
    using enum Convergence;
    // kind, name, what the budget counts, --layers, the options read, memory, traces, convergence,
    // make.
    static const std::vector<IntegratorInfo> table{
        {K::Whitted, "whitted", SamplesPerPixel, layers(Direct, Specular), Reads::Nothing, Film, true,
         Inconsistent, from_budget<WhittedIntegrator>},
        // path: consistent with its default regularisation (--regularize 0: unbiased).
        {K::Path, "path", SamplesPerPixel, all_components(), Reads::Nothing, Film, true, Consistent,
         from_budget<PathIntegrator>},
        {K::PhotonMap, "photonmap", SamplesPerPixel, all_components(), Reads::PhotonMap, PhotonMaps, true,
         KernelBiased,
         [](const IntegratorConfig& c, const IntegratorInfo& self) -> std::unique_ptr<Integrator> {
             return std::make_unique<PhotonMapIntegrator>(c.photon_map, c.budget, self.layers);
         }},
        {K::Ppm, "ppm", Iterations, layers(Direct, Indirect), Reads::Progressive, HitPoints, true, Consistent,
         progressive<PpmIntegrator>},
        {K::Sppm, "sppm", Iterations, layers(Direct, Indirect), Reads::Progressive, VisiblePoints, true,
         Consistent, progressive<SppmIntegrator>},
        {K::Bdpt, "bdpt", Iterations, all_components(), Reads::Progressive, FixedSums, false, Unbiased,
         [](const IntegratorConfig& c, const IntegratorInfo&) -> std::unique_ptr<Integrator> {
             return std::make_unique<BdptIntegrator>(c.progressive, c.budget);
         }},
        {K::Vcm, "vcm", Iterations, all_components(), Reads::Progressive, LightVertices, false, Consistent,
         [](const IntegratorConfig& c, const IntegratorInfo&) -> std::unique_ptr<Integrator> {
             return std::make_unique<VcmIntegrator>(c.progressive, c.budget);
         }},
    };
    return table;
}

const IntegratorInfo& integrator(IntegratorKind kind) { return integrators().at(size_t(kind)); }

std::optional<IntegratorKind> find_integrator(const std::string& name) {
    for (const IntegratorInfo& i : integrators())
        if (i.name == name) return i.kind;
    return std::nullopt;
}

IntegratorKind integrator_kind(const std::string& name) {
    if (const auto kind = find_integrator(name)) return *kind;
    throw InputError("unknown integrator '" + name + "'");
}

options::Choices<IntegratorKind> integrator_choices() {
    options::Choices<IntegratorKind> out;
    for (const IntegratorInfo& i : integrators()) out.push_back({i.kind, i.name});
    return out;
}

bool applies(const options::Option& o, IntegratorKind kind) { return o.applies(unsigned(kind)); }

std::string integrator_names(options::IntegratorSet set, const std::string& separator) {
    std::string out;
    for (const IntegratorInfo& i : integrators())
        if (set.contains(unsigned(i.kind))) out += (out.empty() ? "" : separator) + i.name;
    return out;
}

namespace {

bool delta_light(const scene::Light& l) {
    using enum scene::Light::Kind;
    return l.kind == Point || l.kind == Spot || l.kind == Directional || l.kind == Goniometric ||
           l.kind == Projection;
}

// Whether a shape of the scene (or of an object it instances) has a material with a mirror or
// sharp-glass lobe, or with `sharp_glossy` also a glossy lobe followed at the default
// --sharp-glossy.
bool has_delta_surface(const scene::Scene& scene, bool sharp_glossy = false) {
    const std::vector<bool> marked =
        sharp_glossy ? photon::caustic_caster_materials(scene, render::kDefaultSharpGlossy)
                     : photon::delta_lobe_materials(scene);
    auto delta = [&](const scene::Shape& s) {
        return s.material >= 0 && size_t(s.material) < marked.size() && marked[size_t(s.material)];
    };
    for (const scene::Shape& s : scene.shapes)
        if (delta(s)) return true;
    for (const scene::Object& o : scene.objects)
        for (const scene::Shape& s : o.shapes)
            if (delta(s)) return true;
    return false;
}

bool glowing_medium(const scene::Scene& scene) {
    for (const scene::Medium& m : scene.media)
        if (!m.emission.is_black()) return true;
    return false;
}

}  // namespace

bool claims(IntegratorKind kind, const scene::Scene& scene) {
    switch (kind) {
        case K::Whitted:
            return false;
        case K::Path:
            return !(std::any_of(scene.lights.begin(), scene.lights.end(), delta_light) &&
                     has_delta_surface(scene));
        case K::Ppm:
        case K::Sppm:
            return !glowing_medium(scene);
        default:
            return true;
    }
}

IntegratorKind agreement_reference(const scene::Scene& scene) {
    // A delta light behind sharp glossy surfaces: path reaches it only by next-event estimation at
    // a vertex inside the glossy chain, which makes a reference of fireflies; bdpt's light paths
    // carry it smoothly.
    const bool delta_lights = std::any_of(scene.lights.begin(), scene.lights.end(), delta_light);
    return claims(K::Path, scene) && !(delta_lights && has_delta_surface(scene, true)) ? K::Path : K::Bdpt;
}

film::BiasAllowance agreement_bias(IntegratorKind kind) {
    // The kernels' radii at the end of a modest render, in pixels: ppm and sppm start at 4 pixel
    // footprints (--radius-pixels, or the pilot's density radius of about as many) and their radius
    // reduction (alpha 0.7: R^2 falls as about i^-0.3) halves that within 64 iterations; vcm's merging
    // radius starts from the same pilot and shrinks alike; photonmap's caustic estimate is held to at
    // least 1 pixel (--caustic-min-pixels) and its global map is seen through final gathering (blurred
    // one bounce away), with the irradiance cache interpolating between points. 2 pixels for all four.
    // The image mean: 2 % (the kernels' edge losses over a whole image of walls and corners).
    switch (integrator(kind).convergence) {
        case Convergence::Consistent:
        case Convergence::KernelBiased:
            return {2.0, 0.02};
        default:
            return {};
    }
}

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind, const IntegratorConfig& config) {
    const IntegratorInfo& info = integrator(kind);
    // The option tables hold the valid ranges: the integrators take the structs as valid.
    try {
        options::validate(budget_options(), &config.budget.settings);
        if (info.reads == Reads::PhotonMap) options::validate(photon_map_options(), &config.photon_map);
        if (info.reads == Reads::Progressive) options::validate(progressive_options(), &config.progressive);
    } catch (const options::ValueError& e) {
        throw InputError(e.what());
    }
    return info.make(config, info);
}

}  // namespace phos::integrators
