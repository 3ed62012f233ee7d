// glReadPixels of the back buffer (see framebuffer.h).
#include "display/framebuffer.h"

#include <cstdint>
#include <vector>

#include "io/image/tonemap.h"

#ifdef PHOS_HAS_GLFW
#include <GLFW/glfw3.h>

namespace phos::display {

Image read_framebuffer(int width, int height) {
    std::vector<uint8_t> rgb(size_t(width) * size_t(height) * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    Image img(width, height);
    for (int y = 0; y < height; ++y)  // GL rows are bottom first
        for (int x = 0; x < width; ++x) {
            const uint8_t* p = &rgb[(size_t(height - 1 - y) * size_t(width) + size_t(x)) * 3];
            img.at(x, y) =
                Rgb(io::srgb8_to_linear(p[0]), io::srgb8_to_linear(p[1]), io::srgb8_to_linear(p[2]));
        }
    return img;
}

}  // namespace phos::display
#endif
