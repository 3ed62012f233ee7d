// Reading gzip-compressed input files through zlib (see gzip_file.h).
#include "io/gzip/gzip_file.h"

#include <zlib.h>

#include <algorithm>
#include <climits>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace phos::io {

bool is_gzip(std::string_view bytes) {
    return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
           static_cast<unsigned char>(bytes[1]) == 0x8b;
}

std::string gunzip(std::string_view bytes, const std::string& path, size_t max_bytes) {
    z_stream z{};
    // 16 + MAX_WBITS: a gzip header and trailer (CRC-32 and length checked), not raw or zlib data.
    if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK)
        throw ParseError(path, 0, 0, "cannot start gzip decompression");
    std::string out;
    const auto fail = [&](const std::string& what) {
        const size_t at = size_t(z.total_in);
        inflateEnd(&z);
        throw ParseError(path, 0, 0,
                         "corrupt gzip stream: " + what + " (at byte " + std::to_string(at) + " of " +
                             std::to_string(bytes.size()) + " compressed)");
    };
    size_t in_pos = 0;
    char buffer[1 << 16];
    for (;;) {
        if (z.avail_in == 0 && in_pos < bytes.size()) {
            const size_t n = std::min(bytes.size() - in_pos, size_t(UINT_MAX));
            z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + in_pos));
            z.avail_in = uInt(n);
            in_pos += n;
        }
        z.next_out = reinterpret_cast<Bytef*>(buffer);
        z.avail_out = sizeof buffer;
        const int rc = inflate(&z, Z_NO_FLUSH);
        const size_t produced = sizeof buffer - z.avail_out;
        if (out.size() + produced > max_bytes)
            fail("it decompresses to more than " + std::to_string(max_bytes) + " bytes");
        out.append(buffer, produced);
        if (rc == Z_STREAM_END) {
            // Another member may follow (gzip writes one per concatenated file); trailing zero
            // bytes (padding some tools leave) end the file.
            const size_t used = in_pos - z.avail_in;
            std::string_view rest = bytes.substr(used);
            if (rest.find_first_not_of('\0') == std::string_view::npos) break;
            if (!is_gzip(rest)) fail("unexpected bytes after the end of the compressed data");
            if (inflateReset(&z) != Z_OK) fail("cannot restart for the next member");
            continue;
        }
        if (rc == Z_BUF_ERROR && z.avail_in == 0 && in_pos == bytes.size())
            fail("the file ends inside the stream");
        if (rc != Z_OK && rc != Z_BUF_ERROR) fail(z.msg ? z.msg : "zlib error " + std::to_string(rc));
    }
    inflateEnd(&z);
    return out;
}

bool read_maybe_gzip(const std::string& path, std::string& out) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) return false;
    out = std::move(ss).str();
    if (is_gzip(out)) out = gunzip(out, path);
    return true;
}

std::unique_ptr<std::istream> open_maybe_gzip(const std::string& path) {
    auto file = std::make_unique<std::ifstream>(path, std::ios::binary);
    if (!*file) return nullptr;
    char magic[2] = {0, 0};
    file->read(magic, 2);
    const bool gz = file->gcount() == 2 && is_gzip(std::string_view(magic, 2));
    file->clear();
    file->seekg(0);
    if (!gz) return file;
    std::ostringstream compressed;
    compressed << file->rdbuf();
    if (file->bad()) return nullptr;
    return std::make_unique<std::istringstream>(gunzip(std::move(compressed).str(), path));
}

}  // namespace phos::io
