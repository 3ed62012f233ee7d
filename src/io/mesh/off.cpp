// OFF (Object File Format) reader: `[ST][C][N]OFF` header, counts, one vertex per line, then one
// polygon per line as `k i1 ... ik [colour]` (fan-triangulated; colours ignored). Strict: every
// problem is a ParseError at the offending line and column of the mesh file.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "io/gzip/gzip_file.h"
#include "io/mesh/mesh_io.h"

namespace phos::io {
namespace {

struct Tok {
    std::string text;
    int col = 0;
};
struct Line {
    int number = 0;
    std::vector<Tok> toks;
    int end_col = 1;
};

// Splits the file into non-empty lines of tokens, dropping `#` comments.
std::vector<Line> split_lines(const std::string& path, const std::string& bytes, int& last_line) {
    std::vector<Line> lines;
    Line cur;
    cur.number = 1;
    int col = 1;
    bool comment = false, in_tok = false;
    for (size_t i = 0; i <= bytes.size(); ++i) {
        const char c = i < bytes.size() ? bytes[i] : '\n';
        if (c == '\n') {
            cur.end_col = col;
            last_line = cur.number;
            const int next = cur.number + 1;
            if (!cur.toks.empty()) lines.push_back(std::move(cur));
            cur = Line{};
            cur.number = next;
            col = 1, comment = false, in_tok = false;
            continue;
        }
        const unsigned char u = static_cast<unsigned char>(c);
        const bool space = c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
        if (!space && (u < 0x20 || u == 0x7F)) {
            throw ParseError(
                path, cur.number, col,
                "binary or control byte " + printf_string("0x%02X", u) + " (binary OFF is not supported)");
        }
        if (c == '#') comment = true;
        if (comment || space) {
            in_tok = false;
        } else {
            if (!in_tok) cur.toks.push_back(Tok{"", col});
            cur.toks.back().text += c;
            in_tok = true;
        }
        // Columns count characters: skip UTF-8 continuation bytes.
        if ((u & 0xC0) != 0x80) ++col;
    }
    return lines;
}

bool parse_float(const std::string& s, float& out) {
    const char* b = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
    const char* e = s.data() + s.size();
    double v = 0;
    const auto [p, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || p != e || !std::isfinite(v) || std::fabs(v) > 3.4e38) return false;
    out = float(v);
    return true;
}

bool parse_count(const std::string& s, long long& out) {
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size();
}

}  // namespace

scene::TriangleMesh read_off(const std::string& path) {
    std::string bytes;
    if (!read_maybe_gzip(path, bytes)) throw ParseError(path, 0, 0, "cannot open OFF file");
    int last_line = 1;
    const std::vector<Line> lines = split_lines(path, bytes, last_line);
    const auto fail = [&](int line, int col, const std::string& msg) {
        throw ParseError(path, line, col, msg);
    };
    // A truncated file is reported at the end of its last non-empty line.
    const auto fail_eof = [&](const std::string& msg) {
        if (lines.empty()) fail(last_line, 1, msg);
        fail(lines.back().number, lines.back().end_col, msg);
    };

    if (lines.empty()) fail(1, 1, "empty file (expected the OFF header)");
    size_t li = 0;
    // Header: [ST][C][N]OFF, optionally followed by the counts on the same line.
    const Line& head = lines[li++];
    const std::string& h = head.toks[0].text;
    if (h.size() < 3 || h.compare(h.size() - 3, 3, "OFF") != 0)
        fail(head.number, head.toks[0].col, "expected the OFF header, got '" + h + "'");
    std::string prefix = h.substr(0, h.size() - 3);
    bool has_st = false, has_c = false, has_n = false;
    if (prefix.rfind("ST", 0) == 0) has_st = true, prefix.erase(0, 2);
    if (!prefix.empty() && prefix[0] == 'C') has_c = true, prefix.erase(0, 1);
    if (!prefix.empty() && prefix[0] == 'N') has_n = true, prefix.erase(0, 1);
    if (!prefix.empty())
        fail(head.number, head.toks[0].col, "unsupported OFF variant '" + h + "' (4D / n-dimensional OFF)");
    std::vector<Tok> counts(head.toks.begin() + 1, head.toks.end());
    int counts_line = head.number;
    if (!counts.empty() && counts[0].text == "BINARY")
        fail(head.number, counts[0].col, "binary OFF is not supported");
    if (counts.empty()) {
        if (li >= lines.size()) fail_eof("file ends before the vertex and face counts");
        counts = lines[li].toks;
        counts_line = lines[li++].number;
    }
    if (counts.size() < 2 || counts.size() > 3)
        fail(
            counts_line, counts[0].col,
            "expected the counts 'vertices faces [edges]', got " + std::to_string(counts.size()) + " values");
    long long nv = 0, nf = 0, ne = 0;
    if (!parse_count(counts[0].text, nv) || nv < 0)
        fail(counts_line, counts[0].col, "bad vertex count '" + counts[0].text + "'");
    if (!parse_count(counts[1].text, nf) || nf < 0)
        fail(counts_line, counts[1].col, "bad face count '" + counts[1].text + "'");
    if (counts.size() == 3 && (!parse_count(counts[2].text, ne) || ne < 0))
        fail(counts_line, counts[2].col, "bad edge count '" + counts[2].text + "'");
    // Each vertex/face needs its own line; a count beyond the lines left is a truncated file, and
    // checking first keeps a corrupt count from reserving gigabytes.
    const long long lines_left = static_cast<long long>(lines.size() - li);
    if (nv > lines_left)
        fail_eof("file ends early: it declares " + std::to_string(nv) + " vertices but has only " +
                 std::to_string(lines_left) + " lines left");
    if (nf > lines_left - nv)
        fail_eof("file ends early: it declares " + std::to_string(nf) + " faces but has only " +
                 std::to_string(lines_left - nv) + " lines after the vertices");

    scene::TriangleMesh mesh;
    mesh.positions.reserve(size_t(nv));
    const size_t need = 3 + (has_n ? 3 : 0) + (has_c ? 3 : 0) + (has_st ? 2 : 0);
    for (long long v = 0; v < nv; ++v) {
        const Line& l = lines[li++];
        float x[32];
        if (l.toks.size() < need)
            fail(l.number, l.end_col,
                 "vertex " + std::to_string(v) + " has " + std::to_string(l.toks.size()) +
                     " numbers, expected " + std::to_string(need) + " (for " + h + ")");
        for (size_t k = 0; k < l.toks.size(); ++k) {
            float value;
            if (!parse_float(l.toks[k].text, value))
                fail(l.number, l.toks[k].col, "expected a finite number, got '" + l.toks[k].text + "'");
            if (k < 32) x[k] = value;
        }
        mesh.positions.push_back({x[0], x[1], x[2]});
        if (has_n) mesh.normals.push_back({x[3], x[4], x[5]});
        if (has_st) {
            // s t come last on the line (after a colour of 3 or 4 components, if any).
            const size_t n = std::min<size_t>(l.toks.size(), 32);
            mesh.uvs.push_back({x[n - 2], x[n - 1]});
        }
    }
    for (long long f = 0; f < nf; ++f) {
        const Line& l = lines[li++];
        long long k = 0;
        if (!parse_count(l.toks[0].text, k))
            fail(l.number, l.toks[0].col, "expected the face's vertex count, got '" + l.toks[0].text + "'");
        if (k < 3) fail(l.number, l.toks[0].col, "a face needs at least 3 vertices, got " + l.toks[0].text);
        if (static_cast<long long>(l.toks.size()) - 1 < k)
            fail(l.number, l.end_col,
                 "face " + std::to_string(f) + " has " + std::to_string(l.toks.size() - 1) +
                     " indices, expected " + std::to_string(k));
        std::vector<uint32_t> idx(static_cast<size_t>(k));
        for (long long j = 0; j < k; ++j) {
            const Tok& t = l.toks[size_t(1 + j)];
            long long i = 0;
            if (!parse_count(t.text, i))
                fail(l.number, t.col, "expected a vertex index, got '" + t.text + "'");
            if (i < 0 || i >= nv)
                fail(l.number, t.col,
                     "vertex index " + t.text + " out of range (the file has " + std::to_string(nv) +
                         " vertices)");
            idx[size_t(j)] = uint32_t(i);
        }
        // Anything after the indices is a per-face colour: checked to be numeric, then ignored.
        for (size_t j = size_t(k) + 1; j < l.toks.size(); ++j) {
            float unused;
            if (!parse_float(l.toks[j].text, unused))
                fail(l.number, l.toks[j].col, "expected a face colour number, got '" + l.toks[j].text + "'");
        }
        for (size_t j = 1; j + 1 < idx.size(); ++j) {  // fan around the first corner
            mesh.indices.push_back(idx[0]);
            mesh.indices.push_back(idx[j]);
            mesh.indices.push_back(idx[j + 1]);
        }
    }
    if (li < lines.size())
        fail(lines[li].number, lines[li].toks[0].col,
             "unexpected content after the last face (is the face count " + std::to_string(nf) + " right?)");
    return mesh;
}

}  // namespace phos::io
