// The integrator registry (see registry.h): the table, lookups by kind and name, and make.
#include "integrators/registry.h"

#include "core/error.h"
#include "integrators/bdpt.h"
#include "integrators/path.h"
#include "integrators/photon_map.h"
#include "integrators/ppm.h"
#include "integrators/sppm.h"
#include "integrators/vcm.h"
#include "integrators/whitted.h"

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
    // kind, name, what the budget counts, --layers, the options read, memory, traces, make.
    static const std::vector<IntegratorInfo> table{
        {K::Whitted, "whitted", SamplesPerPixel, layers(Direct, Specular), Reads::Nothing, Film, true,
         from_budget<WhittedIntegrator>},
        {K::Path, "path", SamplesPerPixel, all_components(), Reads::Nothing, Film, true,
         from_budget<PathIntegrator>},
        {K::PhotonMap, "photonmap", SamplesPerPixel, all_components(), Reads::PhotonMap, PhotonMaps, true,
         [](const IntegratorConfig& c, const IntegratorInfo& self) -> std::unique_ptr<Integrator> {
             return std::make_unique<PhotonMapIntegrator>(c.photon_map, c.budget, self.layers);
         }},
        {K::Ppm, "ppm", Iterations, layers(Direct, Indirect), Reads::Progressive, HitPoints, true,
         progressive<PpmIntegrator>},
        {K::Sppm, "sppm", Iterations, layers(Direct, Indirect), Reads::Progressive, VisiblePoints, true,
         progressive<SppmIntegrator>},
        {K::Bdpt, "bdpt", Iterations, all_components(), Reads::Progressive, FixedSums, false,
         [](const IntegratorConfig& c, const IntegratorInfo&) -> std::unique_ptr<Integrator> {
             return std::make_unique<BdptIntegrator>(c.progressive, c.budget);
         }},
        {K::Vcm, "vcm", Iterations, all_components(), Reads::Progressive, LightVertices, false,
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
