// Tile-parallel pixel loop (see pixel_loop.h for the determinism argument).
#include "integrators/pixel_loop.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

#include "film/tiles.h"

namespace phos::integrators {

void for_each_sample(const Prepared& prepared, const SampleFn& sample,
                     const std::function<void(const RayCounts& rays)>& tile_done) {
    const RenderOptions& opt = prepared.options;
    const auto tiles = film::make_tiles(opt.width, opt.height);
    const int n = std::max(1, opt.spp) * std::max(1, opt.dof_samples);
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
        if (tile_done) tile_done(rays);
    });
}

void render_samples(const Prepared& prepared, const std::string& label, Progress& progress,
                    const SampleFn& sample) {
    progress.start(label, film::make_tiles(prepared.options.width, prepared.options.height).size());
    for_each_sample(prepared, sample, [&](const RayCounts& rays) {
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

void render_layers(const Prepared& prepared, film::Film& film, Progress& progress, const std::string& label,
                   const std::vector<std::string>& layers, const PartsFn& parts) {
    // Layers are created before the parallel loop (creation is not thread-safe).
    constexpr Rgb RadianceParts::*kParts[] = {&RadianceParts::direct, &RadianceParts::caustic,
                                              &RadianceParts::indirect, &RadianceParts::specular};
    constexpr const char* kNames[] = {"direct", "caustic", "indirect", "specular"};
    std::vector<std::pair<film::Layer*, Rgb RadianceParts::*>> out;
    for (const std::string& name : layers) {
        const auto it = std::find(std::begin(kNames), std::end(kNames), name);
        if (it == std::end(kNames)) throw std::invalid_argument("render_layers: unknown layer " + name);
        out.emplace_back(&film.layer(name), kParts[it - std::begin(kNames)]);
    }
    render_samples(prepared, label, progress,
                   [&](int x, int y, const accel::Ray& ray, Sampler& sampler, RayCounts& rays) {
                       RadianceParts p;
                       film.add_sample(x, y, parts(ray, sampler, rays, p));
                       for (const auto& [layer, part] : out) layer->add(x, y, p.*part);
                   });
}

}  // namespace phos::integrators
