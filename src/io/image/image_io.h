// Reading and writing images, format chosen by file extension. Writers go through a temporary file
// renamed into place, so an interrupted or failed write never leaves a truncated or clobbered file.
#pragma once

#include <string>

#include "core/image.h"

namespace phos::io {

struct ImageWriteOptions {
    float exposure = 0.0f;  // stops; 8-bit outputs (PNG, BMP) are scaled by 2^exposure then sRGB-encoded
};

// Writes `image` (linear RGB radiance) to `path`: .exr (float RGB), .pfm (linear), .png and .bmp
// (sRGB-encoded 8-bit). Throws InputError on an unknown extension or any I/O failure.
void write_image(const std::string& path, const Image& image, const ImageWriteOptions& options = {});
// True if `path`'s extension names a format write_image supports.
bool is_writable_image_path(const std::string& path);

// Reads an image as linear RGB: .exr and .pfm as stored (linear); .png/.jpg/.jpeg/.tga/.bmp decoded
// from sRGB when `srgb` (colour data) or kept as-is when not (data maps); .hdr linear.
// Throws InputError (with the file name) when the file is missing or malformed.
Image read_image(const std::string& path, bool srgb = true);

}  // namespace phos::io
