// Tile-parallel pixel loop (see pixel_loop.h for the determinism argument).
#include "integrators/pixel_loop.h"

#include <tbb/parallel_for.h>

#include "film/tiles.h"

namespace phos::integrators {

void render_samples(const Prepared& prepared, const std::string& label, Progress& progress,
                    const SampleFn& sample) {
    const RenderOptions& opt = prepared.options;
    const auto tiles = film::make_tiles(opt.width, opt.height);
    const int n = std::max(1, opt.spp) * std::max(1, opt.dof_samples);
    progress.start(label, tiles.size());
    tbb::parallel_for(size_t(0), tiles.size(), [&](size_t t) {
        const film::Tile& tile = tiles[t];
        RayCounts rays;
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                const uint64_t pixel = uint64_t(y) * uint64_t(opt.width) + uint64_t(x);
                for (int s = 0; s < n; ++s) {
                    Sampler sampler(opt.seed, pixel, uint64_t(s));
                    const Vec2 jitter = stratified_sample(s, n, sampler.next2());
                    const Vec2 lens = sampler.next2();
                    const accel::Ray ray =
                        prepared.camera.generate_ray(float(x) + jitter.x, float(y) + jitter.y, lens);
                    ++rays.camera;
                    sample(x, y, ray, sampler, rays);
                }
            }
        prepared.stats.add_rays(rays);
        progress.advance();
    });
    progress.finish();
}

void render_pixels(const Prepared& prepared, film::Film& film, Progress& progress,
                   const RadianceFn& radiance) {
    render_samples(prepared, "render", progress,
                   [&](int x, int y, const accel::Ray& ray, Sampler& sampler, RayCounts& rays) {
                       film.add_sample(x, y, radiance(ray, sampler, rays));
                   });
}

}  // namespace phos::integrators
