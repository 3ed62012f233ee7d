// Re-running the traced pixel's camera samples (see pixel_trace.h).
#include "render/pixel_trace.h"

#include <algorithm>

#include "render/path_recorder.h"

namespace phos::render {

void trace_pixel_samples(const Prepared& P, const film::Film& film, const RadianceFn& radiance) {
    PathRecorder* trace = requested_trace();
    if (!trace) return;
    const int x = trace->x(), y = trace->y();
    const film::Tile pixel{x, y, x + 1, y + 1};
    const double taken = film.main().weight(x, y);  // the finite samples the pixel holds
    const uint64_t most = uint64_t(std::max(1, P.options.spp)) * uint64_t(std::max(1, P.options.dof_samples));
    RayCounts rays;  // not counted in the render's statistics
    uint64_t finite = 0;
    for (uint32_t s = 0; s < most && double(finite) < taken; ++s)
        render_tile_samples(
            P, pixel, s, s + 1,
            [&](int, int, const Ray& ray, float weight, Sampler& sampler, RayCounts& counts) {
                RecordingScope scope(trace, s);
                // Weight 0: a ray the camera's lenses blocked, a black sample as in the render.
                const Rgb L = weight != 0 ? radiance(ray, sampler, counts) * weight : Rgb(0.0f);
                scope.done(L);
                if (L.is_finite()) ++finite;
            },
            rays);
}

}  // namespace phos::render
