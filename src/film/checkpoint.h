// The saved state of a progressive photon-mapping render (PPM / SPPM): per-hit-point statistics
// (photon count N, radius², flux τ, direct-light sums), iteration and photon counts, and what the
// render was made from, so `phos render --resume` can continue it bit for bit. Binary format with
// a magic, a version and a checksum; written atomically.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace phos::film {

// Statistics of one hit-point slot (SPPM: one per pixel; PPM: one per pixel and eye sample).
struct SlotStats {
    double n = 0;                  // accumulated photon count N_i (fractional after α-reduction)
    double r2 = 0;                 // squared radius R_i² (0 = not yet initialised)
    double tau[3] = {0, 0, 0};     // accumulated, radius-reduced flux τ_i (unnormalised)
    double direct[3] = {0, 0, 0};  // sum over iterations of direct light + emission seen
};

struct ProgressiveState {
    static constexpr uint32_t kVersion = 2;

    // What the render was made from: refused on resume when any differs.
    std::string integrator;  // "ppm" or "sppm"
    uint32_t width = 0, height = 0;
    uint32_t slots_per_pixel = 1;
    uint64_t seed = 0;
    uint64_t scene_hash = 0;    // hash of the scene file's bytes
    uint64_t options_hash = 0;  // hash of the options that change the image

    // Progress.
    uint64_t iterations = 0;         // completed iterations
    uint64_t photons_emitted = 0;    // total photons emitted over those iterations
    uint64_t target_iterations = 0;  // what the interrupted run was asked for (for a bare --resume)

    // The `phos render` arguments that started the render (scene path made absolute, without
    // --resume), so a bare `phos render --resume FILE` can continue it.
    std::vector<std::string> command_line;

    std::vector<SlotStats> slots;  // width * height * slots_per_pixel, row-major
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

// Throws InputError naming every field of `saved` that differs from `expected` (integrator, image
// size, slots, seed, scene hash, options hash): a checkpoint of another render cannot be resumed.
void check_resumable(const ProgressiveState& saved, const ProgressiveState& expected,
                     const std::string& path);

}  // namespace phos::film
