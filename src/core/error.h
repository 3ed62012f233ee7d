// Error types. ParseError carries the location of malformed input (file:line:col) and, when that
// file was included by another (a mesh named by a scene, an included scene), the places that
// included it; InputError is a bad option or unusable input with no location. The CLI turns both
// into exit code 2.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace phos {

struct ParseError : std::runtime_error {
    std::string file;
    int line = 0;
    int column = 0;
    std::string message;
    // Where `file` was included from, innermost first ("scene.scn:12:1"), as compilers and pbrt
    // show it: what() prints each on a line of its own, "  included from scene.scn:12:1".
    std::vector<std::string> included_from;

    ParseError(std::string file_, int line_, int column_, std::string message_,
               std::vector<std::string> included_from_ = {})
        : std::runtime_error(format(file_, line_, column_, message_)),
          file(std::move(file_)),
          line(line_),
          column(column_),
          message(std::move(message_)),
          included_from(std::move(included_from_)) {
        update_text();
    }

    // Records that the file holding the error (or the file that included it, and so on outwards)
    // was included at `f:l:c`. Callers add the places from the inside out as the error passes them.
    void add_included_from(const std::string& f, int l, int c) { add_included_from(location(f, l, c)); }
    void add_included_from(std::string place) {  // place: "file:line:col", as location() writes it
        included_from.push_back(std::move(place));
        update_text();
    }

    const char* what() const noexcept override { return text_.c_str(); }

    static std::string location(const std::string& f, int l, int c) {
        std::string s = f;
        if (l > 0) {
            s += ":" + std::to_string(l);
            if (c > 0) s += ":" + std::to_string(c);
        }
        return s;
    }
    static std::string format(const std::string& f, int l, int c, const std::string& m) {
        return location(f, l, c) + ": " + m;
    }

private:
    void update_text() {
        text_ = format(file, line, column, message);
        for (const std::string& at : included_from) text_ += "\n  included from " + at;
    }
    std::string text_;
};

// A problem with the user's input that has no file position (bad option, unwritable output...).
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace phos
