// Per-format readers and writers behind io/image_io.h (one .cpp per format). Internal to io/image,
// but tests use it to reach format-specific options such as greyscale PFM.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/image.h"
#include "io/image/image_io.h"

namespace phos::io::detail {

// Writers write straight to `path` (the caller, write_image, hands them a temporary name) and
// throw InputError (or any std::exception) on failure.
void write_exr(const std::string& path, const Image& image);
// `greyscale` writes a one-channel "Pf" file holding the channel average.
void write_pfm(const std::string& path, const Image& image, bool greyscale = false);
void write_png(const std::string& path, const Image& image, const ImageWriteOptions& options);
void write_bmp(const std::string& path, const Image& image, const ImageWriteOptions& options);

// Readers throw InputError mentioning `path`.
Image read_exr(const std::string& path);
Image read_pfm(const std::string& path);
// PNG, JPEG, TGA, BMP (8 or 16 bit, decoded from sRGB when `srgb`) and Radiance HDR (linear).
Image read_stb(const std::string& path, bool srgb);

// stb_image decodes a truncated uncompressed BMP without complaint (missing rows read as 0); this
// returns a reason when the BMP file `bytes` is shorter than its header promises, else "".
std::string bmp_truncation(std::span<const unsigned char> bytes);

// "cannot read 'path': reason" — the one wording all readers use.
[[noreturn]] void throw_read_error(const std::string& path, const std::string& reason);

// The whole file at `path`, for readers that decode from memory; refuses (throw_read_error) a file
// that cannot be read or holds more than `max_bytes`.
std::vector<unsigned char> read_file_bytes(const std::string& path, size_t max_bytes = SIZE_MAX);

// Refuses (throw_read_error) a header that claims more pixels than a file of `file_bytes` bytes
// can plausibly encode, before anything is allocated for them. The bound, kMaxPixelsPerByte, is
// far above what any compression reaches on real images (a 1-bit PNG of one colour is about 8,000
// pixels per byte), so only corrupt or hostile headers meet it.
// Formats with a tighter bound pass their own: a TGA run-length packet encodes at most 128 pixels
// in 2 bytes or more (kMaxTgaPixelsPerByte).
constexpr unsigned long long kMaxPixelsPerByte = 1ull << 15;
constexpr unsigned long long kMaxTgaPixelsPerByte = 64;
void check_pixel_count(const std::string& path, long long width, long long height,
                       unsigned long long file_bytes, unsigned long long max_per_byte = kMaxPixelsPerByte);

}  // namespace phos::io::detail
