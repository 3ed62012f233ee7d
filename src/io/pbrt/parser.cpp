// Directive-level parsing of pbrt-v4 files: argument lists, typed parameter lists, Include/Import
// (textual, relative to the including file, cycles rejected) and dispatch to a ParserTarget.
#include "io/pbrt/parser.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "io/pbrt/upgrade_v3.h"

namespace phos::io::pbrt {
namespace {

namespace fs = std::filesystem;

std::string canonical(const std::string& path) {
    std::error_code ec;
    const fs::path c = fs::weakly_canonical(fs::absolute(path), ec);
    return ec ? path : c.string();
}

class Parser {
public:
    explicit Parser(ParserTarget& target) : target_(target) {}

    void run(const std::string& path) {
        push(path, nullptr);
        for (;;) {
            Token t = next();
            if (t.kind == Token::Kind::End) {
                target_.end_of_files(t.loc);
                return;
            }
            if (t.kind != Token::Kind::Word)
                t.loc.fail(t.kind == Token::Kind::String
                               ? "expected a directive, found the string \"" + t.text + "\""
                               : "expected a directive, found '" + t.text + "'");
            directive(t);
        }
    }

private:
    void push(const std::string& path, const Loc* from) {
        const std::string canon = canonical(path);
        for (const std::string& open : open_files_)
            if (open == canon) from->fail("Include cycle: '" + path + "' is already being read");
        stack_.push_back(std::make_unique<Tokenizer>(path, from));
        open_files_.push_back(canon);
    }

    // The next token, continuing in the including file when an included one ends.
    Token next() {
        for (;;) {
            Token t = stack_.back()->next();
            if (t.kind != Token::Kind::End || stack_.size() == 1) return t;
            stack_.pop_back();
            open_files_.pop_back();
        }
    }
    const Token& peek() {
        while (stack_.back()->peek().kind == Token::Kind::End && stack_.size() > 1) {
            stack_.pop_back();
            open_files_.pop_back();
        }
        return stack_.back()->peek();
    }

    static bool to_number(const std::string& s, double& out) {
        const char* b = s.c_str();
        char* e = nullptr;
        out = std::strtod(b, &e);
        return e != b && *e == '\0';
    }

    float number(const Loc& directive_loc, const std::string& directive) {
        const Token t = next();
        double v = 0;
        if (t.kind == Token::Kind::End)
            directive_loc.fail(directive + ": unexpected end of file, expected a number");
        if (t.kind != Token::Kind::Word || !to_number(t.text, v))
            t.loc.fail(directive + ": expected a number, found '" + t.text + "'");
        if (!std::isfinite(v)) t.loc.fail(directive + ": '" + t.text + "' is not a finite number");
        return float(v);
    }
    Vec3 vec3(const Loc& loc, const std::string& d) {
        const float x = number(loc, d), y = number(loc, d), z = number(loc, d);
        return {x, y, z};
    }

    std::string string_arg(const Loc& directive_loc, const std::string& directive) {
        const Token t = next();
        if (t.kind == Token::Kind::End)
            directive_loc.fail(directive + ": unexpected end of file, expected a string");
        if (t.kind != Token::Kind::String)
            t.loc.fail(directive + ": expected a quoted string, found '" + t.text + "'");
        return t.text;
    }

    // 16 numbers, with or without brackets.
    void matrix(const Loc& loc, const std::string& d, float m[16]) {
        const bool bracket = peek().kind == Token::Kind::LBracket;
        Token open;
        if (bracket) open = next();
        for (int i = 0; i < 16; ++i) m[i] = number(loc, d);
        if (bracket) {
            const Token close = next();
            if (close.kind != Token::Kind::RBracket)
                open.loc.fail(d + ": missing ']' after 16 matrix values");
        }
    }

    void add_value(Param& p, const Token& v, const Loc* open_bracket) {
        if (v.kind == Token::Kind::String) {
            p.strings.push_back(v.text);
            return;
        }
        if (v.text == "true" || v.text == "false") {
            p.bools.push_back(v.text == "true");
            return;
        }
        double x = 0;
        if (!to_number(v.text, x)) {
            if (open_bracket)
                open_bracket->fail("missing ']' to close this '[' (found '" + v.text + "' at " + v.loc.str() +
                                   ")");
            v.loc.fail("expected a value for parameter " + p.declaration() + ", found '" + v.text + "'");
        }
        if (!std::isfinite(x)) v.loc.fail("'" + v.text + "' is not a finite number");
        p.numbers.push_back(x);
    }

    Param one_param() {
        const Token decl = next();
        std::istringstream ss(decl.text);
        Param p;
        std::string extra;
        ss >> p.type >> p.name >> extra;
        if (p.name.empty() || !extra.empty())
            decl.loc.fail("malformed parameter declaration \"" + decl.text + "\" (want \"type name\")");
        p.loc = decl.loc;
        const Token v = next();
        if (v.kind == Token::Kind::LBracket) {
            for (;;) {
                const Token x = next();
                if (x.kind == Token::Kind::RBracket) break;
                if (x.kind == Token::Kind::End || x.kind == Token::Kind::LBracket)
                    v.loc.fail("missing ']' to close this '['");
                add_value(p, x, &v.loc);
            }
        } else if (v.kind == Token::Kind::End || v.kind == Token::Kind::RBracket) {
            decl.loc.fail("parameter " + p.declaration() + " has no value");
        } else {
            add_value(p, v, nullptr);
        }
        return p;
    }

    ParamList params() {
        ParamList list;
        while (peek().kind == Token::Kind::String) list.add(one_param());
        return list;
    }

    void include(const Loc& loc, const std::string& d) {
        const std::string name = string_arg(loc, d);
        fs::path p(name);
        if (p.is_relative()) p = fs::path(loc.filename()).parent_path() / p;
        push(p.string(), &loc);  // errors in the file say "included from" this directive
    }

    void directive(const Token& t) {
        const std::string& d = t.text;
        const Loc& loc = t.loc;
        auto typed = [&](auto method) {
            std::string type = string_arg(loc, d);
            ParamList pl = params();
            upgrade_directive(d, type, pl, loc);  // pbrt-v3's names and parameters (upgrade_v3.h)
            if (d == "Attribute")
                record_attribute(type, pl, loc);
            else
                add_attributes(d, pl);
            (target_.*method)(type, pl, loc);
        };
        if (d == "AttributeBegin") {
            attribute_stack_.push_back(attributes_);
            target_.attribute_begin(loc);
        } else if (d == "AttributeEnd") {
            if (!attribute_stack_.empty()) {
                attributes_ = std::move(attribute_stack_.back());
                attribute_stack_.pop_back();
            }
            target_.attribute_end(loc);
        } else if (d == "Shape")
            typed(&ParserTarget::shape);
        else if (d == "Translate")
            target_.translate(vec3(loc, d), loc);
        else if (d == "Scale")
            target_.scale(vec3(loc, d), loc);
        else if (d == "Rotate") {
            const float a = number(loc, d);
            target_.rotate(a, vec3(loc, d), loc);
        } else if (d == "LookAt") {
            const Vec3 e = vec3(loc, d), l = vec3(loc, d), u = vec3(loc, d);
            target_.look_at(e, l, u, loc);
        } else if (d == "Transform" || d == "ConcatTransform") {
            float m[16];
            matrix(loc, d, m);
            if (d == "Transform")
                target_.transform(m, loc);
            else
                target_.concat_transform(m, loc);
        } else if (d == "Identity")
            target_.identity(loc);
        else if (d == "CoordinateSystem")
            target_.coordinate_system(string_arg(loc, d), loc);
        else if (d == "CoordSysTransform")
            target_.coord_sys_transform(string_arg(loc, d), loc);
        else if (d == "ReverseOrientation")
            target_.reverse_orientation(loc);
        else if (d == "Material")
            typed(&ParserTarget::material);
        else if (d == "MakeNamedMaterial")
            typed(&ParserTarget::make_named_material);
        else if (d == "NamedMaterial")
            target_.named_material(string_arg(loc, d), loc);
        else if (d == "Texture") {
            const std::string name = string_arg(loc, d);
            std::string type = string_arg(loc, d);
            const std::string cls = string_arg(loc, d);
            ParamList pl = params();
            upgrade_texture(type, cls, pl);
            add_attributes(d, pl);
            target_.texture(name, type, cls, pl, loc);
        } else if (d == "LightSource")
            typed(&ParserTarget::light_source);
        else if (d == "AreaLightSource")
            typed(&ParserTarget::area_light_source);
        else if (d == "Camera")
            typed(&ParserTarget::camera);
        else if (d == "Film")
            typed(&ParserTarget::film);
        else if (d == "PixelFilter")
            typed(&ParserTarget::pixel_filter);
        else if (d == "Sampler")
            typed(&ParserTarget::sampler);
        else if (d == "Integrator")
            typed(&ParserTarget::integrator);
        else if (d == "Accelerator")
            typed(&ParserTarget::accelerator);
        else if (d == "ColorSpace")
            target_.color_space(string_arg(loc, d), loc);
        else if (d == "Option") {
            if (peek().kind != Token::Kind::String) loc.fail("Option: expected \"type name\" value");
            const Param p = one_param();
            ParamList check;  // validates the type and values
            check.add(p);
            target_.option(check.all()[0], loc);
        } else if (d == "MakeNamedMedium")
            typed(&ParserTarget::make_named_medium);
        else if (d == "MediumInterface") {
            const std::string inside = string_arg(loc, d);
            std::string outside = inside;
            if (peek().kind == Token::Kind::String) outside = next().text;
            target_.medium_interface(inside, outside, loc);
        } else if (d == "WorldBegin")
            target_.world_begin(loc);
        else if (d == "TransformBegin")
            target_.transform_begin(loc);
        else if (d == "TransformEnd")
            target_.transform_end(loc);
        else if (d == "Attribute")
            typed(&ParserTarget::attribute);
        else if (d == "ObjectBegin") {
            attribute_stack_.push_back(attributes_);  // an object definition is an attribute block
            target_.object_begin(string_arg(loc, d), loc);
        } else if (d == "ObjectEnd") {
            if (!attribute_stack_.empty()) {
                attributes_ = std::move(attribute_stack_.back());
                attribute_stack_.pop_back();
            }
            target_.object_end(loc);
        } else if (d == "ObjectInstance")
            target_.object_instance(string_arg(loc, d), loc);
        else if (d == "Include" || d == "Import")
            include(loc, d);
        else if (d == "WorldEnd") {
            // pbrt-v3's end of the world block: nothing to do (pbrt-v4 ends it at the end of input).
        } else if (d == "TransformTimes") {
            number(loc, d);
            number(loc, d);
            target_.ignored_directive(d, loc);
        } else if (d == "ActiveTransform") {
            const Token w = next();
            if (w.kind != Token::Kind::Word ||
                (w.text != "StartTime" && w.text != "EndTime" && w.text != "All"))
                w.loc.fail("ActiveTransform: expected StartTime, EndTime or All");
            target_.ignored_directive(d + " " + w.text, loc);
        } else {
            loc.fail("unknown directive '" + d + "'");
        }
    }

    // pbrt-v4's Attribute defaults in effect, per kind ("shape", "light", "material", "medium",
    // "texture"), saved and restored with attribute blocks.
    void record_attribute(const std::string& kind, const ParamList& pl, const Loc& loc) {
        if (kind != "shape" && kind != "light" && kind != "material" && kind != "medium" && kind != "texture")
            loc.fail("Attribute: unknown target \"" + kind +
                     "\" (pbrt-v4 has \"shape\", \"light\", \"material\", \"medium\", \"texture\")");
        std::vector<Param>& list = attributes_[kind];
        for (const Param& p : pl.all()) {
            std::erase_if(list, [&](const Param& q) { return q.name == p.name; });  // the latest value wins
            list.push_back(p);
        }
    }
    void add_attributes(const std::string& directive, ParamList& pl) const {
        if (attributes_.empty() || !target_.applies_attributes()) return;
        const char* kind = directive == "Shape"                                           ? "shape"
                           : directive == "LightSource" || directive == "AreaLightSource" ? "light"
                           : directive == "Material" || directive == "MakeNamedMaterial"  ? "material"
                           : directive == "MakeNamedMedium"                               ? "medium"
                           : directive == "Texture"                                       ? "texture"
                                                                                          : nullptr;
        if (!kind) return;
        const auto it = attributes_.find(kind);
        if (it == attributes_.end()) return;
        for (Param p : it->second)
            if (!pl.peek(p.name)) {
                p.used = true;  // a default the directive need not read
                pl.add(std::move(p));
            }
    }

    ParserTarget& target_;
    std::map<std::string, std::vector<Param>> attributes_;
    std::vector<std::map<std::string, std::vector<Param>>> attribute_stack_;
    std::vector<std::unique_ptr<Tokenizer>> stack_;
    std::vector<std::string> open_files_;
};

}  // namespace

void parse_file(const std::string& path, ParserTarget& target) { Parser(target).run(path); }

}  // namespace phos::io::pbrt
