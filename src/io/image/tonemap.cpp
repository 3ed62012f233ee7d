// Exposure scaling and the sRGB OETF / inverse OETF (see tonemap.h).
#include "io/image/tonemap.h"

#include <array>
#include <cmath>

namespace phos::io {

float exposure_scale(float stops) { return std::exp2(stops); }

float linear_to_srgb(float linear) {
    if (!(linear > 0.0f)) return 0.0f;  // also catches NaN
    if (linear >= 1.0f) return 1.0f;
    // Evaluate in double so the 8-bit rounding below is not disturbed by float pow error.
    const double x = linear;
    if (x <= 0.0031308) return float(12.92 * x);
    return float(1.055 * std::pow(x, 1.0 / 2.4) - 0.055);
}

float srgb_to_linear(float encoded) {
    if (!(encoded > 0.0f)) return 0.0f;
    if (encoded >= 1.0f) return 1.0f;
    const double c = encoded;
    if (c <= 0.04045) return float(c / 12.92);
    return float(std::pow((c + 0.055) / 1.055, 2.4));
}

uint8_t linear_to_srgb8(float linear) {
    // linear_to_srgb already clamps to [0, 1] and maps NaN to 0, so the product is in [0, 255].
    return uint8_t(std::lround(double(linear_to_srgb(linear)) * 255.0));
}

float srgb8_to_linear(uint8_t code) {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[size_t(i)] = srgb_to_linear(float(i) / 255.0f);
        return t;
    }();
    return table[code];
}

std::vector<uint8_t> to_srgb8(const Image& image, float exposure_stops) {
    const float scale = exposure_scale(exposure_stops);
    std::vector<uint8_t> out(image.pixels.size() * 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const Rgb c = image.pixels[i] * scale;
        out[3 * i + 0] = linear_to_srgb8(c.r);
        out[3 * i + 1] = linear_to_srgb8(c.g);
        out[3 * i + 2] = linear_to_srgb8(c.b);
    }
    return out;
}

}  // namespace phos::io
