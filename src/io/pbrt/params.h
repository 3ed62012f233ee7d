// Typed parameter lists of pbrt directives ("float radius" [ 1 ]). Lookups check the declared type
// and mark a parameter as used, so the builder can report every parameter nothing read.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/vec.h"
#include "io/pbrt/tokenizer.h"

namespace phos::io::pbrt {

struct Param {
    std::string type;  // canonical: float integer bool string texture point2 vector2 point3 vector3
                       // normal3 rgb spectrum blackbody
    std::string name;
    Loc loc;
    std::vector<double> numbers;
    std::vector<std::string> strings;
    std::vector<bool> bools;
    mutable bool used = false;

    std::string declaration() const { return "\"" + type + " " + name + "\""; }
};

class ParamList {
public:
    // Adds a parameter; fails at its location if the type is unknown, a value has the wrong kind
    // or count, or the name is given twice.
    void add(Param p);

    // The parameter called `name` (marked used), or nullptr.
    const Param* find(const std::string& name) const;
    bool has(const std::string& name) const;

    // Single values: `def` if absent. The parameter must have the matching type and one value.
    float get_float(const std::string& name, float def) const;
    int get_int(const std::string& name, int def) const;
    bool get_bool(const std::string& name, bool def) const;
    std::string get_string(const std::string& name, const std::string& def) const;
    Vec3 get_point3(const std::string& name, Vec3 def) const;  // point3 / vector3 / normal3

    // Arrays: empty if absent.
    std::vector<float> get_floats(const std::string& name) const;
    std::vector<int> get_ints(const std::string& name) const;
    std::vector<std::string> get_strings(const std::string& name) const;
    std::vector<Vec3> get_point3s(const std::string& name) const;  // point3 / vector3 / normal3
    std::vector<Vec2> get_point2s(const std::string& name) const;  // point2 / vector2

    // Editing, for the pbrt-v3 rules (upgrade_v3.h): the parameter called `name` (not marked used),
    // or nullptr; removes it and returns it; renames it (keeping its type and values).
    const Param* peek(const std::string& name) const;
    Param* edit(const std::string& name);
    std::optional<Param> take(const std::string& name);
    void rename(const std::string& from, const std::string& to);
    // Marks everything used (after one warning covering a whole unsupported directive).
    void mark_all_used() const;
    // One warning (or, if `strict`, a ParseError) per parameter that no lookup read.
    void report_unused(const std::string& directive, bool strict) const;

    const std::vector<Param>& all() const { return params_; }

private:
    const Param* typed(const std::string& name, std::initializer_list<const char*> types) const;
    std::vector<Param> params_;
};

}  // namespace phos::io::pbrt
