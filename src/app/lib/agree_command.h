// `phos agree SCENE`: renders the scene with every integrator that claims it at equal time (two
// seeds each) and with the reference integrator at a multiple of that time, compares every 8 x 8
// block's mean (app/lib/agreement.h), prints the table and the blocks that disagree; exit status 0
// when all agree, 1 when any disagrees, 2 for bad input.
#pragma once

#include <cstdint>
#include <string>

#include "app/lib/render_options.h"

namespace phos::app {

struct AgreeCommand {
    std::string scene_path;
    double time = 5;          // --time: seconds per integrator and seed
    std::string integrators;  // --integrators a,b,...: empty: every integrator that claims the scene
    std::string reference;    // --reference NAME: empty: integrators::agreement_reference
    int block = 8;            // --block N
    uint64_t seed = 0;        // --seed S: tested seeds S, S + 1; the reference's S + 2, S + 3
    // The options `phos render` takes that shape the image, under the same names (--width and
    // --height in settings.render, marked given), and --threads, -q, --strict, --quality.
    RenderCommand settings;
};

// The reference renders this many times as long as each tested integrator.
inline constexpr double kReferenceTimeFactor = 4;
// Without --width/--height, the scene's image size is scaled down to at most this many pixels on
// its longer side.
inline constexpr int kAgreeMaxSize = 128;

// Adds the `agree` subcommand to `app`, filling `cmd` when parsed.
CLI::App* add_agree_command(CLI::App& app, AgreeCommand& cmd, RegisterTable register_table);

// Runs it; throws ParseError / InputError for bad input. Returns 0 when every integrator agrees
// with the reference, 1 when any does not.
int run_agree(const AgreeCommand& cmd);

}  // namespace phos::app
