// The one small interface every rendering algorithm implements, and the factory that picks one
// by name.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/progress.h"
#include "film/film.h"
#include "render/prepared.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class Integrator {
public:
    virtual ~Integrator() = default;
    // Renders into `film` (sized options.width x options.height).
    virtual void render(const Prepared& prepared, film::Film& film, Progress& progress) = 0;
};

}  // namespace phos::integrators
