// Picks an integrator by name ("whitted", "path", ...) — the names the CLI accepts.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.h"

namespace phos::integrators {

std::vector<std::string> integrator_names();
// Throws InputError for an unknown name.
std::unique_ptr<Integrator> make_integrator(const std::string& name);

}  // namespace phos::integrators
