// Integrator registry.
#include "integrators/factory.h"

#include "core/error.h"
#include "integrators/path.h"
#include "integrators/whitted.h"

namespace phos::integrators {

std::vector<std::string> integrator_names() { return {"whitted", "path"}; }

std::unique_ptr<Integrator> make_integrator(const std::string& name, const IntegratorConfig& /*config*/) {
    if (name == "whitted") return std::make_unique<WhittedIntegrator>();
    if (name == "path") return std::make_unique<PathIntegrator>();
    throw InputError("unknown integrator '" + name + "'");
}

}  // namespace phos::integrators
