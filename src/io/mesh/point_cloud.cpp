// The PLY and plain-text point-cloud writers (see point_cloud.h). Binary PLY is little-endian
// whatever the host's byte order; rows are assembled in blocks so large clouds stream out.
#include "io/mesh/point_cloud.h"

#include <algorithm>
#include <bit>
#include <charconv>

#include "core/error.h"

namespace phos::io {
namespace {

constexpr size_t kBlockPoints = 1 << 14;  // rows assembled per write

// A property name is one word; a comment one line.
void check_header_text(const std::string& text, bool one_word) {
    bool ok = !(one_word && text.empty());
    for (const char c : text) ok &= c != '\n' && c != '\r' && !(one_word && (c == ' ' || c == '\t'));
    if (!ok)
        throw InputError(std::string("point cloud: ") + (one_word ? "property name" : "comment") + " '" +
                         text + "' would break the PLY header");
}

// Throws unless every column has `cloud.size()` values in its own vector.
void check_columns(const PointCloud& cloud) {
    const size_t n = cloud.size();
    for (const PointColumn& c : cloud.columns) {
        check_header_text(c.name, true);
        if (c.size() != n || !(c.is_float ? c.bytes.empty() : c.floats.empty()))
            throw InputError("point cloud: column '" + c.name + "' has " + std::to_string(c.size()) +
                             " values for " + std::to_string(n) + " points");
    }
}

void append_float_text(std::string& s, float v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    s.append(buf, r.ptr);
}

void append_row_text(std::string& s, const std::vector<const PointColumn*>& columns, size_t i) {
    for (size_t k = 0; k < columns.size(); ++k) {
        if (k > 0) s += ' ';
        const PointColumn& c = *columns[k];
        if (c.is_float)
            append_float_text(s, c.floats[i]);
        else
            s += std::to_string(unsigned(c.bytes[i]));
    }
    s += '\n';
}

void append_row_binary(std::string& s, const std::vector<const PointColumn*>& columns, size_t i) {
    for (const PointColumn* c : columns) {
        if (!c->is_float) {
            s += char(c->bytes[i]);
            continue;
        }
        const uint32_t bits = std::bit_cast<uint32_t>(c->floats[i]);
        const char le[4] = {char(bits & 0xff), char((bits >> 8) & 0xff), char((bits >> 16) & 0xff),
                            char(bits >> 24)};
        s.append(le, 4);
    }
}

void write_rows(std::ostream& out, const std::vector<const PointColumn*>& columns, size_t n, bool binary) {
    std::string block;
    for (size_t start = 0; start < n; start += kBlockPoints) {
        block.clear();
        const size_t end = std::min(n, start + kBlockPoints);
        for (size_t i = start; i < end; ++i) {
            if (binary)
                append_row_binary(block, columns, i);
            else
                append_row_text(block, columns, i);
        }
        out.write(block.data(), std::streamsize(block.size()));
    }
    out.flush();
    if (!out) throw InputError("point cloud: write failed");
}

}  // namespace

PointColumn& PointCloud::add_floats(const std::string& name) {
    columns.push_back({name, true, {}, {}});
    return columns.back();
}

PointColumn& PointCloud::add_bytes(const std::string& name) {
    columns.push_back({name, false, {}, {}});
    return columns.back();
}

void write_ply_points(std::ostream& out, const PointCloud& cloud, bool binary) {
    check_columns(cloud);
    std::string header = "ply\nformat ";
    header += binary ? "binary_little_endian" : "ascii";
    header += " 1.0\n";
    for (const std::string& c : cloud.comments) {
        check_header_text(c, false);
        header += "comment " + c + "\n";
    }
    header += "element vertex " + std::to_string(cloud.size()) + "\n";
    std::vector<const PointColumn*> columns;
    for (const PointColumn& c : cloud.columns) {
        header += std::string("property ") + (c.is_float ? "float " : "uchar ") + c.name + "\n";
        columns.push_back(&c);
    }
    header += "end_header\n";
    out.write(header.data(), std::streamsize(header.size()));
    write_rows(out, columns, cloud.size(), binary);
}

void write_point_text(std::ostream& out, const PointCloud& cloud, const std::vector<std::string>& names) {
    check_columns(cloud);
    std::vector<const PointColumn*> columns;
    for (const std::string& name : names) {
        const PointColumn* found = nullptr;
        for (const PointColumn& c : cloud.columns)
            if (c.name == name) found = &c;
        if (!found) throw InputError("point cloud: no column '" + name + "'");
        columns.push_back(found);
    }
    const std::string count = std::to_string(cloud.size()) + "\n";
    out.write(count.data(), std::streamsize(count.size()));
    write_rows(out, columns, cloud.size(), false);
}

}  // namespace phos::io
