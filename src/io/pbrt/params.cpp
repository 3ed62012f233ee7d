// Parameter-list validation and typed lookups.
#include "io/pbrt/params.h"

#include <cmath>
#include <limits>

#include "core/log.h"

namespace phos::io::pbrt {
namespace {

std::string canonical_type(const std::string& t) {
    if (t == "point") return "point3";
    if (t == "vector") return "vector3";
    if (t == "normal") return "normal3";
    if (t == "color") return "rgb";
    return t;
}

// Number of values one element of the type takes (0: any count).
int arity(const std::string& t) {
    if (t == "point2" || t == "vector2") return 2;
    if (t == "point3" || t == "vector3" || t == "normal3") return 3;
    if (t == "rgb") return 3;
    return 1;
}

}  // namespace

void ParamList::add(Param p) {
    p.type = canonical_type(p.type);
    const std::string& t = p.type;
    const bool numeric = t == "float" || t == "integer" || t == "point2" || t == "vector2" || t == "point3" ||
                         t == "vector3" || t == "normal3" || t == "rgb" || t == "blackbody";
    const bool textual = t == "string" || t == "texture";
    if (!numeric && !textual && t != "bool" && t != "spectrum")
        p.loc.fail("unknown parameter type '" + t + "' in " + p.declaration());
    for (const Param& q : params_)
        if (q.name == p.name)
            p.loc.fail("parameter '" + p.name + "' given twice (first at " + q.loc.str() + ")");
    const size_t count = p.numbers.size() + p.strings.size() + p.bools.size();
    if (count == 0) p.loc.fail("parameter " + p.declaration() + " has no values");
    if (t == "bool") {
        // Accept quoted "true"/"false" as well as bare words.
        for (const std::string& s : p.strings) {
            if (s != "true" && s != "false")
                p.loc.fail("bool parameter " + p.declaration() + " needs true or false");
            p.bools.push_back(s == "true");
        }
        p.strings.clear();
        if (!p.numbers.empty())
            p.loc.fail("bool parameter " + p.declaration() + " needs true or false, not numbers");
    } else if (numeric) {
        if (!p.strings.empty() || !p.bools.empty())
            p.loc.fail("parameter " + p.declaration() + " needs numbers, got " +
                       (p.bools.empty() ? "a string" : "a bool"));
        const int n = arity(t);
        if (p.numbers.size() % size_t(n) != 0)
            p.loc.fail("parameter " + p.declaration() + " needs a multiple of " + std::to_string(n) +
                       " values, got " + std::to_string(p.numbers.size()));
        if (t == "rgb" && p.numbers.size() != 3)
            p.loc.fail("rgb parameter " + p.declaration() + " needs 3 values");
        // pbrt-v4: a temperature; pbrt-v3: a temperature and a scale.
        if (t == "blackbody" && p.numbers.size() > 2)
            p.loc.fail("blackbody parameter " + p.declaration() +
                       " needs a temperature (and, as in pbrt-v3, a scale), got " +
                       std::to_string(p.numbers.size()) + " values");
        if (t == "integer")
            for (double v : p.numbers) {
                if (v != std::floor(v))
                    p.loc.fail("integer parameter " + p.declaration() + " has a non-integer value");
                // Read as int later (get_int, get_ints); a value beyond int cannot be converted.
                if (v < double(std::numeric_limits<int>::min()) ||
                    v > double(std::numeric_limits<int>::max()))
                    p.loc.fail("integer parameter " + p.declaration() + " has a value out of range");
            }
    } else if (textual) {
        if (!p.numbers.empty() || !p.bools.empty())
            p.loc.fail("parameter " + p.declaration() + " needs a quoted string");
    } else {  // spectrum: one name/filename, or wavelength-value pairs
        if (!p.bools.empty() || (!p.strings.empty() && !p.numbers.empty()) || p.strings.size() > 1)
            p.loc.fail("spectrum parameter " + p.declaration() + " needs a name or wavelength-value pairs");
        if (!p.numbers.empty() && p.numbers.size() % 2 != 0)
            p.loc.fail("spectrum parameter " + p.declaration() + " needs an even number of values");
    }
    params_.push_back(std::move(p));
}

const Param* ParamList::find(const std::string& name) const {
    for (const Param& p : params_)
        if (p.name == name) {
            p.used = true;
            return &p;
        }
    return nullptr;
}

const Param* ParamList::peek(const std::string& name) const {
    for (const Param& p : params_)
        if (p.name == name) return &p;
    return nullptr;
}

Param* ParamList::edit(const std::string& name) {
    for (Param& p : params_)
        if (p.name == name) return &p;
    return nullptr;
}

std::optional<Param> ParamList::take(const std::string& name) {
    for (auto it = params_.begin(); it != params_.end(); ++it)
        if (it->name == name) {
            Param p = std::move(*it);
            params_.erase(it);
            return p;
        }
    return std::nullopt;
}

void ParamList::rename(const std::string& from, const std::string& to) {
    for (Param& p : params_)
        if (p.name == from) {
            if (const Param* q = peek(to))
                p.loc.fail("parameter '" + to + "' given twice (first at " + q->loc.str() + ")");
            p.name = to;
            return;
        }
}

bool ParamList::has(const std::string& name) const {
    for (const Param& p : params_)
        if (p.name == name) return true;
    return false;
}

const Param* ParamList::typed(const std::string& name, std::initializer_list<const char*> types) const {
    const Param* p = find(name);
    if (!p) return nullptr;
    std::string want;
    for (const char* t : types) {
        if (p->type == t) return p;
        want += want.empty() ? t : std::string(" or ") + t;
    }
    p->loc.fail("parameter '" + name + "' should be " + want + ", not " + p->type);
}

namespace {
void expect_one(const Param& p, size_t n) {
    if (n != 1) p.loc.fail("parameter " + p.declaration() + " takes one value, got " + std::to_string(n));
}
}  // namespace

float ParamList::get_float(const std::string& name, float def) const {
    const Param* p = typed(name, {"float"});
    if (!p) return def;
    expect_one(*p, p->numbers.size());
    return float(p->numbers[0]);
}

int ParamList::get_int(const std::string& name, int def) const {
    const Param* p = typed(name, {"integer"});
    if (!p) return def;
    expect_one(*p, p->numbers.size());
    return int(p->numbers[0]);
}

bool ParamList::get_bool(const std::string& name, bool def) const {
    const Param* p = typed(name, {"bool"});
    if (!p) return def;
    expect_one(*p, p->bools.size());
    return p->bools[0];
}

std::string ParamList::get_string(const std::string& name, const std::string& def) const {
    const Param* p = typed(name, {"string"});
    if (!p) return def;
    expect_one(*p, p->strings.size());
    return p->strings[0];
}

Vec3 ParamList::get_point3(const std::string& name, Vec3 def) const {
    const Param* p = typed(name, {"point3", "vector3", "normal3"});
    if (!p) return def;
    expect_one(*p, p->numbers.size() / 3);
    return {float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2])};
}

std::vector<float> ParamList::get_floats(const std::string& name) const {
    const Param* p = typed(name, {"float"});
    if (!p) return {};
    return {p->numbers.begin(), p->numbers.end()};
}

std::vector<int> ParamList::get_ints(const std::string& name) const {
    const Param* p = typed(name, {"integer"});
    std::vector<int> out;
    if (p)
        for (double v : p->numbers) {
            if (std::fabs(v) > 2147483647.0) p->loc.fail("integer value out of range in " + p->declaration());
            out.push_back(int(v));
        }
    return out;
}

std::vector<std::string> ParamList::get_strings(const std::string& name) const {
    const Param* p = typed(name, {"string"});
    return p ? p->strings : std::vector<std::string>{};
}

std::vector<Vec3> ParamList::get_point3s(const std::string& name) const {
    const Param* p = typed(name, {"point3", "vector3", "normal3"});
    std::vector<Vec3> out;
    if (p)
        for (size_t i = 0; i + 2 < p->numbers.size(); i += 3)
            out.push_back({float(p->numbers[i]), float(p->numbers[i + 1]), float(p->numbers[i + 2])});
    return out;
}

std::vector<Vec2> ParamList::get_point2s(const std::string& name) const {
    const Param* p = typed(name, {"point2", "vector2", "float"});
    std::vector<Vec2> out;
    if (p) {
        // pbrt-v3 files give uv as a flat "float uv" array.
        if (p->numbers.size() % 2 != 0)
            p->loc.fail("parameter " + p->declaration() + " needs pairs of values");
        for (size_t i = 0; i + 1 < p->numbers.size(); i += 2)
            out.push_back({float(p->numbers[i]), float(p->numbers[i + 1])});
    }
    return out;
}

void ParamList::mark_all_used() const {
    for (const Param& p : params_) p.used = true;
}

void ParamList::report_unused(const std::string& directive, bool strict) const {
    for (const Param& p : params_) {
        if (p.used) continue;
        p.used = true;
        const std::string msg = directive + ": parameter " + p.declaration() + " is not used by phos";
        if (strict) p.loc.fail(msg + " (--strict)");
        log::warn(p.loc.str() + ": " + msg + " (ignored)");
    }
}

}  // namespace phos::io::pbrt
