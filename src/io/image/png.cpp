// PNG writer through libpng: 8-bit sRGB RGB with an sRGB chunk. PNG reading goes through
// stb_image.cpp. libpng reports errors by longjmp, so the libpng calls live in one function whose
// locals are all trivially destructible; the C++ side turns its result into an exception.
#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/image/formats.h"
#include "io/image/tonemap.h"

namespace phos::io::detail {
namespace {

struct PngError {
    char message[256] = "unknown libpng error";
};

void on_error(png_structp png, png_const_charp msg) {
    auto* err = static_cast<PngError*>(png_get_error_ptr(png));
    std::snprintf(err->message, sizeof err->message, "libpng: %s", msg);
    png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // warnings do not stop the write

// Writes the whole image; false (with `err` filled in) on any libpng failure.
bool write_png_rows(FILE* f, int width, int height, png_bytep* rows, PngError* err) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, err, on_error, on_warning);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

void write_png(const std::string& path, const Image& image, const ImageWriteOptions& options) {
    std::vector<uint8_t> rgb = to_srgb8(image, options.exposure);
    std::vector<png_bytep> rows(size_t(image.height));
    for (int y = 0; y < image.height; ++y) rows[size_t(y)] = rgb.data() + size_t(y) * size_t(image.width) * 3;

    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
    if (!f) throw InputError(std::strerror(errno));
    PngError err;
    if (!write_png_rows(f.get(), image.width, image.height, rows.data(), &err)) throw InputError(err.message);
    if (std::fclose(f.release()) != 0) throw InputError(std::string("write failed: ") + std::strerror(errno));
}

}  // namespace phos::io::detail
