// Tokeniser for phos's line-oriented text formats (`.scn`, `.scene` / `.mesh` / `.mat`): splits a
// file into white-space separated tokens with their 1-based line and column, drops `#` comments,
// rejects binary or non-UTF-8 content with a located error, and classifies numbers strictly.
#pragma once

#include <string>
#include <vector>

namespace phos::io::text {

struct Token {
    std::string text;
    int line = 0;
    int col = 0;  // 1-based, counted in characters (UTF-8 code points), a tab counts as one
};

struct LexedFile {
    std::vector<Token> tokens;
    int end_line = 1;  // position just past the last character, for "unexpected end of file"
    int end_col = 1;
};

// Tokenises `content`; `file` names it in errors. Throws ParseError on NUL/control bytes or
// malformed UTF-8 (at the offending byte).
LexedFile lex(const std::string& file, const std::string& content);

// Reads a whole file as bytes; throws InputError when it cannot be opened.
std::string read_file_bytes(const std::string& path);

// Classifies a token as a number (plain decimal: no nan, inf or hex floats); `value` is set when
// it is one. Overflow beyond float range is NotFinite, underflow is 0.
enum class NumberKind { Number, NotNumber, NotFinite };
NumberKind parse_number(const std::string& text, double& value);

}  // namespace phos::io::text
