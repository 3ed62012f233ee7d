// Input files that may be gzip-compressed (pbrt's `.pbrt.gz` includes and imports, `.ply.gz`
// meshes, and any other mesh or scene file phos reads): the two gzip magic bytes at the start of
// the file decide, not its name. Decompression is zlib's (RFC 1952 streams, several members one
// after the other as gzip writes them); a damaged stream is a ParseError located at the file,
// saying what zlib found and where in the compressed bytes, without printing any of them.
#pragma once

#include <istream>
#include <memory>
#include <string>
#include <string_view>

namespace phos::io {

// Whether `bytes` starts with the gzip magic (0x1f 0x8b).
bool is_gzip(std::string_view bytes);

// The decompressed contents of the gzip stream `bytes`, read from `path` (named in errors).
// Throws ParseError(path, 0, 0, ...) for a truncated or corrupt stream, and for one that would
// decompress to more than `max_bytes`.
std::string gunzip(std::string_view bytes, const std::string& path, size_t max_bytes = size_t(1) << 36);

// The file's bytes, decompressed when it is a gzip stream. Returns false when the file cannot be
// opened or read (the caller says so in its own words); throws as gunzip does.
bool read_maybe_gzip(const std::string& path, std::string& out);

// The file as a stream: the file itself when it is not compressed, else its decompressed bytes in
// memory. Null when the file cannot be opened; throws as gunzip does.
std::unique_ptr<std::istream> open_maybe_gzip(const std::string& path);

}  // namespace phos::io
