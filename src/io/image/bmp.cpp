// BMP writer: uncompressed 24-bit BGR, rows bottom to top, each padded to 4 bytes, behind the
// 14-byte file header and 40-byte BITMAPINFOHEADER. BMP reading goes through stb_image.cpp.
#include <algorithm>
#include <cerrno>
#include <cstdint>
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

void put16(std::vector<uint8_t>& out, uint32_t v) {
    out.push_back(uint8_t(v));
    out.push_back(uint8_t(v >> 8));
}
void put32(std::vector<uint8_t>& out, uint32_t v) {
    put16(out, v & 0xffff);
    put16(out, v >> 16);
}

uint32_t get32(const uint8_t* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

}  // namespace

std::string bmp_truncation(std::span<const unsigned char> bytes) {
    uint8_t h[34] = {};
    const size_t got = std::min(bytes.size(), sizeof h);
    if (got > 0) std::memcpy(h, bytes.data(), got);
    const int64_t size = int64_t(bytes.size());
    if (got < 2 || h[0] != 'B' || h[1] != 'M') return "";  // not a BMP
    // stb reads a header the file lacks as zeros (uncompressed pixels of whatever size the bytes
    // that are there claim), so the file must hold its whole header first.
    const uint32_t header_size = got >= 18 ? get32(h + 14) : 0;
    if (got < 18 || size < 14 + int64_t(header_size))
        return "truncated BMP header (" + std::to_string(size) + " bytes)";
    // Only the headers stb reads have a size we can predict: BITMAPCOREHEADER (12 bytes, 16-bit
    // sizes, no compression) and BITMAPINFOHEADER or later (40 bytes and more). Of the latter, only
    // uncompressed (BI_RGB) and bit-field pixels; RLE data (1, 2) is left to stb, which refuses it.
    // Other compression codes (JPEG, PNG, CMYK, or none at all) are refused here: stb reads them as
    // uncompressed pixels without checking the size, row by row, however many rows the header claims.
    const uint32_t offset = get32(h + 10);
    int64_t width = 0, height = 0, bpp = 0;
    if (header_size == 12) {
        width = h[18] | h[19] << 8, height = h[20] | h[21] << 8, bpp = h[24] | h[25] << 8;
    } else if (header_size >= 40) {
        const uint32_t compression = get32(h + 30);
        if (compression == 1 || compression == 2) return "";
        if (compression != 0 && compression != 3)
            return "unsupported BMP compression " + std::to_string(compression);
        width = int32_t(get32(h + 18)), height = int32_t(get32(h + 22)), bpp = uint16_t(h[28] | h[29] << 8);
    } else {
        return "";  // a header type stb refuses
    }
    if (width <= 0 || height == 0 || bpp <= 0 || bpp > 32) return "";
    const int64_t row = ((width * bpp + 31) / 32) * 4, rows = height < 0 ? -height : height;
    // row < 2^36 and rows <= 2^31: their product may not fit in 64 bits, and then no file is long enough.
    if (rows > (INT64_MAX - int64_t(offset)) / row)
        return "truncated BMP (" + std::to_string(size) + " bytes; its header asks for more than 2^63)";
    const int64_t needed = int64_t(offset) + row * rows;
    if (size < needed)
        return "truncated BMP (" + std::to_string(size) + " of " + std::to_string(needed) + " bytes)";
    return "";
}

void write_bmp(const std::string& path, const Image& image, const ImageWriteOptions& options) {
    const size_t row_bytes = (size_t(image.width) * 3 + 3) & ~size_t(3);
    const size_t pixel_bytes = row_bytes * size_t(image.height);
    const size_t file_bytes = 54 + pixel_bytes;
    if (file_bytes > 0x7fffffffu) throw InputError("image too large for BMP");

    const std::vector<uint8_t> rgb = to_srgb8(image, options.exposure);
    std::vector<uint8_t> out;
    out.reserve(file_bytes);
    // File header: magic, file size, two reserved words, offset of the pixel data.
    out.push_back('B');
    out.push_back('M');
    put32(out, uint32_t(file_bytes));
    put32(out, 0);
    put32(out, 54);
    // BITMAPINFOHEADER: positive height = bottom-up rows; 1 plane, 24 bpp, BI_RGB (no compression),
    // 2835 pixels per metre (72 dpi), no palette.
    put32(out, 40);
    put32(out, uint32_t(image.width));
    put32(out, uint32_t(image.height));
    put16(out, 1);
    put16(out, 24);
    put32(out, 0);
    put32(out, uint32_t(pixel_bytes));
    put32(out, 2835);
    put32(out, 2835);
    put32(out, 0);
    put32(out, 0);
    for (int y = image.height - 1; y >= 0; --y) {
        const uint8_t* src = rgb.data() + size_t(y) * size_t(image.width) * 3;
        for (int x = 0; x < image.width; ++x) {
            out.push_back(src[3 * x + 2]);
            out.push_back(src[3 * x + 1]);
            out.push_back(src[3 * x + 0]);
        }
        for (size_t pad = size_t(image.width) * 3; pad < row_bytes; ++pad) out.push_back(0);
    }

    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
    if (!f) throw InputError(std::strerror(errno));
    if (std::fwrite(out.data(), 1, out.size(), f.get()) != out.size())
        throw InputError(std::string("write failed: ") + std::strerror(errno));
    if (std::fclose(f.release()) != 0) throw InputError(std::string("write failed: ") + std::strerror(errno));
}

}  // namespace phos::io::detail
