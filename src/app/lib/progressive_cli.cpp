// Command-line options of the progressive integrators (registered on `phos render`).
#include "app/lib/progressive_cli.h"

#include <cmath>
#include <string>

namespace phos::app {
namespace {

// A finite number > 0 (CLI11's PositiveNumber reports its range up to the largest double).
const CLI::Validator kPositive(
    [](std::string& text) -> std::string {
        try {
            size_t used = 0;
            const double v = std::stod(text, &used);
            if (used == text.size() && v > 0 && std::isfinite(v)) return {};
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not a positive number";
    },
    "POSITIVE");

}  // namespace

void add_progressive_options(CLI::App& render, integrators::ProgressiveOptions& o) {
    render
        .add_option("--alpha", o.alpha, "ppm/sppm: fraction of new photons kept per iteration (default 0.7)")
        ->check(CLI::Range(0.01f, 1.0f));
    render
        .add_option("--photons-per-iter", o.photons_per_iter,
                    "ppm/sppm: photons traced per iteration (default 200000)")
        ->check(CLI::Range(uint64_t(1), uint64_t(1) << 32));
    render
        .add_option("--radius", o.radius,
                    "ppm/sppm: initial gather radius in scene units (default: automatic)")
        ->check(kPositive);
    render
        .add_option("--radius-pixels", o.radius_pixels,
                    "ppm/sppm: automatic initial radius in pixel footprints at the hit distance (default 4)")
        ->check(kPositive);
    render
        .add_option(
            "--radius-photons", o.radius_photons,
            "sppm: the first iteration's photons (a pilot, not used in the estimate) set each pixel's "
            "automatic radius so its disc holds about K photons, within 1-8 pixel footprints "
            "(default 64; 0 = off)")
        ->check(CLI::Range(0.0, 1e9));
    render
        .add_option("--direct-samples,--ppm-direct-samples", o.direct_samples,
                    "ppm/sppm: light samples per visible point (default: sppm 4 per iteration, ppm 16)")
        ->check(CLI::Range(1, 65536));
    render.add_option("--ppm-eye-samples", o.eye_samples, "ppm: hit points per pixel (default 1)")
        ->check(CLI::Range(1, 4096));
    render.add_option("--iterations", o.iterations, "ppm/sppm: number of iterations (same as --spp)")
        ->check(CLI::Range(1, 1 << 30));
    render
        .add_option("--time", o.time, "ppm/sppm: stop after the iteration that crosses SECONDS of wall time")
        ->check(kPositive);
    render.add_option("--write-every", o.write_every, "ppm/sppm: write the current image every SECONDS")
        ->check(kPositive);
    render.add_option("--checkpoint", o.checkpoint_path, "ppm/sppm: save the progressive state to FILE");
    render
        .add_option("--checkpoint-every", o.checkpoint_every,
                    "ppm/sppm: iterations between checkpoints (default 8)")
        ->check(CLI::Range(1, 1 << 30));
    render.add_option("--resume", o.resume_path,
                      "ppm/sppm: continue the render saved in checkpoint FILE (same scene and options)");
}

}  // namespace phos::app
