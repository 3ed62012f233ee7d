// The seed renderer's single-dash flags (`-md 8`, `-gf cone 1.1`, `-no_rs`...) that have no phos
// spelling: each is rewritten to the phos option with the same effect, or consumed with one warning
// saying why it has no effect in a physically based renderer. docs/usage.md lists them all.
#pragma once

#include <string>
#include <vector>

namespace phos::app {

struct SeedFlagResult {
    std::vector<std::string> args;      // the command line with seed flags translated
    std::vector<std::string> warnings;  // one per seed flag that has no effect
};

// Translates the seed flags in `args` (arguments after the program name). Flags phos already
// spells the same way after its single-dash normalisation (-resolution, -v, -global...) pass through.
// A seed flag missing its value is left as it is, so the parser reports it.
SeedFlagResult translate_seed_flags(const std::vector<std::string>& args);

// The seed's `photonmap in.scn -flags... out.png`: when `args` is `render SCENE -flags... IMAGE` and
// IMAGE (an image file name) is not the value of -o, it moves right after the scene, where the
// render command takes its positional output (an option taking several values would swallow it).
void move_trailing_output(std::vector<std::string>& args);

}  // namespace phos::app
