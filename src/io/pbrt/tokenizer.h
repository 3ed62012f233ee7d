// Splits a pbrt-v4 scene file into tokens (bare words and numbers, quoted strings, brackets) and
// remembers where each one starts, so every later error can say file:line:col.
#pragma once

#include <memory>
#include <string>

namespace phos::io::pbrt {

// A position in a scene file (1-based line and column).
struct Loc {
    std::shared_ptr<const std::string> file;
    int line = 0;
    int col = 0;

    const std::string& filename() const;
    std::string str() const;                                   // "file:line:col"
    [[noreturn]] void fail(const std::string& message) const;  // throws ParseError here
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
    const std::string& path() const { return *file_; }

private:
    Token scan();

    std::shared_ptr<const std::string> file_;
    std::string src_;
    size_t pos_ = 0;
    int line_ = 1;
    int col_ = 1;
    bool has_peeked_ = false;
    Token peeked_;
};

}  // namespace phos::io::pbrt
