// Option tables (see option_table.h): parsing with one wording, ranges, lookups, validation.
#include "core/option_table.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "core/format.h"

namespace phos::options {

bool Range::contains(double v) const {
    if (std::isnan(v)) return false;
    if (lo_open ? !(v > lo) : !(v >= lo)) return false;
    if (hi_open ? !(v < hi) : !(v <= hi)) return false;
    return true;
}

std::string Range::text() const {
    auto end = [](double v) {
        return std::isinf(v) ? std::string(v < 0 ? "-inf" : "inf") : format_number(v);
    };
    return std::string(lo_open || std::isinf(lo) ? "(" : "[") + end(lo) + ", " + end(hi) +
           (hi_open || std::isinf(hi) ? ")" : "]");
}

Range between(double lo, double hi) { return Range{lo, hi, false, false}; }
Range at_least(double lo) { return Range{lo, std::numeric_limits<double>::infinity(), false, true}; }
Range positive() { return Range{0, std::numeric_limits<double>::infinity(), true, true}; }

const Option* Table::find(const std::string& name) const {
    for (const Option& o : options) {
        if (o.name == name || o.negation == name) return &o;
        for (const auto& a : o.aliases)
            if (a == name) return &o;
    }
    return nullptr;
}

const Option* Table::find_pbrt(const std::string& pbrt_name) const {
    for (const Option& o : options)
        if (!o.pbrt.empty() && o.pbrt == pbrt_name) return &o;
    return nullptr;
}

std::string Table::default_text(const Option& o) const {
    if (!o.default_text.empty()) return o.default_text;
    if (o.flag) return o.get(defaults.get()) == (o.flag_value ? "true" : "false") ? "on" : "off";
    return o.get(defaults.get());
}

double parse_number(const std::string& text) {
    const char* begin = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    if (text.empty() || end != begin + text.size() || std::isspace(static_cast<unsigned char>(text[0])))
        throw ValueError("'" + text + "' is not a number");
    if (!std::isfinite(v) || errno == ERANGE) throw ValueError("'" + text + "' is not a finite number");
    return v;
}

long long parse_integer(const std::string& text) {
    const char* begin = text.c_str();
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(begin, &end, 10);
    if (text.empty() || end != begin + text.size() || std::isspace(static_cast<unsigned char>(text[0]))) {
        // "1.5" or "1e3" are numbers but not whole ones: say so.
        try {
            parse_number(text);
        } catch (const ValueError&) {
            throw ValueError("'" + text + "' is not a number");
        }
        throw ValueError("'" + text + "' is not a whole number");
    }
    if (errno == ERANGE) throw ValueError("'" + text + "' is too large");
    return v;
}

unsigned long long parse_unsigned(const std::string& text) {
    if (!text.empty() && text[0] == '-') {
        const long long v = parse_integer(text);  // reports non-numbers first
        throw ValueError(std::to_string(v) + " is negative");
    }
    const char* begin = text.c_str();
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(begin, &end, 10);
    if (text.empty() || end != begin + text.size() || std::isspace(static_cast<unsigned char>(text[0]))) {
        parse_integer(text);  // throws the right wording
        throw ValueError("'" + text + "' is not a whole number");
    }
    if (errno == ERANGE) throw ValueError("'" + text + "' is too large");
    return v;
}

bool parse_bool(const std::string& text) {
    if (text == "true" || text == "on" || text == "1" || text == "yes") return true;
    if (text == "false" || text == "off" || text == "0" || text == "no") return false;
    throw ValueError("'" + text + "' is not true or false");
}

std::string format_number(double v, bool as_float) {
    if (v == std::floor(v) && std::fabs(v) < 1e15) {
        return printf_string("%.0f", v);
    }
    // Shortest form that reads back to the same float or double.
    std::string s;
    for (int p = 6; p <= 17; ++p) {
        s = printf_string("%.*g", p, v);
        const double back = std::strtod(s.c_str(), nullptr);
        if (as_float ? float(back) == float(v) : back == v) break;
    }
    return s;
}

std::string option_error(const Option& o, const std::string& why) { return o.flag_name() + ": " + why; }

Table subset(const Table& table, const std::function<bool(const std::string& name)>& keep) {
    Table t = table;
    std::erase_if(t.options, [&](const Option& o) { return !keep(o.name); });
    return t;
}

void validate(const Table& table, const void* object) {
    for (const Option& o : table.options) {
        try {
            o.check(object);
        } catch (const ValueError& e) {
            throw ValueError(option_error(o, e.what()));
        }
    }
}

std::vector<std::pair<std::string, std::string>> values(const Table& table, const void* object, Effect effect,
                                                        std::optional<unsigned> integrator) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const Option& o : table.options)
        if (o.effect == effect && (!integrator || o.applies(*integrator)))
            out.emplace_back(o.flag_name(), o.get(object));
    return out;
}

}  // namespace phos::options
