// Point-cloud writers: a PLY vertex element (binary little-endian or ASCII, opened by MeshLab and
// CloudCompare) and a plain text table, from a neutral set of named per-point columns.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace phos::io {

// One per-point property, one value per point: in `floats` (a PLY `float`) or `bytes` (a PLY
// `uchar`), as `is_float` says; the other vector stays empty.
struct PointColumn {
    std::string name;  // PLY property name: "x", "red", "power_r"...
    bool is_float = true;
    std::vector<float> floats;
    std::vector<uint8_t> bytes;
    size_t size() const { return is_float ? floats.size() : bytes.size(); }
};

// Points as columns (in property order) and the comments the PLY header carries.
struct PointCloud {
    std::vector<std::string> comments;  // one line each, without "comment "
    std::vector<PointColumn> columns;
    size_t size() const { return columns.empty() ? 0 : columns.front().size(); }
    PointColumn& add_floats(const std::string& name);
    PointColumn& add_bytes(const std::string& name);
};

// Writes `cloud` as a PLY file with one `vertex` element. Floats are written exactly (ASCII: the
// shortest text that reads back to the same float). Throws InputError when the columns differ in
// length, a name or comment would break the header, or the stream fails.
void write_ply_points(std::ostream& out, const PointCloud& cloud, bool binary);

// Writes the plain text table: the point count on the first line, then per point the values of
// the named columns separated by spaces. Throws InputError for a name that is not a column.
void write_point_text(std::ostream& out, const PointCloud& cloud, const std::vector<std::string>& columns);

}  // namespace phos::io
