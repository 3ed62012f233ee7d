// The one translation unit that compiles stb_image (PNG, JPEG, TGA, BMP, Radiance HDR decoding),
// and the reader built on it. stb returns null with a reason on bad data; we turn that into
// InputError. Alpha is dropped; grey is replicated to RGB.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_PSD
#define STBI_NO_GIF
#define STBI_NO_PIC
#define STBI_NO_PNM
#define STBI_FAILURE_USERMSG
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "core/error.h"
#include "io/image/formats.h"
#include "io/image/tonemap.h"

namespace phos::io::detail {
namespace {

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

std::string stb_reason() {
    const char* r = stbi_failure_reason();
    return r ? std::string(r) : std::string("unknown decoding error");
}

}  // namespace

Image read_stb(const std::string& path, bool srgb) {
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) throw_read_error(path, std::strerror(errno));
    if (const std::string reason = bmp_truncation(f.get()); !reason.empty()) throw_read_error(path, reason);
    int w = 0, h = 0, n = 0;
    Image image;

    if (stbi_is_hdr_from_file(f.get())) {
        // Radiance HDR holds linear floats already; stb would not alter them for .hdr input.
        std::unique_ptr<float, StbFree> data(stbi_loadf_from_file(f.get(), &w, &h, &n, 3));
        if (!data || w <= 0 || h <= 0) throw_read_error(path, stb_reason());
        image = Image(w, h);
        for (size_t i = 0; i < image.pixels.size(); ++i)
            image.pixels[i] = Rgb(data.get()[3 * i], data.get()[3 * i + 1], data.get()[3 * i + 2]);
        return image;
    }

    if (stbi_is_16_bit_from_file(f.get())) {
        std::unique_ptr<stbi_us, StbFree> data(stbi_load_from_file_16(f.get(), &w, &h, &n, 3));
        if (!data || w <= 0 || h <= 0) throw_read_error(path, stb_reason());
        image = Image(w, h);
        for (size_t i = 0; i < image.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const float v = float(data.get()[3 * i + size_t(c)]) / 65535.0f;
                image.pixels[i][c] = srgb ? srgb_to_linear(v) : v;
            }
        return image;
    }

    // Plain 8-bit load: stbi_loadf would apply its own gamma 2.2 guess instead of the sRGB curve.
    std::unique_ptr<stbi_uc, StbFree> data(stbi_load_from_file(f.get(), &w, &h, &n, 3));
    if (!data || w <= 0 || h <= 0) throw_read_error(path, stb_reason());
    image = Image(w, h);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const uint8_t v = data.get()[3 * i + size_t(c)];
            image.pixels[i][c] = srgb ? srgb8_to_linear(v) : float(v) / 255.0f;
        }
    return image;
}

}  // namespace phos::io::detail
