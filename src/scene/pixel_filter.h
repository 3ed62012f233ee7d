// The pixel reconstruction filter as plain data: which filter, its radius in pixels and its shape
// parameters, with pbrt-v4's defaults. The box of radius 1/2 (each sample counts for the pixel it
// was taken in) is phos's default; render/pixel_filter.h samples and evaluates the others.
#pragma once

#include "core/vec.h"

namespace phos::scene {

struct PixelFilter {
    enum class Kind {
        Box,       // 1 inside the radius
        Gaussian,  // per axis: max(0, G(x, sigma) - G(radius, sigma))
        Mitchell,  // per axis: Mitchell & Netravali 1988's cubic with B, C, stretched to the radius
        Lanczos,   // per axis: sinc(x) sinc(x / tau) inside the radius
        Triangle,  // per axis: max(0, radius - |x|)
    };
    Kind kind = Kind::Box;
    Vec2 radius{0.5f, 0.5f};                 // half-width in pixels along x and y
    float sigma = 0.5f;                      // Gaussian standard deviation, pixels
    float b = 1.0f / 3.0f, c = 1.0f / 3.0f;  // Mitchell
    float tau = 3.0f;                        // Lanczos: lobes of the windowing sinc

    // pbrt-v4's default radius of each filter.
    static Vec2 default_radius(Kind kind) {
        switch (kind) {
            case Kind::Box:
                return {0.5f, 0.5f};
            case Kind::Gaussian:
                return {1.5f, 1.5f};
            case Kind::Mitchell:
                return {2.0f, 2.0f};
            case Kind::Lanczos:
                return {4.0f, 4.0f};
            case Kind::Triangle:
                return {2.0f, 2.0f};
        }
        return {0.5f, 0.5f};
    }
    // Each sample counts only for the pixel it was taken in (the box of radius 1/2).
    bool is_pixel_box() const { return kind == Kind::Box && radius.x == 0.5f && radius.y == 0.5f; }
};

}  // namespace phos::scene
