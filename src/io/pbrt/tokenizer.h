// Splits a pbrt-v4 scene file into tokens (bare words and numbers, quoted strings, brackets) and
// remembers where each one starts, so every later error can say file:line:col.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/error.h"

namespace phos::io::pbrt {

// A scene file as its tokens refer to it: the name, and where an Include or Import named it.
struct SourceFile {
    std::string name;
    std::vector<std::string> included_from;  // innermost first: "scene.pbrt:3:9"
};

// A position in a scene file (1-based line and column).
struct Loc {
    std::shared_ptr<const SourceFile> file;
    int line = 0;
    int col = 0;

    const std::string& filename() const;
    std::string str() const;  // "file:line:col"
    // Throws ParseError here, naming the Include/Import lines that led to this file.
    [[noreturn]] void fail(const std::string& message) const;
    // Adds this place and the includes that led to it to an error from a file named here (a PLY mesh).
    void add_to(ParseError& e) const;
};

struct Token {
    enum class Kind { Word, String, LBracket, RBracket, End };
    Kind kind = Kind::End;
    std::string text;  // the word, or a string's contents with escapes resolved
    Loc loc;
};

class Tokenizer {
public:
    // Reads the whole file; throws ParseError at `included_from` (or at the file itself) if it
    // cannot be read.
    Tokenizer(const std::string& path, const Loc* included_from);

    Token next();
    const Token& peek();
    const std::string& path() const { return file_->name; }

private:
    Token scan();

    std::shared_ptr<const SourceFile> file_;
    std::string src_;
    size_t pos_ = 0;
    int line_ = 1;
    int col_ = 1;
    bool has_peeked_ = false;
    Token peeked_;
};

}  // namespace phos::io::pbrt
