// OpenEXR: written as 32-bit float R, G, B (ZIP compressed, lossless); read from any scanline or
// tiled file holding R/G/B (missing ones read as 0) or only Y (grey), half or float, through the
// general FrameBuffer API, which converts to float and handles a data window not at the origin.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/image/formats.h"

namespace phos::io::detail {

static_assert(sizeof(Rgb) == 3 * sizeof(float), "Rgb must be three packed floats for the EXR frame buffer");

void write_exr(const std::string& path, const Image& image) {
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(path.c_str(), header);
        Imf::FrameBuffer fb;
        // OpenEXR only reads through these pointers when writing.
        char* base = reinterpret_cast<char*>(const_cast<Rgb*>(image.pixels.data()));
        const size_t xs = sizeof(Rgb), ys = sizeof(Rgb) * size_t(image.width);
        fb.insert("R", Imf::Slice(Imf::FLOAT, base, xs, ys));
        fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
        fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
        file.setFrameBuffer(fb);
        file.writePixels(image.height);
    } catch (const std::exception& e) {
        throw InputError(std::string("OpenEXR: ") + e.what());
    }
}

namespace {

// The data windows read_exr accepts: sides up to 2^24, at most 2^31 pixels, and (when the file's
// size is known) no more pixels than check_pixel_count allows for it.
void check_data_window(const std::string& path, long long w, long long h, const uintmax_t* file_bytes) {
    if (w <= 0 || h <= 0 || w > (1 << 24) || h > (1 << 24) || w * h > (1ll << 31))
        throw_read_error(path, "unsupported EXR data window size");
    if (file_bytes) check_pixel_count(path, w, h, *file_bytes);
}

// OpenEXR trusts a header's sizes before it reads any pixel, so they are checked against the file
// first, from the bytes alone:
//  - it allocates (and clears) an attribute's claimed size before it notices that the file is
//    shorter: a 369-byte file whose string attribute claims 846 MB takes 0.6 s, and times out under
//    the address sanitizer (the image fuzzer's finding);
//  - opening a scanline file allocates line buffers for a block of lines (up to 32) of the data
//    window's width, and a tiled one buffers of its tile size: a 148-byte file whose data window is
//    33.5 M pixels wide asks for 2.2 GB (another of the fuzzer's findings). So each part's data window is
//    held to what read_exr accepts (check_data_window), and its
//    buffers (width x 32 lines, or a tile, times the channels' bytes per pixel) to the bytes of an
//    image of the plausible pixel count at 16 bytes per pixel.
// The layout (openexr.com, "OpenEXR File Layout"): magic 76 2f 31 01, a 4-byte version with flags
// (0x1000: multi-part, each part's header ending with a null byte and the list with an empty
// header), then attributes: name and type as null-terminated strings, a little-endian int32 size,
// the value. Anything else odd is left to OpenEXR's own checks.
void check_exr_header(const std::string& path, uintmax_t file_bytes) {
    std::ifstream in(path, std::ios::binary);
    unsigned char head[8];
    if (!in.read(reinterpret_cast<char*>(head), 8)) return;
    if (head[0] != 0x76 || head[1] != 0x2f || head[2] != 0x31 || head[3] != 0x01) return;
    const bool multipart = (head[5] & 0x10) != 0;
    uintmax_t pos = 8;
    const auto read_string = [&](std::string& out) {
        out.clear();
        for (char c; in.get(c);) {
            ++pos;
            if (c == 0) return true;
            if (out.size() >= 255) return false;
            out += c;
        }
        return false;
    };
    const auto le32 = [](const std::string& v, size_t at) {
        return int32_t(uint32_t(uint8_t(v[at])) | uint32_t(uint8_t(v[at + 1])) << 8 |
                       uint32_t(uint8_t(v[at + 2])) << 16 | uint32_t(uint8_t(v[at + 3])) << 24);
    };
    std::string name, type, value;
    for (int headers = 0; headers < 1 << 16; ++headers) {
        int attributes = 0;
        long long w = 0, h = 0, tile_w = 0, tile_h = 0, pixel_bytes = 0;
        for (;; ++attributes) {
            if (!read_string(name)) return;
            if (name.empty()) break;  // end of this header
            if (!read_string(type)) return;
            unsigned char b[4];
            if (!in.read(reinterpret_cast<char*>(b), 4)) return;
            pos += 4;
            const int32_t size =
                int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24);
            if (size < 0 || uintmax_t(size) > file_bytes - std::min(pos, file_bytes))
                throw_read_error(path, "EXR attribute '" + name + "' (" + type + ") claims " +
                                           std::to_string(size) + " bytes, more than the " +
                                           std::to_string(file_bytes - std::min(pos, file_bytes)) +
                                           " left in the file");
            value.resize(size_t(size));
            if (!in.read(value.data(), size)) return;
            pos += uintmax_t(size);
            if (name == "dataWindow" && type == "box2i" && size == 16) {
                w = (long long)le32(value, 8) - le32(value, 0) + 1;
                h = (long long)le32(value, 12) - le32(value, 4) + 1;
            } else if (name == "tiles" && type == "tiledesc" && size >= 8) {
                tile_w = uint32_t(le32(value, 0)), tile_h = uint32_t(le32(value, 4));
            } else if (name == "channels" && type == "chlist") {
                // name, int32 pixel type (0 uint, 1 half, 2 float), 4 bytes, 2 int32 samplings.
                for (size_t at = 0; at < value.size() && value[at] != 0;) {
                    const size_t end = value.find('\0', at);
                    if (end == std::string::npos || end + 17 > value.size()) break;
                    pixel_bytes += le32(value, end + 1) == 1 ? 2 : 4;
                    at = end + 17;
                }
            }
        }
        if (attributes == 0) return;  // the empty header that ends a multi-part file's list
        check_data_window(path, w, h, &file_bytes);
        // One buffer's pixels: a tile, or a block of up to 32 full lines.
        const long double buffer = tile_w > 0 ? (long double)tile_w * (long double)tile_h
                                              : (long double)w * (long double)std::min(h, 32ll);
        if (buffer * (long double)std::max(pixel_bytes, 1ll) >
            (long double)file_bytes * (long double)kMaxPixelsPerByte * 16.0L)
            throw_read_error(path, "its header asks for " + std::to_string((unsigned long long)(buffer)) +
                                       "-pixel buffers of " + std::to_string(pixel_bytes) +
                                       " bytes per pixel, implausibly large for a file of " +
                                       std::to_string(file_bytes) + " bytes (corrupt header?)");
        if (!multipart) return;
    }
}

}  // namespace

Image read_exr(const std::string& path) {
    try {
        std::error_code size_error;
        const auto file_bytes = std::filesystem::file_size(path, size_error);
        if (!size_error) check_exr_header(path, file_bytes);
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const long long w = (long long)dw.max.x - dw.min.x + 1, h = (long long)dw.max.y - dw.min.y + 1;
        check_data_window(path, w, h, size_error ? nullptr : &file_bytes);
        const Imf::ChannelList& channels = file.header().channels();
        const bool has_rgb =
            channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
        const bool has_y = channels.findChannel("Y") != nullptr;
        if (!has_rgb && !has_y) throw_read_error(path, "EXR has no R, G, B or Y channel");

        Image image(static_cast<int>(w), static_cast<int>(h));
        char* base = reinterpret_cast<char*>(image.pixels.data());
        const size_t xs = sizeof(Rgb), ys = sizeof(Rgb) * size_t(w);
        Imf::FrameBuffer fb;
        // Slice::Make offsets the pointer by the data window origin so pixel (min.x, min.y) lands at
        // our (0, 0); absent channels are filled with 0.
        const char* names[3] = {"R", "G", "B"};
        for (int c = 0; c < 3; ++c) {
            const char* name = has_rgb ? names[c] : "Y";
            if (!has_rgb && c > 0) continue;  // grey: read Y into R, copy below
            fb.insert(name, Imf::Slice::Make(Imf::FLOAT, base + size_t(c) * sizeof(float), dw, xs, ys));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (!has_rgb)
            for (Rgb& p : image.pixels) p = Rgb(p.r);
        return image;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw_read_error(path, std::string("OpenEXR: ") + e.what());
    }
}

}  // namespace phos::io::detail
