// Portable float map (PFM): "PF" (RGB) or "Pf" (grey) header, width height, then a scale whose sign
// gives the byte order (negative = little endian); 32-bit floats, rows stored bottom to top.
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/image/formats.h"

namespace phos::io::detail {
namespace {

constexpr bool kHostLittle = std::endian::native == std::endian::little;

float load_float(const unsigned char* p, bool little) {
    uint32_t u = 0;
    if (little)
        u = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
    else
        u = uint32_t(p[3]) | uint32_t(p[2]) << 8 | uint32_t(p[1]) << 16 | uint32_t(p[0]) << 24;
    return std::bit_cast<float>(u);
}

// Minimal header scanner over the file's bytes.
struct Scanner {
    const std::vector<unsigned char>& bytes;
    size_t pos = 0;

    static bool is_space(unsigned char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
    void skip_space() {
        while (pos < bytes.size() && is_space(bytes[pos])) ++pos;
    }
    std::string token() {
        skip_space();
        std::string t;
        while (pos < bytes.size() && !is_space(bytes[pos]) && t.size() < 64) t += char(bytes[pos++]);
        return t;
    }
};

bool parse_int(const std::string& s, long long& out) {
    if (s.empty() || s.size() > 9) return false;
    out = 0;
    for (char c : s) {
        if (c < '0' || c > '9') return false;
        out = out * 10 + (c - '0');
    }
    return true;
}

}  // namespace

Image read_pfm(const std::string& path) {
    const std::vector<unsigned char> bytes = read_file_bytes(path);

    Scanner sc{bytes};
    const std::string magic = sc.token();
    int channels = 0;
    if (magic == "PF")
        channels = 3;
    else if (magic == "Pf")
        channels = 1;
    else
        throw_read_error(path, "not a PFM file (expected 'PF' or 'Pf' header)");

    long long w = 0, h = 0;
    if (!parse_int(sc.token(), w) || !parse_int(sc.token(), h) || w <= 0 || h <= 0)
        throw_read_error(path, "malformed PFM size");
    const std::string scale_text = sc.token();
    char* end = nullptr;
    const double scale = std::strtod(scale_text.c_str(), &end);
    if (scale_text.empty() || *end != '\0' || scale == 0.0 || !std::isfinite(scale))
        throw_read_error(path, "malformed PFM scale '" + scale_text + "'");
    // Exactly one whitespace character separates the header from the raster.
    if (sc.pos >= bytes.size() || !Scanner::is_space(bytes[sc.pos]))
        throw_read_error(path, "truncated PFM header");
    const size_t data = sc.pos + 1;
    const bool little = scale < 0;

    const size_t row_bytes = size_t(w) * size_t(channels) * 4;
    const size_t needed = row_bytes * size_t(h);
    if (bytes.size() - data < needed)
        throw_read_error(path, "truncated PFM data (" + std::to_string(bytes.size() - data) + " of " +
                                   std::to_string(needed) + " bytes)");

    Image image(static_cast<int>(w), static_cast<int>(h));
    for (int y = 0; y < image.height; ++y) {
        // File row 0 is the bottom of the picture; our row 0 is the top.
        const unsigned char* row = bytes.data() + data + size_t(image.height - 1 - y) * row_bytes;
        for (int x = 0; x < image.width; ++x) {
            const unsigned char* p = row + size_t(x) * size_t(channels) * 4;
            if (channels == 3)
                image.at(x, y) =
                    Rgb(load_float(p, little), load_float(p + 4, little), load_float(p + 8, little));
            else
                image.at(x, y) = Rgb(load_float(p, little));
        }
    }
    return image;
}

void write_pfm(const std::string& path, const Image& image, bool greyscale) {
    const int channels = greyscale ? 1 : 3;
    const std::string header = std::string(greyscale ? "Pf" : "PF") + "\n" + std::to_string(image.width) +
                               " " + std::to_string(image.height) + "\n" + (kHostLittle ? "-1.0" : "1.0") +
                               "\n";
    std::vector<float> row(size_t(image.width) * size_t(channels));
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
    if (!f) throw InputError(std::strerror(errno));
    bool ok = std::fwrite(header.data(), 1, header.size(), f.get()) == header.size();
    for (int y = image.height - 1; y >= 0 && ok; --y) {
        for (int x = 0; x < image.width; ++x) {
            const Rgb c = image.at(x, y);
            if (greyscale)
                row[size_t(x)] = c.average();
            else {
                row[3 * size_t(x) + 0] = c.r;
                row[3 * size_t(x) + 1] = c.g;
                row[3 * size_t(x) + 2] = c.b;
            }
        }
        // Host byte order, which the sign of the scale above declares.
        ok = std::fwrite(row.data(), sizeof(float), row.size(), f.get()) == row.size();
    }
    if (!ok) throw InputError(std::string("write failed: ") + std::strerror(errno));
    if (std::fclose(f.release()) != 0) throw InputError(std::string("write failed: ") + std::strerror(errno));
}

}  // namespace phos::io::detail
