// Front door of io/image: picks the format from the file extension and routes writes through
// atomic_write so a failed write never leaves a partial file.
#include "io/image/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/error.h"
#include "io/image/atomic_write.h"
#include "io/image/formats.h"

namespace phos::io {
namespace {

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

namespace detail {

void throw_read_error(const std::string& path, const std::string& reason) {
    throw InputError("cannot read '" + path + "': " + reason);
}

std::vector<unsigned char> read_file_bytes(const std::string& path, size_t max_bytes) {
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) throw_read_error(path, std::strerror(errno));
    std::vector<unsigned char> bytes;
    unsigned char buf[1 << 16];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, f.get())) > 0;) {
        bytes.insert(bytes.end(), buf, buf + n);
        if (bytes.size() > max_bytes)
            throw_read_error(path,
                             "file too large for its decoder (over " + std::to_string(max_bytes) + " bytes)");
    }
    if (std::ferror(f.get())) throw_read_error(path, std::strerror(errno));
    return bytes;
}

void check_pixel_count(const std::string& path, long long width, long long height,
                       unsigned long long file_bytes, unsigned long long max_per_byte) {
    if (width <= 0 || height <= 0) return;  // the decoder reports those
    // Both factors are below 2^31 wherever this is called, so the product fits.
    const unsigned long long pixels = (unsigned long long)width * (unsigned long long)height;
    if (pixels / max_per_byte > file_bytes)
        throw_read_error(path, "its header claims " + std::to_string(width) + " x " + std::to_string(height) +
                                   " pixels, implausibly many for a file of " + std::to_string(file_bytes) +
                                   " bytes (corrupt header?)");
}

}  // namespace detail

bool is_writable_image_path(const std::string& path) {
    const std::string ext = lower_extension(path);
    return ext == ".exr" || ext == ".pfm" || ext == ".png" || ext == ".bmp";
}

void write_image(const std::string& path, const Image& image, const ImageWriteOptions& options) {
    const std::string ext = lower_extension(path);
    if (!is_writable_image_path(path))
        throw InputError("cannot write '" + path + "': unknown image format '" + ext +
                         "' (expected .exr, .pfm, .png or .bmp)");
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != size_t(image.width) * size_t(image.height))
        throw InputError("cannot write '" + path + "': image is empty or its size is inconsistent");
    atomic_write(path, [&](const std::string& temp) {
        if (ext == ".exr")
            detail::write_exr(temp, image);
        else if (ext == ".pfm")
            detail::write_pfm(temp, image);
        else if (ext == ".png")
            detail::write_png(temp, image, options);
        else
            detail::write_bmp(temp, image, options);
    });
}

Image read_image(const std::string& path, bool srgb) {
    const std::string ext = lower_extension(path);
    const bool known = ext == ".exr" || ext == ".pfm" || ext == ".png" || ext == ".jpg" || ext == ".jpeg" ||
                       ext == ".tga" || ext == ".bmp" || ext == ".hdr";
    if (!known)
        detail::throw_read_error(path, "unknown image format '" + ext +
                                           "' (expected .exr, .pfm, .png, .jpg, .jpeg, .tga, .bmp or .hdr)");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        if (std::filesystem::exists(path, ec)) detail::throw_read_error(path, "not a regular file");
        detail::throw_read_error(path, "no such file");
    }
    if (ext == ".exr") return detail::read_exr(path);
    if (ext == ".pfm") return detail::read_pfm(path);
    return detail::read_stb(path, srgb);
}

}  // namespace phos::io
