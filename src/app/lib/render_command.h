// `phos render`: the function that runs a render from its options (render_options.h).
#pragma once

#include <string>

#include "app/lib/render_options.h"

namespace phos::app {

// Where layer `layer` of `output` is written: out.png -> out.caustic.png.
std::string layer_path(const std::string& output, const std::string& layer);

// Runs the render; throws ParseError / InputError for bad input.
void run_render(const RenderCommand& cmd);

}  // namespace phos::app
