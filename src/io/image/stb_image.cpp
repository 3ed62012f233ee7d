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

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

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

// stb_image 2.27 (Debian 12) copies a JPEG Huffman table's symbols into 256-entry arrays without
// checking that the table's 16 code counts add up to at most 256, so a corrupt DHT segment
// overwrites the decoder's memory; and it decodes a scan with a Huffman table no DHT segment
// defined, reading the table's uninitialised memory as code limits and offsets (a symbol index of
// -56837: an out-of-bounds read, the image fuzzer's finding). This walks the file the way stb does
// (segments skipped by their length, entropy-coded data scanned for markers, fill bytes 0xFF
// skipped) and returns a reason when any DHT segment stb could reach holds such a table, or a scan
// uses a table not defined before it, else "".
std::string jpeg_huffman_problem(std::span<const unsigned char> b) {
    // stb takes a file for a JPEG when it starts with an SOI marker, 0xFF fill bytes allowed.
    size_t p = 0;
    while (p < b.size() && b[p] == 0xFF) ++p;
    if (p == 0 || p >= b.size() || b[p] != 0xD8) return "";  // not a JPEG
    ++p;
    // Bytes past the end read as 0, as in stb.
    const auto at = [&](size_t i) -> unsigned { return i < b.size() ? b[i] : 0u; };
    bool defined[2][4] = {};  // [class: 0 DC, 1 AC][table id]
    bool progressive = false;
    while (p < b.size()) {
        if (b[p] != 0xFF) {  // entropy-coded data or padding: look for the next marker
            ++p;
            continue;
        }
        while (p < b.size() && b[p] == 0xFF) ++p;
        if (p >= b.size()) break;
        const unsigned m = b[p++];
        if (m == 0x00 || m == 0x01 || (m >= 0xD0 && m <= 0xD8)) continue;  // stuffing, TEM, RSTn, SOI
        if (m == 0xD9) break;                                              // EOI: stb stops here
        const size_t length = at(p) << 8 | at(p + 1);
        if (m == 0xC2) progressive = true;
        if (m == 0xDA) {
            // Which tables the scan decodes with (stb rejects indices above 3 itself): baseline
            // scans a DC and an AC table per component; progressive DC-first scans (Ss = 0,
            // Ah = 0) DC tables only, DC refinements none, AC scans (Ss > 0) AC tables only.
            const unsigned ns = at(p + 2);
            const unsigned ss = at(p + 3 + 2 * ns), ah = at(p + 5 + 2 * ns) >> 4;
            for (unsigned i = 0; i < ns && i < 4; ++i) {
                const unsigned td = at(p + 4 + 2 * i) >> 4, ta = at(p + 4 + 2 * i) & 15;
                const bool dc = !progressive || (ss == 0 && ah == 0), ac = !progressive || ss > 0;
                if ((dc && td <= 3 && !defined[0][td]) || (ac && ta <= 3 && !defined[1][ta]))
                    return "corrupt JPEG (a scan uses a Huffman table that no DHT segment defines)";
            }
        }
        if (m == 0xC4) {
            long left = long(length) - 2;
            size_t q = p + 2;
            while (left > 0) {
                const unsigned tc = at(q) >> 4, th = at(q) & 15;
                if (tc > 1 || th > 3) break;  // stb rejects the segment before using it
                unsigned codes = 0;
                for (size_t i = 1; i <= 16; ++i) codes += at(q + i);
                if (codes > 256)
                    return "corrupt JPEG (a Huffman table declares " + std::to_string(codes) +
                           " codes; at most 256 are possible)";
                defined[tc][th] = true;
                q += 17 + codes;
                left -= long(17 + codes);
            }
        }
        p += std::max<size_t>(length, 2);
    }
    return "";
}

// stb_image 2.27 decodes a run-length encoded Radiance HDR scanline with a loop that never ends when
// a "dump" count is 0, which is also what it reads at the end of the file: a truncated or corrupt
// file hangs it. This walks the scanlines of the `width` x `height` HDR file `b` as stb does and
// returns a reason when it would meet such a count, else "".
std::string hdr_rle_problem(std::span<const unsigned char> b, int width, int height) {
    if (width < 8 || width >= 32768) return "";  // stb reads flat pixels then, which always ends
    const auto at = [&](size_t i) -> unsigned { return i < b.size() ? b[i] : 0u; };  // 0 past the end
    // The header: the magic line, lines up to an empty one, then the "-Y h +X w" line.
    size_t p = 0;
    const auto skip_line = [&] {
        const size_t first = p;
        while (p < b.size() && b[p] != '\n') ++p;
        // stb ends the header at a line whose first byte is 0, not only at an empty one (it reads
        // lines as C strings): a "\0" line made this walk miss the pixels (the fuzzer's timeouts).
        const bool empty = p == first || b[first] == 0;
        if (p < b.size()) ++p;
        return empty;
    };
    skip_line();
    while (p < b.size() && !skip_line()) {
    }
    skip_line();
    const std::string problem =
        "corrupt HDR (a run-length encoded scanline ends early or holds an empty run)";
    for (int y = 0; y < height; ++y) {
        const unsigned c1 = at(p), c2 = at(p + 1), len_high = at(p + 2);
        p += 3;
        if (c1 != 2 || c2 != 2 || (len_high & 0x80)) return "";  // stb reads the rest as flat pixels
        if (int(len_high << 8 | at(p++)) != width) return "";    // stb rejects the scanline
        for (int k = 0; k < 4; ++k)
            for (int x = 0; x < width;) {
                unsigned count = at(p++);
                if (count > 128) {
                    ++p;  // the run's value
                    count -= 128;
                } else {
                    if (count == 0) return problem;
                    p += count;
                }
                if (int(count) > width - x) return "";  // stb rejects the run
                x += int(count);
            }
    }
    return "";
}

// stb_image 2.27 grows its buffer for a PNG IDAT chunk to the chunk's claimed length before it
// reads a byte of it: a 92-byte file claiming a 1.9 GB chunk made it allocate 2 GB (the image
// fuzzer's out-of-memory finding). This walks the chunks (8-byte signature, then length, type,
// data, CRC each) up to IEND and returns a reason when a chunk claims more bytes than the file
// has left, else "" (also for files that are not PNG).
std::string png_chunk_problem(std::span<const unsigned char> b) {
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (b.size() < 8 || std::memcmp(b.data(), kSignature, 8) != 0) return "";
    for (size_t pos = 8; b.size() - pos >= 8;) {
        const unsigned char* c = b.data() + pos;
        const uint64_t length = uint64_t(c[0]) << 24 | uint64_t(c[1]) << 16 | uint64_t(c[2]) << 8 | c[3];
        pos += 8;
        const uint64_t left = b.size() - pos;
        if (length > left)
            return "corrupt PNG (a chunk claims " + std::to_string(length) + " bytes, more than the " +
                   std::to_string(left) + " left in the file)";
        if (std::memcmp(c + 4, "IEND", 4) == 0) break;
        if (length + 4 > left) break;  // data and CRC
        pos += size_t(length) + 4;
    }
    return "";
}

// Whether stb decodes the bytes as TGA: by content, whatever the file's name, trying the formats in
// stb's own order (TGA's weak test comes last).
bool decodes_as_tga(std::span<const unsigned char> b) {
    stbi__context s;
    stbi__start_mem(&s, b.data(), int(b.size()));
    return !stbi__png_test(&s) && !stbi__bmp_test(&s) && !stbi__jpeg_test(&s) && !stbi__hdr_test(&s) &&
           stbi__tga_test(&s);
}

}  // namespace

Image read_stb(const std::string& path, bool srgb) {
    // stb decodes from memory, the bytes every check below walks. Its file reader keeps only the
    // first 128 bytes for the rewinds between its format tests, so a test that reads further (a
    // JPEG after 137 fill bytes, the image fuzzer's finding) left it decoding a stream that is not
    // the file, one the checks could not see: a Huffman table whose counts came from stale buffer
    // bytes overran stb's size list. stb's lengths are ints.
    const std::vector<unsigned char> bytes = read_file_bytes(path, size_t(INT_MAX));
    const unsigned char* const data_in = bytes.data();
    const int size = int(bytes.size());
    if (const std::string reason = bmp_truncation(bytes); !reason.empty()) throw_read_error(path, reason);
    if (const std::string reason = jpeg_huffman_problem(bytes); !reason.empty())
        throw_read_error(path, reason);
    if (const std::string reason = png_chunk_problem(bytes); !reason.empty()) throw_read_error(path, reason);
    // stb allocates the whole image from the header before reading any pixel (and for TGA then
    // loops over every pixel even when the file ends), so a corrupt size is refused first.
    const bool hdr = stbi_is_hdr_from_memory(data_in, size);
    int w = 0, h = 0, n = 0;
    if (stbi_info_from_memory(data_in, size, &w, &h, &n)) {
        // TGA: stb fills the pixels a truncated run-length file lacks, however many its header
        // claims, so the bound is what run-length packets can encode.
        check_pixel_count(path, w, h, bytes.size(),
                          decodes_as_tga(bytes) ? kMaxTgaPixelsPerByte : kMaxPixelsPerByte);
        if (hdr)
            if (const std::string reason = hdr_rle_problem(bytes, w, h); !reason.empty())
                throw_read_error(path, reason);
    }
    Image image;

    if (hdr) {
        // Radiance HDR holds linear floats already; stb would not alter them for .hdr input.
        std::unique_ptr<float, StbFree> data(stbi_loadf_from_memory(data_in, size, &w, &h, &n, 3));
        if (!data || w <= 0 || h <= 0) throw_read_error(path, stb_reason());
        image = Image(w, h);
        for (size_t i = 0; i < image.pixels.size(); ++i)
            image.pixels[i] = Rgb(data.get()[3 * i], data.get()[3 * i + 1], data.get()[3 * i + 2]);
        return image;
    }

    if (stbi_is_16_bit_from_memory(data_in, size)) {
        std::unique_ptr<stbi_us, StbFree> data(stbi_load_16_from_memory(data_in, size, &w, &h, &n, 3));
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
    std::unique_ptr<stbi_uc, StbFree> data(stbi_load_from_memory(data_in, size, &w, &h, &n, 3));
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
