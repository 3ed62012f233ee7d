// Declarative option tables: one entry per option holds its flag, the field it fills, its default
// (the field's own initialiser), its valid range, its help text and what it affects. The same
// entries drive the command line (app/lib/cli.cpp), validation (one wording, naming the option),
// `--help` with defaults, a checkpoint's option list, scene-file integrator parameters (pbrt
// `Integrator` parameters map onto entries by name) and the generated docs/options.md. Code that
// uses the options receives the plain struct and never mentions a flag.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace phos::options {

// A value that cannot be stored: the message names the value, not the option (the caller adds
// where it came from: "--alpha", or a scene file's location and parameter).
struct ValueError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// What an option changes. `Image`: the pixels (part of a checkpoint's identity); `Budget`: how much
// work is done (a resumed render may change it); `None`: neither (output names, threads, messages).
enum class Effect { Image, Budget, None };

// Closed or open numeric interval, printed as "[1, 65536]", "(0, 1]", "[0, inf)".
struct Range {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = false, hi_open = false;
    bool contains(double v) const;
    std::string text() const;
};
Range between(double lo, double hi);  // [lo, hi]
Range at_least(double lo);            // [lo, inf)
Range positive();                     // (0, inf)

// The integrators an option applies to, as bits over their numbers. Core cannot know the
// integrators: their registry (integrators/registry.h) numbers them, builds these sets and names
// them in text. The empty set means every integrator.
struct IntegratorSet {
    uint32_t bits = 0;
    bool empty() const { return bits == 0; }
    bool contains(unsigned integrator) const { return integrator < 32 && (bits >> integrator & 1u) != 0; }
};

// One word of a word-valued option and the value it stands for (an enumerator).
template <class E>
struct Choice {
    E value;
    std::string name;
};
template <class E>
using Choices = std::vector<Choice<E>>;

// "a|b|c": the words of `choices`, for help, docs and messages.
template <class E>
std::string choice_list(const Choices<E>& choices) {
    std::string list;
    for (const Choice<E>& c : choices) list += (list.empty() ? "" : "|") + c.name;
    return list;
}
// The word for `value` (its number when `choices` has none).
template <class E>
std::string choice_name(const Choices<E>& choices, E value) {
    for (const Choice<E>& c : choices)
        if (c.value == value) return c.name;
    return std::to_string(static_cast<long long>(value));
}
// The value `word` stands for; ValueError "'c' is not one of a|b" when it is none of them.
template <class E>
E parse_choice(const Choices<E>& choices, const std::string& word) {
    for (const Choice<E>& c : choices)
        if (c.name == word) return c.value;
    throw ValueError("'" + word + "' is not one of " + choice_list(choices));
}

struct Option {
    std::string name;                  // long name without dashes: "photons-per-iter"
    std::vector<std::string> aliases;  // further long names accepted for the same option
    std::string short_name;            // one letter ("o" for -o), or empty
    std::string negation;              // flags only: a long name that clears it ("no-projection-maps")
    bool flag = false;                 // takes no value; present = `flag_value`
    bool flag_value = true;
    int arity = 1;           // values taken (flags: 0)
    std::string value_name;  // "N", "SECONDS", "W H"
    std::string help;
    std::string pbrt;          // pbrt-v4 Integrator parameter that maps onto it ("" = none)
    std::string pbrt_unset;    // a value of that parameter meaning "pbrt's default" (kept as ours)
    std::string default_text;  // shown instead of the field's value when that needs words
    std::string range_text;    // accepted values, for help and docs ("(0, 1]", "a|b|c")
    Effect effect = Effect::Image;
    IntegratorSet applies_to;  // integrators it matters for (empty: all)
    bool hidden = false;       // accepted but left out of --help and the docs (old spellings)

    // Type-erased access to the field inside the table's struct (`void*` is that struct).
    std::function<void(void*, const std::vector<std::string>&)> set;  // parse + check; ValueError
    std::function<std::string(const void*)> get;                      // current value as text
    std::function<void(const void*)> check;                           // stored value valid? ValueError

    std::string flag_name() const { return "--" + name; }
    // True if the option matters for the integrator numbered `integrator` (IntegratorSet).
    bool applies(unsigned integrator) const { return applies_to.empty() || applies_to.contains(integrator); }
};

// The options of one subsystem (film, camera, photon maps, progressive...), all filling fields of
// one struct type. `defaults` is a default-constructed instance: its values are the defaults.
struct Table {
    std::string title;  // section name in --help and docs ("Photon map")
    std::string about;  // one line for the docs
    std::vector<Option> options;
    std::shared_ptr<const void> defaults;

    const Option* find(const std::string& name) const;  // by name or alias, without dashes
    const Option* find_pbrt(const std::string& pbrt_name) const;
    std::string default_text(const Option& o) const;  // what --help shows as the default
};

// Parsing helpers with the tables' wording ("'abc' is not a number", "0 is not in (0, 1]").
double parse_number(const std::string& text);
long long parse_integer(const std::string& text);
unsigned long long parse_unsigned(const std::string& text);
bool parse_bool(const std::string& text);
// Shortest text that reads back to `v` (to float(v) when `as_float`); whole numbers without a point.
std::string format_number(double v, bool as_float = false);

// Builds a Table over struct S. Fields are given as member pointers, or for nested fields as
// generic lambdas `[](auto& s) -> auto& { return s.global.photons; }`.
template <class S>
class TableBuilder {
    // The field `access` names in `s` (const or not): a member pointer, or a generic lambda
    // `[](auto& s) -> auto& { return s.a.b; }` for nested fields.
    template <class Obj, class Access>
    static decltype(auto) field_of(const Access& access, Obj& s) {
        if constexpr (std::is_member_object_pointer_v<Access>)
            return (s.*access);
        else
            return access(s);
    }
    // The type of that field.
    template <class Access>
    using Field = std::remove_cvref_t<decltype(field_of(std::declval<const Access&>(), std::declval<S&>()))>;

public:
    TableBuilder(std::string title, std::string about) {
        table_.title = std::move(title);
        table_.about = std::move(about);
        table_.defaults = std::make_shared<const S>();
    }

    // A number (the field's type: integral or floating) within `range`.
    template <class Access>
    Option& number(std::string name, Access access, std::string value_name, Range range, std::string help) {
        Option o = base(std::move(name), std::move(value_name), std::move(help));
        o.range_text = range.text();
        using T = std::remove_cvref_t<decltype(field_of(access, std::declval<S&>()))>;
        o.set = [access, range](void* s, const std::vector<std::string>& v) {
            T& field = field_of(access, object(s));
            if constexpr (std::is_unsigned_v<T>) {
                const unsigned long long x = parse_unsigned(v.at(0));
                check_range(double(x), range);
                field = T(x);
            } else if constexpr (std::is_integral_v<T>) {
                const long long x = parse_integer(v.at(0));
                check_range(double(x), range);
                field = T(x);
            } else {
                const double x = parse_number(v.at(0));
                check_range(x, range);
                field = T(x);
            }
        };
        o.get = [access](const void* s) {
            if constexpr (std::is_integral_v<T>)
                return std::to_string(field_of(access, object(s)));
            else
                return format_number(double(field_of(access, object(s))), std::is_same_v<T, float>);
        };
        o.check = [access, range](const void* s) { check_range(double(field_of(access, object(s))), range); };
        return add(std::move(o));
    }

    // A switch: present sets the field to `value`; `negation` (optional) sets the opposite.
    template <class Access>
    Option& flag(std::string name, Access access, std::string help, bool value = true,
                 std::string negation = "") {
        Option o = base(std::move(name), "", std::move(help));
        o.flag = true;
        o.flag_value = value;
        o.arity = 0;
        o.negation = std::move(negation);
        o.set = [access](void* s, const std::vector<std::string>& v) {
            field_of(access, object(s)) = v.empty() ? true : parse_bool(v[0]);
        };
        o.get = [access](const void* s) -> std::string {
            return field_of(access, object(s)) ? "true" : "false";
        };
        o.check = [](const void*) {};
        return add(std::move(o));
    }

    // A word from `choices`, stored as the value it stands for (an enum field).
    template <class Access>
    Option& choice(std::string name, Access access, Choices<Field<Access>> choices, std::string help) {
        Option o = base(std::move(name), "NAME", std::move(help));
        o.range_text = choice_list(choices);
        o.set = [access, choices](void* s, const std::vector<std::string>& v) {
            field_of(access, object(s)) = parse_choice(choices, v.at(0));
        };
        o.get = [access, choices](const void* s) {
            return choice_name(choices, field_of(access, object(s)));
        };
        o.check = [access, choices](const void* s) {
            const auto value = field_of(access, object(s));
            for (const Choice<Field<Access>>& c : choices)
                if (c.value == value) return;
            throw ValueError(choice_name(choices, value) + " is not one of " + choice_list(choices));
        };
        return add(std::move(o));
    }

    // Free text (a path...).
    template <class Access>
    Option& text(std::string name, Access access, std::string value_name, std::string help) {
        Option o = base(std::move(name), std::move(value_name), std::move(help));
        o.set = [access](void* s, const std::vector<std::string>& v) {
            field_of(access, object(s)) = v.at(0);
        };
        o.get = [access](const void* s) { return field_of(access, object(s)); };
        o.check = [](const void*) {};
        return add(std::move(o));
    }

    // Anything else: `set` parses `arity` words into the struct (throwing ValueError), `get` prints
    // the stored value, `check` validates it (may be empty).
    Option& custom(std::string name, std::string value_name, int arity, std::string help,
                   std::function<void(S&, const std::vector<std::string>&)> set,
                   std::function<std::string(const S&)> get, std::function<void(const S&)> check = {}) {
        Option o = base(std::move(name), std::move(value_name), std::move(help));
        o.arity = arity;
        o.set = [set](void* s, const std::vector<std::string>& v) { set(*static_cast<S*>(s), v); };
        o.get = [get](const void* s) { return get(*static_cast<const S*>(s)); };
        o.check = [check](const void* s) {
            if (check) check(*static_cast<const S*>(s));
        };
        return add(std::move(o));
    }

    Option& last() { return table_.options.back(); }
    std::vector<Option>& options() { return table_.options; }
    Table build() { return std::move(table_); }

    static void check_range(double v, const Range& r) {
        if (!r.contains(v)) throw ValueError(format_number(v) + " is not in " + r.text());
    }

private:
    static S& object(void* s) { return *static_cast<S*>(s); }
    static const S& object(const void* s) { return *static_cast<const S*>(s); }
    static Option base(std::string name, std::string value_name, std::string help) {
        Option o;
        o.name = std::move(name);
        o.value_name = std::move(value_name);
        o.help = std::move(help);
        return o;
    }
    Option& add(Option o) {
        table_.options.push_back(std::move(o));
        return table_.options.back();
    }
    Table table_;
};

// The message for a value of option `o` that was refused: "--alpha: 0 is not in (0, 1]".
std::string option_error(const Option& o, const std::string& why);

// `table` with only the options whose names `keep` accepts: the same entries (names, checks, help),
// for a command that takes part of another's options.
Table subset(const Table& table, const std::function<bool(const std::string& name)>& keep);

// Checks every option's stored value in `object` (a struct of the table's type); throws ValueError
// with option_error's wording for the first invalid one.
void validate(const Table& table, const void* object);

// (flag, value) for each option of `table` whose effect is `effect`, as stored in `object`; with
// `integrator` (its number, IntegratorSet), only the options that apply to it.
std::vector<std::pair<std::string, std::string>> values(const Table& table, const void* object, Effect effect,
                                                        std::optional<unsigned> integrator = std::nullopt);

}  // namespace phos::options
