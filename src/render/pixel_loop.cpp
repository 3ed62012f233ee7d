// Tile-parallel pixel loop in sample passes (see pixel_loop.h for the determinism argument and
// sample_passes.h for budgets, interrupts and checkpoints).
#include "render/pixel_loop.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "render/pixel_trace.h"
#include "render/sample_passes.h"

namespace phos::render {

namespace {
constinit thread_local uint32_t t_sample_index = 0;
constinit thread_local float t_wavelength_sample = -1;
}  // namespace

uint32_t current_sample_index() { return t_sample_index; }
float current_wavelength_sample() { return t_wavelength_sample; }

void render_tile_samples(const Prepared& prepared, const film::Tile& tile, uint32_t s0, uint32_t s1,
                         const SampleFn& sample, RayCounts& rays) {
    const RenderOptions& opt = prepared.options;
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) {
            const uint64_t pixel = uint64_t(y) * uint64_t(opt.width) + uint64_t(x);
            const uint64_t scramble = Sampler(opt.seed, pixel, 0x7069786a6974ULL).next_bits();
            for (uint32_t s = s0; s < s1; ++s) {
                Sampler sampler(opt.seed, pixel, uint64_t(s));
                const PixelFilterSampler::FilmSample at =
                    prepared.filter.sample(pixel_sample_position(s, scramble));
                const Vec2 lens = sampler.next2();
                float camera_weight = 1;
                const Ray ray = prepared.camera.generate_ray(float(x) + at.position.x,
                                                             float(y) + at.position.y, lens, camera_weight);
                ++rays.camera;
                t_sample_index = s;
                t_wavelength_sample = spectrum::wavelength_sequence_point(s, hash_combine(scramble, 0x776c));
                // A ray the camera's lenses block comes with weight 0: the sample counts as black.
                sample(x, y, ray, at.weight * camera_weight, sampler, rays);
                t_sample_index = 0;
                t_wavelength_sample = -1;
            }
        }
}

void for_each_sample(const Prepared& prepared, int samples, const SampleFn& sample,
                     const std::function<void(const RayCounts& rays)>& tile_done) {
    const auto tiles = film::make_tiles(prepared.options.width, prepared.options.height);
    tbb::parallel_for(size_t(0), tiles.size(), [&](size_t t) {
        RayCounts rays;
        render_tile_samples(prepared, tiles[t], 0, uint32_t(std::max(1, samples)), sample, rays);
        if (tile_done) tile_done(rays);
    });
}

RenderDone render_samples(const Prepared& prepared, film::Film& film, const RenderBudget& budget,
                          const std::string& integrator, Progress& progress, const SampleFn& sample,
                          const std::function<void(std::string& payload)>& payload) {
    SamplePasses passes(prepared, film, budget, integrator, progress, payload);
    while (passes.next()) {
        tbb::parallel_for(size_t(0), passes.tiles().size(), [&](size_t t) {
            const auto [first, last] = passes.range(t);
            if (first == last || passes.stopped()) return;  // done, or abandoned on an interrupt
            RayCounts rays;
            render_tile_samples(prepared, passes.tiles()[t], first, last, sample, rays);
            passes.tile_done(t, rays);
        });
        passes.after_pass();
    }
    return passes.finish();
}

RenderDone render_pixels(const Prepared& prepared, film::Film& film, const RenderBudget& budget,
                         const std::string& integrator, Progress& progress, const RadianceFn& radiance) {
    return render_samples(prepared, film, budget, integrator, progress,
                          [&](int x, int y, const Ray& ray, float weight, Sampler& sampler, RayCounts& rays) {
                              // Weight 0 (a ray the lenses blocked) is a black sample, not traced.
                              film.add_sample(
                                  x, y, weight != 0 ? radiance(ray, sampler, rays) * weight : Rgb(0.0f));
                          });
}

RenderDone render_layers(const Prepared& prepared, film::Film& film, const RenderBudget& budget,
                         const std::string& integrator, Progress& progress,
                         const std::vector<Component>& layers, const PartsFn& parts,
                         const std::function<void(std::string& payload)>& payload) {
    // Layers are created before the parallel loop (creation is not thread-safe).
    std::vector<std::pair<film::Layer*, Component>> out;
    for (const Component c : layers) out.emplace_back(&film.layer(component_name(c)), c);
    return render_samples(
        prepared, film, budget, integrator, progress,
        [&](int x, int y, const Ray& ray, float weight, Sampler& sampler, RayCounts& rays) {
            RadianceParts p;
            film.add_sample(x, y, weight != 0 ? parts(ray, sampler, rays, p) * weight : Rgb(0.0f));
            for (const auto& [layer, part] : out) layer->add(x, y, p[part] * weight);
        },
        payload);
}

RenderDone render_paths(const Prepared& prepared, film::Film& film, const RenderBudget& budget,
                        const std::string& integrator, Progress& progress,
                        const std::vector<Component>& layers, const PathFn& radiance) {
    const RadianceFn plain = [&](const Ray& ray, Sampler& sampler, RayCounts& rays) {
        return radiance(ray, sampler, rays, nullptr);
    };
    const RenderDone done =
        prepared.options.layers
            ? render_layers(prepared, film, budget, integrator, progress, layers,
                            [&](const Ray& ray, Sampler& sampler, RayCounts& rays, RadianceParts& parts) {
                                return radiance(ray, sampler, rays, &parts);
                            })
            : render_pixels(prepared, film, budget, integrator, progress, plain);
    trace_pixel_samples(prepared, film, plain);  // --trace-pixel
    return done;
}

}  // namespace phos::render
