// Error types. ParseError carries the location of malformed input (file:line:col); InputError is a
// bad option or unusable input with no location. The CLI turns both into exit code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace phos {

struct ParseError : std::runtime_error {
    std::string file;
    int line = 0;
    int column = 0;
    std::string message;

    ParseError(std::string file_, int line_, int column_, std::string message_)
        : std::runtime_error(format(file_, line_, column_, message_)),
          file(std::move(file_)),
          line(line_),
          column(column_),
          message(std::move(message_)) {}

    static std::string format(const std::string& f, int l, int c, const std::string& m) {
        std::string s = f;
        if (l > 0) {
            s += ":" + std::to_string(l);
            if (c > 0) s += ":" + std::to_string(c);
        }
        return s + ": " + m;
    }
};

// A problem with the user's input that has no file position (bad option, unwritable output...).
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace phos
