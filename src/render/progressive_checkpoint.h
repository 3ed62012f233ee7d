// The saved state of a render, for every integrator: for the progressive photon mappers (PPM /
// SPPM) per-hit-point statistics (PixelStats; their equations are in
// integrators/sppm_pixel_stats.h) and iteration and photon counts; for the
// sample-based ones (whitted, path, photonmap) the film's sums and the samples taken per tile; and
// what the render was made from (scene hash, image-changing options by name and value), so
// `phos render --resume` can continue it bit for bit or say exactly why it cannot. Binary format
// with a magic, a version and a checksum; written atomically.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace phos::render {

// The options that change the image, as (flag, value) pairs in a fixed order, e.g.
// {{"--alpha", "0.7"}, {"--max-depth", "16"}}: filled by the application from its option tables.
using OptionValues = std::vector<std::pair<std::string, std::string>>;

// Statistics of one hit-point slot of progressive photon mapping (SPPM: one per pixel; PPM: one
// per pixel and eye sample). Plain doubles: saved bit for bit.
struct PixelStats {
    double n = 0;                  // accumulated photon count N (fractional after α-reduction)
    double r2 = 0;                 // squared radius R² (0 = not yet initialised)
    double tau[3] = {0, 0, 0};     // accumulated, radius-reduced flux τ (unnormalised)
    double direct[3] = {0, 0, 0};  // sum over iterations of direct light + emission seen
};

struct ProgressiveState {
    static constexpr uint32_t kVersion = 4;

    // What the render was made from: refused on resume when any differs.
    std::string integrator;  // "ppm", "sppm", "path", ...
    uint32_t width = 0, height = 0;
    uint32_t slots_per_pixel = 1;  // progressive statistics per pixel (0: a sample-based render)
    uint64_t seed = 0;
    uint64_t scene_hash = 0;  // hash of the scene file's bytes
    OptionValues options;     // the image-changing options, by flag
    // hash_options(options), set by the integrator when it starts (start_state); a caller that
    // sets only the hash and no list is compared by hash alone.
    uint64_t options_hash = 0;

    // Progress.
    uint64_t iterations = 0;         // completed iterations (samples per pixel in every pixel)
    uint64_t photons_emitted = 0;    // total photons emitted over those iterations
    uint64_t target_iterations = 0;  // what the interrupted run was asked for (for a bare --resume)
    uint64_t rejected_samples = 0;   // NaN / infinite samples dropped so far (for -v)

    // The `phos render` arguments that started the render (scene path made absolute, without
    // --resume), so a bare `phos render --resume FILE` can continue it.
    std::vector<std::string> command_line;

    std::vector<PixelStats> slots;  // width * height * slots_per_pixel, row-major

    // Sample-based integrators: samples per pixel taken in each tile (film::make_tiles order), and
    // the film's sums (film::Layer::sums: r, g, b, weight per pixel) by layer name, "" the image.
    std::vector<uint32_t> tile_samples;
    std::vector<std::pair<std::string, std::vector<double>>> film;
    // The integrator's own data, opaque here: the photon mapper stores its maps (photon_map.cpp),
    // so a resume need not trace them again.
    std::string payload;
};

// Writes `state` to `path` atomically (temporary file + rename). Throws InputError on I/O failure.
void save_checkpoint(const std::string& path, const ProgressiveState& state);
// Reads a checkpoint. Throws InputError("checkpoint 'path': ...") if the file is missing, not a
// phos checkpoint, of another version, truncated, or fails its checksum.
ProgressiveState load_checkpoint(const std::string& path);
// Serialised bytes of `state` (the file's exact content) and the inverse; `what` names the source
// in error messages. Exposed for tests.
std::string encode_checkpoint(const ProgressiveState& state);
ProgressiveState decode_checkpoint(const std::string& bytes, const std::string& what);

// 64-bit FNV-1a-style hash over bytes, then mixed: used for the scene hash and the checksum.
uint64_t hash_bytes(const void* data, size_t size, uint64_t seed = 0);
// Hash of an option list ("flag=value\n" per option, in order).
uint64_t hash_options(const OptionValues& options);

// Throws InputError naming every field of `saved` that differs from `expected`: integrator, image
// size, hit points per pixel, seed, scene contents, and each image-changing option with both
// values ("option --alpha differs: checkpoint 0.7, now 0.5"). A checkpoint of another render
// cannot be resumed.
void check_resumable(const ProgressiveState& saved, const ProgressiveState& expected,
                     const std::string& path);

}  // namespace phos::render
