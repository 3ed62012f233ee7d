// The `.scene` reader's core: files as lines of tokens, cycle detection, and strict argument
// reading (exact counts, finite numbers, existing files), each failure located in its own file.
#include "io/scene_format/reader.h"

#include <algorithm>
#include <cstdio>

#include "core/error.h"
#include "core/log.h"
#include "io/scene_format/scene_format_loader.h"

namespace phos::io::scene_format {
namespace fs = std::filesystem;

namespace {

// Characters (UTF-8 code points) in `s`, for the column just past a token.
int code_points(const std::string& s) {
    return int(std::count_if(s.begin(), s.end(),
                             [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

// The canonical form of an existing path (the path itself if the file system cannot say).
fs::path canonical_of(const fs::path& path) {
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(path, ec);
    return ec ? path : canonical;
}

std::string show_chain(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : " -> ") + n;
    return s;
}

}  // namespace

void Reader::open(const FileArg& arg) {
    File f;
    f.name = arg.name;
    f.dir = arg.path.parent_path();
    f.canonical = arg.canonical;
    if (!files_.empty()) f.named_at = ParseError::location(file().name, arg.token.line, arg.token.col);
    text::LexedFile lexed;
    try {
        lexed = text::lex(arg.name, text::read_file_bytes(arg.path.string()));
    } catch (ParseError& e) {  // a byte the lexer refuses, in the file being opened
        if (!files_.empty()) add_includers(e, arg.token);
        throw;
    }
    for (const Token& t : lexed.tokens) {
        if (f.lines.empty() || f.lines.back().keyword.line != t.line) {
            f.lines.push_back({t, {}, t.col + code_points(t.text)});
        } else {
            f.lines.back().args.push_back(t);
            f.lines.back().end_col = t.col + code_points(t.text);
        }
    }
    f.end_line = lexed.end_line;
    f.end_col = lexed.end_col;
    files_.push_back(std::move(f));
}

void Reader::fail(const Token& at, const std::string& message) const { fail_at(at.line, at.col, message); }

void Reader::fail_at(int line, int col, const std::string& message) const {
    throw ParseError(file().name, line, col, message, include_chain());
}

std::vector<std::string> Reader::include_chain() const {
    std::vector<std::string> chain;
    for (auto it = files_.rbegin(); it != files_.rend(); ++it)
        if (!it->named_at.empty()) chain.push_back(it->named_at);
    return chain;
}

void Reader::add_includers(ParseError& e, const Token& at) const {
    e.add_included_from(file().name, at.line, at.col);
    for (const std::string& place : include_chain()) e.add_included_from(place);
}

std::string Reader::where(const Token& at) const { return file().name + ":" + std::to_string(at.line); }

void Reader::require_args(const Line& l, size_t n, const char* what) const {
    const std::string cmd = l.keyword.text;
    if (l.args.size() < n)
        fail_at(l.keyword.line, l.end_col,
                cmd + ": expected " + what + ", got " + std::to_string(l.args.size()) + " argument" +
                    (l.args.size() == 1 ? "" : "s"));
    if (l.args.size() > n)
        fail(l.args[n], cmd + ": extra argument '" + l.args[n].text + "' (expected " + what + ")");
}

std::vector<double> Reader::numbers(const Line& l, size_t n, const char* names) const {
    const std::string what = std::to_string(n) + (n == 1 ? " number: " : " numbers: ") + names;
    require_args(l, n, what.c_str());
    std::vector<double> v(n);
    for (size_t i = 0; i < n; ++i) {
        switch (text::parse_number(l.args[i].text, v[i])) {
            case text::NumberKind::Number:
                break;
            case text::NumberKind::NotFinite:
                fail(l.args[i], l.keyword.text + ": '" + l.args[i].text + "' is not a finite number");
            case text::NumberKind::NotNumber:
                fail(l.args[i], l.keyword.text + ": expected a number, got '" + l.args[i].text +
                                    "' (arguments: " + names + ")");
        }
    }
    return v;
}

void Reader::require_non_negative(const Line& l, const std::vector<double>& v, size_t first,
                                  size_t count) const {
    for (size_t i = first; i < first + count; ++i)
        if (v[i] < 0)
            fail(l.args[i], l.keyword.text + ": must not be negative, got '" + l.args[i].text + "'");
}

Reader::FileArg Reader::file_argument(const Line& l, size_t i, const char* what) const {
    FileArg f;
    f.token = l.args[i];
    const fs::path p(f.token.text);
    f.path = p.is_absolute() ? p : file().dir / p;
    f.name = p.is_absolute() ? p.string() : (file().dir / p).lexically_normal().string();
    std::error_code ec;
    if (!fs::exists(f.path, ec))
        fail(f.token, l.keyword.text + ": cannot open " + what + " '" + f.token.text + "': no such file");
    if (fs::is_directory(f.path, ec))
        fail(f.token, l.keyword.text + ": " + what + " '" + f.token.text + "' is a directory");
    // A file already being read would be read forever.
    f.canonical = canonical_of(f.path);
    for (const File& open_file : files_)
        if (open_file.canonical == f.canonical) {
            std::vector<std::string> chain;
            for (const File& g : files_) chain.push_back(g.name);
            chain.push_back(f.name);
            fail(f.token, l.keyword.text + ": '" + f.token.text +
                              "' is already being read (a cycle: " + show_chain(chain) + ")");
        }
    return f;
}

void Reader::reject_duplicate(const Line& l, std::map<std::string, int>& seen) const {
    const auto [it, inserted] = seen.emplace(l.keyword.text, l.keyword.line);
    if (!inserted)
        fail(l.keyword,
             "'" + l.keyword.text + "' is given twice (first at line " + std::to_string(it->second) + ")");
}

void Reader::read_scene(const std::string& path) {
    open(FileArg{path, canonical_of(path), path, Token{}});
    for (const Line& l : file().lines) scene_command(l);
    finish();
    close();
}

}  // namespace phos::io::scene_format

namespace phos::io {

scene::Scene load_scene_format(const std::string& path) {
    scene::Scene scene;
    scene.source = path;
    scene_format::Reader reader(scene);
    reader.read_scene(path);
    return scene;
}

}  // namespace phos::io
