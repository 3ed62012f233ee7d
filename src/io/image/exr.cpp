// OpenEXR: written as 32-bit float R, G, B (ZIP compressed, lossless); read from any scanline or
// tiled file holding R/G/B (missing ones read as 0) or only Y (grey), half or float, through the
// general FrameBuffer API, which converts to float and handles a data window not at the origin.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

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

// OpenEXR allocates (and clears) an attribute's claimed size before it notices that the file is
// shorter: a 369-byte file whose string attribute claims 846 MB took 0.6 s, and timed out under
// the address sanitizer (the image fuzzer's finding). So the header's attribute sizes are checked
// against the bytes that follow them first. The layout (openexr.com, "OpenEXR File Layout"): magic
// 76 2f 31 01, a 4-byte version with flags (0x1000: multi-part, each part's header ending with a
// null byte and the list with an empty header), then attributes: name and type as null-terminated
// strings, a little-endian int32 size, the value. Anything else odd is left to OpenEXR's own checks.
void check_exr_attribute_sizes(const std::string& path, uintmax_t file_bytes) {
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
    std::string name, type;
    for (int headers = 0; headers < 1 << 16; ++headers) {
        int attributes = 0;
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
            in.seekg(std::streamoff(size), std::ios::cur);
            pos += uintmax_t(size);
        }
        if (!multipart || attributes == 0) return;
    }
}

}  // namespace

Image read_exr(const std::string& path) {
    try {
        std::error_code size_error;
        const auto file_bytes = std::filesystem::file_size(path, size_error);
        if (!size_error) check_exr_attribute_sizes(path, file_bytes);
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const long long w = (long long)dw.max.x - dw.min.x + 1, h = (long long)dw.max.y - dw.min.y + 1;
        if (w <= 0 || h <= 0 || w > (1 << 24) || h > (1 << 24) || w * h > (1ll << 31))
            throw_read_error(path, "unsupported EXR data window size");
        if (!size_error) check_pixel_count(path, w, h, file_bytes);
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
