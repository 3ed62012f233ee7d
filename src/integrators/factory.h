// Picks an integrator by name ("whitted", "path", ...) — the names the CLI accepts — and hands it
// its own options.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "integrators/photon_map_options.h"
#include "integrators/progressive_options.h"
#include "render/render_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

// The per-integrator option structs; each integrator reads its own.
struct IntegratorConfig {
    PhotonMapOptions photon_map;
    ProgressiveOptions progressive;
    RenderBudget budget;  // every integrator's time budget, previews and checkpoints
};

std::vector<std::string> integrator_names();
// True for the integrators whose budget is a count of iterations over the whole image (ppm, sppm,
// bdpt, vcm: --iterations and --spp mean the same) rather than samples per pixel taken in passes.
bool counts_iterations(const std::string& name);
// The component layers integrator `name` records with RenderOptions::layers (they sum to the image).
std::vector<std::string> integrator_layers(const std::string& name);
// Throws InputError for an unknown name or options outside their tables' ranges (the message
// names the option: "--alpha: 0 is not in (0, 1]").
std::unique_ptr<Integrator> make_integrator(const std::string& name, const IntegratorConfig& config = {});

}  // namespace phos::integrators
