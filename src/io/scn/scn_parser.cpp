// The `.scn` parser core: files and includes, the command dispatch, and strict argument reading.
// Every command reads a fixed number of tokens and checks each one, so a short command is reported
// where it ends instead of silently eating the next command's numbers.
#include "io/scn/scn_parser.h"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <charconv>

#include "core/error.h"
#include "core/log.h"

namespace phos::io::scn {
namespace fs = std::filesystem;

namespace {

constexpr int kMaxIncludeDepth = 64;

bool is_command(const std::string& s) {
    static const char* const commands[] = {
        "camera",  "material",  "tri",         "box",        "sphere",     "circle",    "cylinder",
        "cone",    "line",      "mesh",        "begin",      "end",        "include",   "background",
        "ambient", "dir_light", "point_light", "spot_light", "area_light", "rect_light"};
    for (const char* c : commands)
        if (s == c) return true;
    return false;
}

}  // namespace

void Parser::fail(const Token& at, const std::string& message) const {
    throw ParseError(files_.back().name, at.line, at.col, message);
}

std::string Parser::where(const Token& t) const { return files_.back().name + ":" + std::to_string(t.line); }

const Transform& Parser::to_world() const {
    static const Transform identity;
    return groups_.empty() ? identity : groups_.back().to_world;
}

const Token* Parser::next_token() {
    File& f = files_.back();
    if (f.pos >= f.lexed.tokens.size()) return nullptr;
    return &f.lexed.tokens[f.pos++];
}

Parser::Args Parser::numbers(const Token& cmd, int n, const char* names) {
    Args a;
    a.v.reserve(size_t(n));
    a.tok.reserve(size_t(n));
    const auto expected = [&] {
        return cmd.text + ": expected " + std::to_string(n) + " numbers (" + names + "), got ";
    };
    for (int k = 0; k < n; ++k) {
        const Token* t = next_token();
        if (!t) {
            const File& f = files_.back();
            throw ParseError(f.name, f.lexed.end_line, f.lexed.end_col,
                             expected() + "end of file after " + std::to_string(k));
        }
        double v = 0;
        switch (parse_number(t->text, v)) {
            case NumberKind::Number:
                break;
            case NumberKind::NotFinite:
                fail(*t, cmd.text + ": '" + t->text + "' is not a finite number");
            case NumberKind::NotNumber:
                fail(*t, expected() + "'" + t->text + "'");
        }
        a.v.push_back(v);
        a.tok.push_back(*t);
    }
    return a;
}

fs::path Parser::file_argument(const Token& cmd, const char* what, Token& token) {
    const Token* t = next_token();
    if (!t) {
        const File& f = files_.back();
        throw ParseError(f.name, f.lexed.end_line, f.lexed.end_col,
                         cmd.text + ": expected a " + what + ", got end of file");
    }
    token = *t;
    fs::path p(t->text);
    if (p.is_relative()) p = files_.back().dir / p;
    p = p.lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) {
        if (is_command(t->text))
            fail(*t, cmd.text + ": expected a " + what + ", got '" + t->text + "' (missing argument?)");
        double unused;
        if (parse_number(t->text, unused) == NumberKind::Number)
            fail(*t, cmd.text + ": expected a " + what + ", got the number '" + t->text +
                         "' (too many numbers before it?)");
        fail(*t, cmd.text + ": " + what + " '" + t->text + "' not found (looked for '" + p.string() + "')");
    }
    return p;
}

int Parser::default_material() {
    if (default_material_ < 0) {
        // The format leaves -1 outside any group undefined; a mid-grey-white Lambertian surface
        // (albedo 0.8, like the usual "white" walls) is the least surprising reading.
        scene::Material m;
        m.name = "default white diffuse";
        m.diffuse = Rgb(0.8f);
        default_material_ = int(scene_.materials.size());
        scene_.materials.push_back(m);
    }
    return default_material_;
}

int Parser::emitter_material() {
    if (emitter_material_ < 0) {
        // Area lights are surfaces that emit but do not reflect: black diffuse.
        scene::Material m;
        m.name = "area light emitter (black)";
        emitter_material_ = int(scene_.materials.size());
        scene_.materials.push_back(m);
    }
    return emitter_material_;
}

int Parser::material(const Args& a, size_t i) {
    const Token& t = a.tok[i];
    const double v = a.v[i];
    if (v != std::floor(v)) fail(t, "material index must be an integer, got '" + t.text + "'");
    const File& f = files_.back();
    if (v == -1) {
        const int g = groups_.empty() ? -1 : groups_.back().material;
        return g >= 0 ? g : default_material();
    }
    if (v < 0 || v >= double(f.materials.size())) {
        std::string msg = "material " + t.text + " is not defined";
        msg += f.materials.empty()
                   ? " (this file defines no materials yet; use -1 for the group's material)"
                   : " (this file has defined materials 0.." + std::to_string(f.materials.size() - 1) +
                         " so far; use -1 for the group's material)";
        fail(t, msg);
    }
    return f.materials[size_t(v)];
}

void Parser::require_non_negative(const Args& a, size_t i, int count, const std::string& what) const {
    for (int k = 0; k < count; ++k)
        if (a.v[i + size_t(k)] < 0)
            fail(a.tok[i + size_t(k)],
                 what + " must not be negative, got '" + a.tok[i + size_t(k)].text + "'");
}

void Parser::require_positive(const Args& a, size_t i, const std::string& what) const {
    if (!(a.v[i] > 0)) fail(a.tok[i], what + " must be positive, got '" + a.tok[i].text + "'");
}

Vec3 Parser::direction(const Args& a, size_t i, const std::string& what) const {
    const double x = a.v[i], y = a.v[i + 1], z = a.v[i + 2];
    const double len = std::sqrt(x * x + y * y + z * z);
    if (!(len > 0) || !std::isfinite(float(len))) fail(a.tok[i], what + " must be a non-zero vector");
    return {float(x / len), float(y / len), float(z / len)};
}

void Parser::parse_top(const std::string& path) {
    fs::path p(path);
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) throw ParseError(path, 0, 0, "cannot open scene file (not found)");
    // Tokens are referenced across nested includes; no reallocation may move them.
    files_.reserve(size_t(kMaxIncludeDepth) + 1);
    parse_file(p, path, nullptr);
}

void Parser::parse_file(const fs::path& path, const std::string& name, const Token* included_by) {
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(path, ec);
    if (ec) canonical = fs::absolute(path).lexically_normal();
    if (included_by) {
        const auto cycle = std::find_if(files_.begin(), files_.end(),
                                        [&](const File& f) { return f.canonical == canonical; });
        if (cycle != files_.end()) {
            std::string chain;
            for (auto it = cycle; it != files_.end(); ++it) chain += it->name + " -> ";
            fail(*included_by, "include cycle: " + chain + name);
        }
        if (int(files_.size()) >= kMaxIncludeDepth)
            fail(*included_by, "includes nested more than " + std::to_string(kMaxIncludeDepth) + " deep");
    }
    std::string bytes;
    try {
        bytes = read_file_bytes(path.string());
    } catch (const InputError& e) {
        if (included_by) fail(*included_by, std::string("include: ") + e.what());
        throw ParseError(name, 0, 0, e.what());
    }

    // An error anywhere inside an included file also names where the include names the file (and,
    // as the error passes each enclosing include, where that one does).
    const std::string includer = included_by ? files_.back().name : std::string();
    try {
        File f;
        f.name = name;
        f.dir = path.parent_path();
        f.canonical = canonical;
        f.lexed = lex(name, bytes);
        f.group_base = groups_.size();
        f.id = next_file_id_++;
        files_.push_back(std::move(f));

        while (const Token* t = next_token()) command(*t);

        File& done = files_.back();
        if (groups_.size() > done.group_base)
            fail(groups_.back().begin, "begin without a matching end (in this file)");
        files_.pop_back();
    } catch (ParseError& e) {
        if (included_by) e.add_included_from(includer, included_by->line, included_by->col);
        throw;
    }
}

void Parser::command(const Token& keyword) {
    const std::string& k = keyword.text;
    if (k == "camera") return cmd_camera(keyword);
    if (k == "material") return cmd_material(keyword);
    if (k == "tri") return cmd_tri(keyword);
    if (k == "box") return cmd_box(keyword);
    if (k == "sphere") return cmd_sphere(keyword);
    if (k == "circle") return cmd_circle(keyword);
    if (k == "cylinder") return cmd_cylinder_or_cone(keyword, false);
    if (k == "cone") return cmd_cylinder_or_cone(keyword, true);
    if (k == "line") return cmd_line(keyword);
    if (k == "mesh") return cmd_mesh(keyword);
    if (k == "begin") return cmd_begin(keyword);
    if (k == "end") return cmd_end(keyword);
    if (k == "include") return cmd_include(keyword);
    if (k == "background") return cmd_background_or_ambient(keyword, true);
    if (k == "ambient") return cmd_background_or_ambient(keyword, false);
    if (k == "dir_light") return cmd_dir_light(keyword);
    if (k == "point_light") return cmd_point_or_spot_light(keyword, false);
    if (k == "spot_light") return cmd_point_or_spot_light(keyword, true);
    if (k == "area_light") return cmd_area_light(keyword);
    if (k == "rect_light") return cmd_rect_light(keyword);
    double unused;
    if (parse_number(k, unused) != NumberKind::NotNumber)
        fail(keyword, "unexpected number '" + k +
                          "' where a command belongs (too many numbers in the "
                          "previous command?)");
    fail(keyword, "unknown command '" + k + "'");
}

}  // namespace phos::io::scn
