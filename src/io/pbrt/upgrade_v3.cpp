// The pbrt-v3 rules (see upgrade_v3.h); each follows what pbrt-v4's --upgrade writes.
#include "io/pbrt/upgrade_v3.h"

#include <cmath>

#include "core/log.h"

namespace phos::io::pbrt {
namespace {

// A float parameter made by a rule, located where the parameter it replaces was.
Param float_param(const std::string& name, double value, const Loc& loc) {
    Param p;
    p.type = "float";
    p.name = name;
    p.loc = loc;
    p.numbers = {value};
    return p;
}

Param string_param(const std::string& name, std::vector<std::string> values, const Loc& loc) {
    Param p;
    p.type = "string";
    p.name = name;
    p.loc = loc;
    p.strings = std::move(values);
    return p;
}

bool grey(const Param& p) {
    return p.type == "rgb" && p.numbers.size() == 3 && p.numbers[0] == p.numbers[1] &&
           p.numbers[1] == p.numbers[2];
}

// Drops a pbrt-v3 coefficient that pbrt-v4's material no longer has; `expected` is the value that
// makes the drop exact (e.g. glass's Kr = 1): any other value is said once, as pbrt-v4 says it.
void drop(ParamList& params, const std::string& name, double expected, const std::string& material) {
    const std::optional<Param> p = params.take(name);
    if (!p) return;
    if (!(grey(*p) && p->numbers[0] == expected) && !(p->type == "float" && p->numbers[0] == expected))
        log::warn(p->loc.str() + ": pbrt-v3 " + p->declaration() + " has no pbrt-v4 counterpart in \"" +
                  material + "\" (ignored, as pbrt-v4's upgrade does)");
}

// True when `name` is given as the constant grey `value` (pbrt-v3 plastic/uber with Ks = 0: diffuse).
bool is_constant(const ParamList& params, const std::string& name, double value) {
    const Param* p = params.peek(name);
    return p && ((grey(*p) && p->numbers[0] == value) || (p->type == "float" && p->numbers[0] == value));
}

void upgrade_material(std::string& type, ParamList& params, const Loc& loc) {
    if ((type == "glass" || type == "uber") && params.peek("index")) {
        if (params.peek("eta"))
            params.peek("index")->loc.fail("\"" + type + "\" has both \"index\" and \"eta\"");
        params.rename("index", "eta");
    }
    params.rename("bumpmap", "displacement");
    if (type == "matte") {
        type = "diffuse";
        params.rename("Kd", "reflectance");
        params.take("sigma");  // Oren-Nayar roughness: pbrt-v4's diffuse is Lambertian
    } else if (type == "plastic" || type == "uber") {
        const bool no_coat = is_constant(params, "Ks", 0);
        const std::string was = type;
        type = no_coat ? "diffuse" : "coateddiffuse";
        if (no_coat) {
            params.take("roughness");
            params.take("eta");
        }
        drop(params, "Ks", no_coat ? 0 : -1, was);  // the coat's colour: pbrt-v4's coat is clear
        if (was == "uber") {
            drop(params, "Kr", 0, was);
            drop(params, "Kt", 0, was);
            if (const std::optional<Param> o = params.take("opacity"); o && !(grey(*o) && o->numbers[0] == 1))
                log::warn(o->loc.str() +
                          ": pbrt-v3 uber's \"opacity\" is not rendered (the surface is opaque)");
        }
        params.rename("Kd", "reflectance");
    } else if (type == "substrate") {
        type = "coateddiffuse";
        drop(params, "Ks", 1, "substrate");
        params.rename("Kd", "reflectance");
    } else if (type == "glass") {
        type = "dielectric";
        drop(params, "Kr", 1, "glass");
        drop(params, "Kt", 1, "glass");
    } else if (type == "metal") {
        type = "conductor";
        drop(params, "Kr", 1, "metal");
    } else if (type == "mirror") {
        // pbrt-v4's upgrade: a smooth silver conductor.
        type = "conductor";
        drop(params, "Kr", 0, "mirror");
        params.add(float_param("roughness", 0, loc));
        Param eta = string_param("eta", {"metal-Ag-eta"}, loc), k = string_param("k", {"metal-Ag-k"}, loc);
        eta.type = k.type = "spectrum";
        params.add(eta);
        params.add(k);
    } else if (type == "translucent") {
        type = "diffusetransmission";
        params.rename("Kd", "transmittance");
        drop(params, "reflect", 0, "translucent");
        drop(params, "transmit", 1, "translucent");
        drop(params, "Ks", 0, "translucent");
        params.take("roughness");
    } else if (type == "kdsubsurface") {
        type = "subsurface";
        params.rename("Kd", "reflectance");
    } else if (type == "disney") {
        type = "diffuse";
        params.rename("color", "reflectance");
    } else if (type == "mix" && !params.peek("materials")) {
        const std::optional<Param> m1 = params.take("namedmaterial1"), m2 = params.take("namedmaterial2");
        if (!m1 || !m2 || m1->strings.size() != 1 || m2->strings.size() != 1)
            loc.fail(
                "Material \"mix\": needs \"string namedmaterial1\" and \"string namedmaterial2\" (pbrt-v3) "
                "or \"string materials\"");
        // pbrt-v3 weights namedmaterial1 by amount, pbrt-v4 its second material: the order swaps.
        params.add(string_param("materials", {m2->strings[0], m1->strings[0]}, m1->loc));
        if (const Param* a = params.peek("amount"); a && a->type == "rgb") {
            const Param amount = *params.take("amount");
            const double avg = (amount.numbers[0] + amount.numbers[1] + amount.numbers[2]) / 3;
            if (!grey(amount))
                log::warn(amount.loc.str() + ": \"mix\" amount " + amount.declaration() +
                          " is coloured; its average is used (as pbrt-v4's upgrade does)");
            params.add(float_param("amount", avg, amount.loc));
        }
    } else if (type == "none") {
        type = "interface";
    }
}

void upgrade_light(std::string& type, ParamList& params, const Loc& loc, bool area) {
    if (area && type == "area") type = "diffuse";
    params.take(area ? "nsamples" : "samples");
    double factor = 1;
    if (const Param* s = params.peek("scale"); s && s->type != "float") {
        const Param scale = *params.take("scale");
        if (grey(scale)) {
            factor = scale.numbers[0];
        } else {
            // A coloured scale multiplies an RGB emission channel by channel; pbrt-v4's upgrade refuses
            // it, as phos does for a spectral emission (no RGB to multiply).
            Param* target = nullptr;
            for (const char* n : {"L", "I"})
                if (Param* e = params.edit(n); e && e->type == "rgb") target = e;
            if (scale.type != "rgb" || !target)
                scale.loc.fail("a coloured light " + scale.declaration() +
                               " can only multiply an \"rgb\" emission (pbrt-v4's \"scale\" is a float)");
            for (int c = 0; c < 3; ++c) target->numbers[size_t(c)] *= scale.numbers[size_t(c)];
        }
    }
    // pbrt-v3's blackbody [T s]: the temperature, s moving into the scale.
    for (const char* n : {"L", "I"})
        if (Param* e = params.edit(n); e && e->type == "blackbody" && e->numbers.size() == 2) {
            if (!(e->numbers[1] >= 0)) e->loc.fail("blackbody scale (the second value) must not be negative");
            factor *= e->numbers[1];
            e->numbers.resize(1);
        }
    // pbrt-v3's goniometric "mapname" is a latitude-longitude map, which the scene builder reads
    // itself (pbrt-v4's "filename" is an equal-area square): it stays "mapname".
    if (!area && type != "goniometric") {
        if (std::optional<Param> map = params.take("mapname")) {
            if (type == "infinite") {
                if (const Param* L = params.peek("L")) {
                    if (!grey(*L))
                        L->loc.fail(
                            "pbrt-v3 infinite light with \"mapname\": \"L\" must be a grey \"rgb\" to become "
                            "pbrt-v4's \"scale\"");
                    factor *= params.take("L")->numbers[0];
                }
            }
            map->name = "filename";
            params.add(std::move(*map));
        }
    }
    if (factor != 1) {
        const std::optional<Param> s = params.take("scale");
        params.add(float_param("scale", factor * (s ? s->numbers[0] : 1.0), s ? s->loc : loc));
    }
}

void upgrade_film(std::string& type, ParamList& params) {
    if (type != "image") return;
    type = "rgb";
    params.rename("maxsampleluminance", "maxcomponentvalue");
    if (std::optional<Param> s = params.take("scale")) {
        if (params.peek("iso")) s->loc.fail("Film \"image\": \"scale\" and \"iso\" both given");
        s->numbers[0] *= 100;
        s->name = "iso";
        params.add(std::move(*s));
    }
}

void upgrade_texture_params(const std::string& type, const std::string& cls, ParamList& params) {
    if (cls == "scale" && (params.peek("tex1") || params.peek("tex2"))) {
        if (type == "float") {
            params.rename("tex1", "tex");
            params.rename("tex2", "scale");
        } else {
            // One of the two must be a grey "rgb" (the scale), the other the texture.
            const Param* a = params.peek("tex1");
            const Param* b = params.peek("tex2");
            const bool a_grey = a && grey(*a), b_grey = b && grey(*b);
            if (a_grey && b_grey)
                b->loc.fail("\"scale\" texture: two \"rgb\" values (pbrt-v4 needs one texture)");
            const std::string scale_name = a_grey ? "tex1" : b_grey ? "tex2" : "";
            const std::string tex_name = scale_name == "tex1" ? "tex2" : "tex1";
            if (scale_name.empty()) {
                const Param* c = (a && a->type == "rgb") ? a : b;
                if (c && c->type == "rgb")
                    c->loc.fail("\"scale\" texture: a coloured " + c->declaration() +
                                " cannot become pbrt-v4's float \"scale\"");
                params.rename("tex1", "tex");
                params.rename("tex2", "scale");
            } else {
                Param scale = *params.take(scale_name);
                params.rename(tex_name, "tex");
                params.add(float_param("scale", scale.numbers[0], scale.loc));
            }
        }
    }
    if (cls == "imagemap" || cls == "ptex") {
        if (const Param* g = params.peek("gamma")) {
            const Param gamma = *params.take("gamma");
            std::string encoding;
            if (gamma.type == "bool")
                encoding = gamma.bools.at(0) ? "sRGB" : "linear";
            else if (gamma.type == "float")
                encoding = "gamma " + std::to_string(gamma.numbers.at(0));
            else
                g->loc.fail("\"gamma\" must be a bool or a float");
            params.add(string_param("encoding", {encoding}, gamma.loc));
        }
        if (const std::optional<Param> t = params.take("trilinear"); t && t->type == "bool")
            params.add(string_param("filter", {t->bools.at(0) ? "trilinear" : "bilinear"}, t->loc));
    }
}

void upgrade_shape(const std::string& type, ParamList& params) {
    if (type == "loopsubdiv") params.rename("nlevels", "levels");
    params.take("discarddegenerateUVs");
    params.take("shadowalpha");
}

void upgrade_integrator(std::string& type, ParamList& params, const Loc& loc) {
    params.take("rrthreshold");
    if (type == "sppm") params.take("imagewritefrequency");  // its "numiterations" stays (upgrade_v3.h)
    if (const Param* l = params.peek("lightsamplestrategy");
        l && l->strings == std::vector<std::string>{"spatial"})
        params.edit("lightsamplestrategy")->strings = {"bvh"};
    if (type == "directlighting") {
        type = "path";
        params.take("maxdepth");
        params.take("strategy");
        Param depth = float_param("maxdepth", 1, loc);
        depth.type = "integer";
        params.add(std::move(depth));
    }
}

void upgrade_medium(ParamList& params) {
    if (Param* t = params.edit("type"); t && t->strings == std::vector<std::string>{"heterogeneous"})
        t->strings = {"uniformgrid"};
}

void upgrade_filter(const std::string& type, ParamList& params) {
    params.rename("xwidth", "xradius");
    params.rename("ywidth", "yradius");
    if (type == "gaussian")
        if (const std::optional<Param> a = params.take("alpha");
            a && a->type == "float" && a->numbers.at(0) > 0)
            params.add(float_param("sigma", 1 / std::sqrt(2 * a->numbers[0]), a->loc));
}

}  // namespace

void upgrade_directive(const std::string& directive, std::string& type, ParamList& params, const Loc& loc) {
    if (directive == "Material") {
        upgrade_material(type, params, loc);
    } else if (directive == "MakeNamedMaterial") {
        // `type` is the material's name here; its type is the "type" parameter.
        if (const Param* t = params.peek("type"); t && t->type == "string" && t->strings.size() == 1) {
            std::string material = t->strings[0];
            upgrade_material(material, params, loc);
            params.edit("type")->strings = {material};
        }
    } else if (directive == "LightSource" || directive == "AreaLightSource") {
        upgrade_light(type, params, loc, directive == "AreaLightSource");
    } else if (directive == "Film") {
        upgrade_film(type, params);
    } else if (directive == "PixelFilter") {
        upgrade_filter(type, params);
    } else if (directive == "Integrator") {
        upgrade_integrator(type, params, loc);
    } else if (directive == "MakeNamedMedium") {
        upgrade_medium(params);
    } else if (directive == "Shape") {
        upgrade_shape(type, params);
    } else if (directive == "Sampler") {
        if (type == "lowdiscrepancy" || type == "02sequence")
            type = "paddedsobol";
        else if (type == "maxmindist")
            type = "pmj02bn";
        else if (type == "random")
            type = "independent";
    }
}

void upgrade_texture(std::string& type, const std::string& cls, ParamList& params) {
    if (type == "color") type = "spectrum";
    upgrade_texture_params(type, cls, params);
}

}  // namespace phos::io::pbrt
