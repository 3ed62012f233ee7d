// Integrator registry.
#include "integrators/factory.h"

#include "core/error.h"
#include "integrators/bdpt.h"
#include "integrators/path.h"
#include "integrators/photon_map.h"
#include "integrators/ppm.h"
#include "integrators/sppm.h"
#include "integrators/vcm.h"
#include "integrators/whitted.h"

namespace phos::integrators {

std::vector<std::string> integrator_names() {
    return {"whitted", "path", "photonmap", "ppm", "sppm", "bdpt", "vcm"};
}

bool counts_iterations(const std::string& name) {
    return name == "ppm" || name == "sppm" || name == "bdpt" || name == "vcm";
}

std::vector<std::string> integrator_layers(const std::string& name) {
    if (name == "whitted") return {"direct", "specular"};
    if (name == "path" || name == "photonmap" || name == "bdpt" || name == "vcm")
        return {"direct", "caustic", "indirect", "specular"};
    if (name == "ppm" || name == "sppm") return {"direct", "indirect"};
    return {};
}

std::unique_ptr<Integrator> make_integrator(const std::string& name, const IntegratorConfig& config) {
    // The option tables hold the valid ranges: the integrators take the structs as valid.
    try {
        options::validate(photon_map_options(), &config.photon_map);
        options::validate(progressive_options(), &config.progressive);
        options::validate(budget_options(), &config.budget);
    } catch (const options::ValueError& e) {
        throw InputError(e.what());
    }
    if (name == "whitted") return std::make_unique<WhittedIntegrator>(config.budget);
    if (name == "path") return std::make_unique<PathIntegrator>(config.budget);
    if (name == "photonmap") return std::make_unique<PhotonMapIntegrator>(config.photon_map, config.budget);
    if (name == "ppm") return std::make_unique<PpmIntegrator>(config.progressive, config.budget);
    if (name == "sppm") return std::make_unique<SppmIntegrator>(config.progressive, config.budget);
    if (name == "bdpt") return std::make_unique<BdptIntegrator>(config.progressive, config.budget);
    if (name == "vcm") return std::make_unique<VcmIntegrator>(config.progressive, config.budget);
    throw InputError("unknown integrator '" + name + "'");
}

}  // namespace phos::integrators
