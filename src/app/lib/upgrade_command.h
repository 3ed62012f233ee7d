// `phos upgrade IN OUT`: a pbrt-v3 (or pbrt-v4) scene written as one pbrt-v4 file (io/pbrt/
// upgrade_writer.h), as pbrt-v4's `pbrt --upgrade` does.
#pragma once

#include <string>

namespace phos::app {

// Reads `input` (and its includes) and writes its pbrt-v4 form to `output` atomically; nothing is
// written when the input is malformed (ParseError) or `output` is the input (InputError).
void run_upgrade(const std::string& input, const std::string& output);

}  // namespace phos::app
