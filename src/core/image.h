// A linear-RGB float image: what the film produces, what image readers return and writers take.
#pragma once

#include <vector>

#include "core/vec.h"

namespace phos {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<Rgb> pixels;  // row-major, row 0 at the top

    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h)) {}
    Rgb& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
    const Rgb& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

}  // namespace phos
