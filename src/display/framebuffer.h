// Reading back what an OpenGL window shows (the preview window's and the photon viewer's
// screenshots): the current context's back buffer as a linear image, top row first.
#pragma once

#include "core/image.h"

namespace phos::display {

// The back buffer of the current OpenGL context, `width` x `height` framebuffer pixels, decoded
// from 8-bit sRGB to linear. Only in builds with the preview window (PHOS_HAS_GLFW).
Image read_framebuffer(int width, int height);

}  // namespace phos::display
