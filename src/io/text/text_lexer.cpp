// The `.scn` tokeniser. Validation happens here, byte by byte, so a binary file or a file in a
// legacy 8-bit encoding fails at the first bad byte instead of producing nonsense tokens.
#include "io/text/text_lexer.h"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/format.h"

namespace phos::io::text {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// Length of the UTF-8 sequence starting at s[i] (1..4), or 0 when it is malformed (bad lead byte,
// missing/invalid continuation, overlong form, surrogate, or beyond U+10FFFF).
size_t utf8_length(const std::string& s, size_t i) {
    const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char c = byte(i);
    if (c < 0x80) return 1;
    size_t n = 0;
    unsigned cp = 0;
    if ((c & 0xE0) == 0xC0)
        n = 2, cp = c & 0x1Fu;
    else if ((c & 0xF0) == 0xE0)
        n = 3, cp = c & 0x0Fu;
    else if ((c & 0xF8) == 0xF0)
        n = 4, cp = c & 0x07u;
    else
        return 0;
    if (i + n > s.size()) return 0;
    for (size_t k = 1; k < n; ++k) {
        if ((byte(i + k) & 0xC0) != 0x80) return 0;
        cp = (cp << 6) | (byte(i + k) & 0x3Fu);
    }
    static const unsigned min_cp[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < min_cp[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
    return n;
}

}  // namespace

LexedFile lex(const std::string& file, const std::string& content) {
    LexedFile out;
    int line = 1, col = 1;
    size_t i = 0;
    // A UTF-8 byte-order mark is harmless; skip it without counting a column.
    if (content.compare(0, 3, "\xEF\xBB\xBF") == 0) i = 3;
    bool in_comment = false;
    Token current;
    bool in_token = false;
    const auto finish_token = [&] {
        if (in_token) out.tokens.push_back(std::move(current));
        current = Token{};
        in_token = false;
    };
    while (i < content.size()) {
        const unsigned char c = static_cast<unsigned char>(content[i]);
        if (c == '\n') {
            finish_token();
            in_comment = false;
            ++line, col = 1, ++i;
            continue;
        }
        const bool space = c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
        if (!space && (c < 0x20 || c == 0x7F))
            throw ParseError(
                file, line, col,
                "binary or control byte " + printf_string("0x%02X", c) + " (is this a text .scn file?)");
        const size_t n = utf8_length(content, i);
        if (n == 0)
            throw ParseError(
                file, line, col,
                "invalid UTF-8 byte " + printf_string("0x%02X", c) + " (save the file as UTF-8 or ASCII)");
        if (in_comment) {
            i += n, ++col;
            continue;
        }
        if (space) {
            finish_token();
        } else if (c == '#') {
            finish_token();
            in_comment = true;
        } else {
            if (!in_token) {
                current.line = line, current.col = col;
                in_token = true;
            }
            current.text.append(content, i, n);
        }
        i += n, ++col;
    }
    finish_token();
    out.end_line = line, out.end_col = col;
    return out;
}

std::string read_file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot open '" + path + "'");
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw InputError("error reading '" + path + "'");
    return ss.str();
}

NumberKind parse_number(const std::string& text, double& value) {
    // Plain decimal only: [+-] digits [. digits] [e [+-] digits], at least one mantissa digit.
    // strtod would also take "nan", "inf" and hex floats, which no scene means.
    size_t i = 0;
    const size_t n = text.size();
    if (i < n && (text[i] == '+' || text[i] == '-')) ++i;
    const size_t mantissa = i;
    size_t digits = 0;
    while (i < n && is_digit(text[i])) ++i, ++digits;
    if (i < n && text[i] == '.') {
        ++i;
        while (i < n && is_digit(text[i])) ++i, ++digits;
    }
    bool ok = digits > 0;
    if (ok && i < n && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        if (i < n && (text[i] == '+' || text[i] == '-')) ++i;
        size_t exp_digits = 0;
        while (i < n && is_digit(text[i])) ++i, ++exp_digits;
        ok = exp_digits > 0;
    }
    if (!ok || i != n) {
        const std::string l = lower(text.substr(mantissa));
        if (l == "nan" || l == "inf" || l == "infinity") return NumberKind::NotFinite;
        return NumberKind::NotNumber;
    }
    double v = 0;
    const char* first = text.data() + (text[0] == '+' ? 1 : 0);
    const auto [ptr, ec] = std::from_chars(first, text.data() + n, v);
    if (ec == std::errc::result_out_of_range) {
        // Underflow to zero is harmless; overflow is not a finite float.
        if (lower(text).find("e-") != std::string::npos) {
            value = 0;
            return NumberKind::Number;
        }
        return NumberKind::NotFinite;
    }
    if (ec != std::errc() || ptr != text.data() + n) return NumberKind::NotNumber;
    if (!std::isfinite(v) || std::fabs(v) > double(FLT_MAX)) return NumberKind::NotFinite;
    value = v;
    return NumberKind::Number;
}

}  // namespace phos::io::text
