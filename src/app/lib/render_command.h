// `phos render`: the function that runs a render from its options (render_options.h).
#pragma once

#include <string>

#include "app/lib/render_options.h"

namespace phos::app {

// Where layer `layer` of `output` is written: out.png -> out.caustic.png.
std::string layer_path(const std::string& output, const std::string& layer);

// Runs the render; throws ParseError / InputError for bad input. Returns the exit status: 0, or
// 128 + the signal (130 SIGINT, 143 SIGTERM) when an interrupt stopped it (the image so far, and
// the checkpoint with --checkpoint, are written first).
int run_render(const RenderCommand& cmd);

}  // namespace phos::app
