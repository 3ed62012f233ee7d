// pbrt tokenizer: comments run from '#' to the end of the line; strings are double-quoted with C
// escapes and may not span lines; everything else between blanks is a word.
#include "io/pbrt/tokenizer.h"

#include <fstream>
#include <sstream>

#include "core/error.h"
#include "io/gzip/gzip_file.h"

namespace phos::io::pbrt {

const std::string& Loc::filename() const {
    static const std::string none;
    return file ? file->name : none;
}

std::string Loc::str() const {
    std::string s = filename();
    if (line > 0) s += ":" + std::to_string(line);
    if (line > 0 && col > 0) s += ":" + std::to_string(col);
    return s;
}

void Loc::fail(const std::string& message) const {
    throw ParseError(filename(), line, col, message, file ? file->included_from : std::vector<std::string>{});
}

void Loc::add_to(ParseError& e) const {
    e.add_included_from(filename(), line, col);
    if (file)
        for (const std::string& place : file->included_from) e.add_included_from(place);
}

namespace {
std::shared_ptr<const SourceFile> source_file(const std::string& path, const Loc* included_from) {
    SourceFile f;
    f.name = path;
    if (included_from) {
        f.included_from.push_back(included_from->str());
        if (included_from->file)
            f.included_from.insert(f.included_from.end(), included_from->file->included_from.begin(),
                                   included_from->file->included_from.end());
    }
    return std::make_shared<const SourceFile>(std::move(f));
}
}  // namespace

Tokenizer::Tokenizer(const std::string& path, const Loc* included_from)
    : file_(source_file(path, included_from)) {
    bool opened = false;
    try {
        opened = read_maybe_gzip(path, src_);  // a .pbrt.gz file is decompressed whole
    } catch (ParseError& e) {                  // a corrupt stream: say where it was included
        if (included_from) included_from->add_to(e);
        throw;
    }
    if (!opened) {
        if (included_from) included_from->fail("cannot open included file '" + path + "'");
        throw ParseError(path, 0, 0, "cannot open scene file");
    }
}

const Token& Tokenizer::peek() {
    if (!has_peeked_) {
        peeked_ = scan();
        has_peeked_ = true;
    }
    return peeked_;
}

Token Tokenizer::next() {
    if (has_peeked_) {
        has_peeked_ = false;
        return std::move(peeked_);
    }
    return scan();
}

Token Tokenizer::scan() {
    // Skip blanks and comments.
    while (pos_ < src_.size()) {
        const char c = src_[pos_];
        if (c == '\n') {
            ++pos_, ++line_, col_ = 1;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            ++pos_, ++col_;
        } else if (c == '#') {
            while (pos_ < src_.size() && src_[pos_] != '\n') ++pos_;
        } else {
            break;
        }
    }
    Token t;
    t.loc = Loc{file_, line_, col_};
    if (pos_ >= src_.size()) return t;  // End
    const char c = src_[pos_];
    if (c == '[' || c == ']') {
        t.kind = c == '[' ? Token::Kind::LBracket : Token::Kind::RBracket;
        t.text = std::string(1, c);
        ++pos_, ++col_;
        return t;
    }
    if (c == '"') {
        t.kind = Token::Kind::String;
        ++pos_, ++col_;
        for (;;) {
            if (pos_ >= src_.size() || src_[pos_] == '\n') t.loc.fail("unterminated string");
            char d = src_[pos_++];
            ++col_;
            if (d == '"') break;
            if (d == '\\') {
                if (pos_ >= src_.size() || src_[pos_] == '\n') t.loc.fail("unterminated string");
                const char e = src_[pos_++];
                ++col_;
                switch (e) {
                    case 'n':
                        d = '\n';
                        break;
                    case 't':
                        d = '\t';
                        break;
                    case 'r':
                        d = '\r';
                        break;
                    case 'b':
                        d = '\b';
                        break;
                    case 'f':
                        d = '\f';
                        break;
                    case '\\':
                        d = '\\';
                        break;
                    case '\'':
                        d = '\'';
                        break;
                    case '"':
                        d = '"';
                        break;
                    default:
                        Loc{file_, line_, col_ - 2}.fail(std::string("unknown escape sequence '\\") + e +
                                                         "'");
                }
            }
            t.text.push_back(d);
        }
        return t;
    }
    t.kind = Token::Kind::Word;
    const size_t start = pos_;
    while (pos_ < src_.size()) {
        const char d = src_[pos_];
        if (d == ' ' || d == '\t' || d == '\n' || d == '\r' || d == '\f' || d == '\v' || d == '"' ||
            d == '[' || d == ']' || d == '#')
            break;
        ++pos_, ++col_;
    }
    t.text.assign(src_, start, pos_ - start);
    return t;
}

}  // namespace phos::io::pbrt
