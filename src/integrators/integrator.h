// The one small interface every rendering algorithm implements (the registry, registry.h, makes
// them).
#pragma once

#include "core/progress.h"
#include "film/film.h"
#include "render/prepared.h"
#include "render/render_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class Integrator {
public:
    virtual ~Integrator() = default;
    // Renders into `film` (sized options.width x options.height); returns what it completed.
    virtual RenderDone render(const Prepared& prepared, film::Film& film, Progress& progress) = 0;
};

}  // namespace phos::integrators
