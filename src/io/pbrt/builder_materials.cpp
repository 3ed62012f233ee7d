// SceneBuilder: colours and textured parameters, the Texture directive and pbrt materials mapped
// onto phos's layered scene::Material (approximations are warned about once per material type).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/log.h"
#include "io/image/image_io.h"
#include "io/pbrt/builder.h"
#include "io/text/image_texture.h"
#include "spectrum/color.h"
#include "spectrum/dispersion.h"

namespace phos::io::pbrt {
namespace {

// Reads a spectrum file: whitespace-separated wavelength-value pairs, '#' comments.
bool read_spectrum_file(const std::string& path, std::vector<float>& lambda, std::vector<float>& value) {
    std::ifstream in(path);
    if (!in) return false;
    std::string line, all;
    while (std::getline(in, line)) all += line.substr(0, line.find('#')) + " ";
    std::istringstream ss(all);
    double l, v;
    while (ss >> l >> v) lambda.push_back(float(l)), value.push_back(float(v));
    return !lambda.empty() && ss.eof();
}

// pbrt-v4 Trowbridge-Reitz: alpha = sqrt(roughness) when remapped; phos's Phong-like lobe with the
// same width has exponent n = 2 / alpha^2 - 2 (the usual Beckmann/Phong correspondence).
float shininess_from_alpha(float alpha) {
    if (alpha < 1e-3f) return 1e6f;  // pbrt treats this as perfectly smooth
    return std::clamp(2.0f / (alpha * alpha) - 2.0f, 0.0f, 1e6f);
}

}  // namespace

std::optional<Rgb> SceneBuilder::color(const ParamList& params, const std::string& name, SpectrumUse use,
                                       std::optional<spectrum::Distribution>* spectrum_out) const {
    if (spectrum_out) spectrum_out->reset();
    const Param* p = params.find(name);
    if (!p) return std::nullopt;
    const bool illuminant = use == SpectrumUse::Illuminant;
    std::optional<spectrum::Distribution> s;  // the spectrum, when the value is one
    Rgb c;
    if (p->type == "rgb") {
        c = Rgb(float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2]));
        if (use != SpectrumUse::Unbounded && (c.r < 0 || c.g < 0 || c.b < 0))
            p->loc.fail("parameter " + p->declaration() + " must not be negative");
        if (gs_.color_space != "srgb") {
            // Another ColorSpace: the same colour in linear sRGB (an emitted colour keeps its XYZ, a
            // reflectance its whiteness); a colour outside sRGB's gamut is clipped to it.
            const Vec3 v = spectrum::apply(*spectrum::rgb_space_to_srgb(gs_.color_space, !illuminant),
                                           Vec3(c.r, c.g, c.b));
            c = Rgb(v.x, v.y, v.z);
            if (use != SpectrumUse::Unbounded && (c.r < 0 || c.g < 0 || c.b < 0)) {
                warn_once(
                    "gamut", p->loc,
                    "parameter " + p->declaration() + ": a colour outside the sRGB gamut is clipped to it");
                c = Rgb(std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f));
            }
        }
    } else if (p->type == "float") {
        if (p->numbers.size() != 1) p->loc.fail("parameter " + p->declaration() + " takes one value");
        c = Rgb(float(p->numbers[0]));
    } else if (p->type == "blackbody") {
        if (!(p->numbers[0] > 0)) p->loc.fail("blackbody temperature must be positive");
        // pbrt-v3's second value multiplies (pbrt-v4's upgrade moves it into "scale").
        const float k = p->numbers.size() > 1 ? float(p->numbers[1]) : 1.0f;
        if (!(k >= 0)) p->loc.fail("blackbody scale (the second value) must not be negative");
        c = blackbody_rgb(float(p->numbers[0])) * k;
        s = luminance_1(spectrum::Distribution::blackbody(float(p->numbers[0]))).scaled(k);
    } else if (p->type == "spectrum") {
        std::vector<float> lambda, value;
        if (!p->strings.empty()) {
            const std::string& n = p->strings[0];
            if (const auto named = named_spectrum_rgb(n, use)) {
                if (spectrum_out) {
                    if (illuminant) {
                        if (const auto d = named_illuminant(n)) *spectrum_out = luminance_1(*d);
                    } else {
                        *spectrum_out = named_material_spectrum(n);
                    }
                }
                return *named;
            }
            const std::string path = resolve(n, p->loc);
            if (!read_spectrum_file(path, lambda, value))
                p->loc.fail("\"" + n + "\" is neither a named spectrum nor a readable spectrum file");
        } else {
            for (size_t i = 0; i + 1 < p->numbers.size(); i += 2)
                lambda.push_back(float(p->numbers[i])), value.push_back(float(p->numbers[i + 1]));
        }
        for (size_t i = 1; i < lambda.size(); ++i)
            if (!(lambda[i] > lambda[i - 1])) p->loc.fail("spectrum wavelengths must increase");
        c = sampled_spectrum_rgb(lambda, value, use);
        const spectrum::Distribution table =
            spectrum::Distribution::tabulated(std::move(lambda), std::move(value));
        s = illuminant ? luminance_1(table) : table;
    } else {
        p->loc.fail("parameter '" + name + "' should be a colour (rgb, spectrum or blackbody), not " +
                    p->type);
    }
    if (!c.is_finite()) p->loc.fail("parameter " + p->declaration() + " is not finite");
    if (spectrum_out) *spectrum_out = std::move(s);
    return c;
}

Rgb SceneBuilder::color_or_texture(const ParamList& params, const std::string& name, Rgb def, int* tex,
                                   SpectrumUse use, const std::string&) {
    *tex = -1;
    if (const Param* p = params.find(name); p && p->type == "texture") {
        const std::string& t = p->strings[0];
        if (const auto it = spectrum_textures_.find(t); it != spectrum_textures_.end())
            *tex = it->second;
        else if (const auto jt = float_textures_.find(t); jt != float_textures_.end())
            *tex = jt->second;
        else
            p->loc.fail("unknown texture \"" + t + "\"");
        return Rgb(1.0f);
    }
    return color(params, name, use).value_or(def);
}

float SceneBuilder::float_param(const ParamList& params, const std::string& name, float def,
                                const std::string& directive) {
    const Param* p = params.find(name);
    if (!p) return def;
    if (p->type == "texture") {
        warn(p->loc,
             directive + ": textured \"" + name + "\" is not supported; " + std::to_string(def) + " is used");
        return def;
    }
    return params.get_float(name, def);
}

int SceneBuilder::constant_texture(Rgb value) {
    scene::Texture t;
    t.kind = scene::Texture::Kind::Constant;
    t.value = value;
    scene_.textures.push_back(t);
    return int(scene_.textures.size()) - 1;
}

// ---- textures ----

void SceneBuilder::texture(const std::string& name, const std::string& type, const std::string& cls,
                           const ParamList& params, const Loc& loc) {
    require_world(true, "Texture", loc);
    if (type != "float" && type != "spectrum")  // pbrt-v3's "color" arrives as "spectrum" (upgrade_v3.h)
        loc.fail("Texture \"" + name + "\": type must be \"float\" or \"spectrum\", not \"" + type + "\"");
    auto& names = type == "float" ? float_textures_ : spectrum_textures_;
    if (names.count(name)) loc.fail("Texture \"" + name + "\" defined twice");
    const std::string d = "Texture \"" + name + "\" \"" + type + "\" \"" + cls + "\"";
    const SpectrumUse use = SpectrumUse::Albedo;
    const bool grey = type == "float";

    scene::Texture t;
    auto uv_mapping = [&] {
        const std::string mapping = params.get_string("mapping", "uv");
        if (mapping != "uv")
            warn(params.find("mapping")->loc,
                 d + ": mapping \"" + mapping + "\" is not supported; uv mapping is used");
        t.u_scale = params.get_float("uscale", 1.0f);
        t.v_scale = params.get_float("vscale", 1.0f);
        t.u_offset = params.get_float("udelta", 0.0f);
        t.v_offset = params.get_float("vdelta", 0.0f);
    };
    // A texture-or-value parameter as a texture index (constants get their own texture).
    auto tex_arg = [&](const std::string& pname, Rgb def) {
        int idx = -1;
        const Rgb v = color_or_texture(params, pname, def, &idx, use, d);
        return idx >= 0 ? idx : constant_texture(v);
    };

    if (cls == "constant") {
        t.kind = scene::Texture::Kind::Constant;
        t.value = color(params, "value", use).value_or(Rgb(1.0f));
    } else if (cls == "scale") {
        t.kind = scene::Texture::Kind::Scale;
        t.tex1 = tex_arg("tex", Rgb(1.0f));
        int idx = -1;
        t.value = color_or_texture(params, "scale", Rgb(1.0f), &idx, use, d);
        t.tex2 = idx;
    } else if (cls == "mix" || cls == "directionmix") {
        warn(loc, d + " is not supported; its first texture (\"tex1\") is used");
        const int first = tex_arg("tex1", Rgb(0.0f));
        params.mark_all_used();
        names[name] = first;
        return;
    } else if (cls == "checkerboard") {
        t.kind = scene::Texture::Kind::Checkerboard;
        if (params.get_int("dimension", 2) != 2)
            warn(params.find("dimension")->loc, d + ": only 2D checkerboards are supported");
        uv_mapping();
        t.tex1 = tex_arg("tex1", Rgb(1.0f));
        t.tex2 = tex_arg("tex2", Rgb(0.0f));
    } else if (cls == "imagemap") {
        t.kind = scene::Texture::Kind::Image;
        uv_mapping();
        const Param* fp = params.find("filename");
        if (!fp) loc.fail(d + ": missing \"string filename\"");
        const std::string filename = params.get_string("filename", "");
        const std::string encoding = params.get_string("encoding", "sRGB");
        float gamma = 1.0f;
        bool srgb = true;
        if (encoding == "linear") {
            srgb = false;
        } else if (encoding.rfind("gamma ", 0) == 0) {
            srgb = false;
            gamma = std::strtof(encoding.c_str() + 6, nullptr);
            if (!(gamma > 0)) params.find("encoding")->loc.fail("bad gamma in encoding \"" + encoding + "\"");
        } else if (encoding != "sRGB") {
            params.find("encoding")
                ->loc.fail("unknown encoding \"" + encoding + "\" (sRGB, linear or gamma G)");
        }
        const std::string wrap = params.get_string("wrap", "repeat");
        if (wrap == "repeat")
            t.wrap = scene::Texture::Wrap::Repeat;
        else if (wrap == "clamp")
            t.wrap = scene::Texture::Wrap::Clamp;
        else if (wrap == "black")
            t.wrap = scene::Texture::Wrap::Black;
        else if (wrap == "octahedralsphere") {
            warn(params.find("wrap")->loc,
                 d + ": wrap \"octahedralsphere\" is not supported; \"repeat\" is used");
        } else {
            params.find("wrap")->loc.fail("unknown wrap mode \"" + wrap + "\"");
        }
        const bool invert = params.get_bool("invert", false);
        t.value = Rgb(params.get_float("scale", 1.0f));
        params.get_string("filter", "bilinear");  // phos filters bilinearly whatever is asked
        params.get_float("maxanisotropy", 8.0f);
        const std::string path = resolve(filename, fp->loc);
        Image img;
        try {
            img = read_image(path, srgb);
        } catch (const std::exception& e) {
            fp->loc.fail(d + ": " + e.what());
        }
        auto ti = text::to_texture_image(std::move(img));
        for (Rgb& c : ti->texels) {
            if (gamma != 1.0f) c = Rgb(std::pow(c.r, gamma), std::pow(c.g, gamma), std::pow(c.b, gamma));
            if (grey) c = Rgb(c.average());
            if (invert) c = Rgb(std::max(0.0f, 1 - c.r), std::max(0.0f, 1 - c.g), std::max(0.0f, 1 - c.b));
        }
        t.image = std::move(ti);
        t.filename = path;
        t.invert_v = false;  // pbrt looks images up at (s, 1 - t), i.e. v = 0 is the bottom row: our default
    } else {
        warn(loc, d + ": texture class \"" + cls + "\" is not supported; a constant 0.5 is used");
        params.mark_all_used();
        t.kind = scene::Texture::Kind::Constant;
        t.value = Rgb(0.5f);
    }
    done(params, d);
    scene_.textures.push_back(std::move(t));
    names[name] = int(scene_.textures.size()) - 1;
}

// ---- materials ----

scene::Material SceneBuilder::make_material(const std::string& type, const ParamList& params, const Loc& loc,
                                            const std::string& d) {
    scene::Material m;
    for (const char* p : {"displacement", "normalmap"})
        if (const Param* q = params.find(p))
            warn(q->loc, d + ": \"" + std::string(p) + "\" is not supported (ignored)");
    const SpectrumUse albedo = SpectrumUse::Albedo;
    auto roughness_shininess = [&](const std::string& prefix) {
        const bool remap = params.get_bool("remaproughness", true);
        const float r = float_param(params, prefix + "roughness", 0.0f, d);
        const float ur = float_param(params, prefix + "uroughness", r, d);
        const float vr = float_param(params, prefix + "vroughness", r, d);
        if (ur < 0 || vr < 0) loc.fail(d + ": roughness must not be negative");
        if (ur != vr) warn(loc, d + ": anisotropic roughness is not supported; the mean is used");
        float alpha = 0.5f * (ur + vr);
        if (remap) alpha = std::sqrt(alpha);
        return shininess_from_alpha(alpha);
    };
    // A dielectric's index: a float, a named glass (its Sellmeier index, `ior` at the d line), or
    // a spectrum of wavelength-value pairs inline or in a file (`ior` its value at the d line).
    // *dispersion gets the index's spectrum when it has one.
    auto eta_param = [&](const std::string& name, float def,
                         std::optional<spectrum::Distribution>* dispersion = nullptr) {
        const Param* p = params.find(name);
        if (!p) return def;
        float eta = def;
        std::optional<spectrum::Distribution> dispersive;
        if (p->type == "float") {
            eta = params.get_float(name, def);
        } else if (p->type == "spectrum") {
            std::vector<float> l, v;
            if (!p->strings.empty()) {
                const std::string& n = p->strings[0];
                if (const auto value = named_spectrum_value(n)) {
                    eta = *value;
                    if (n.rfind("glass-", 0) == 0) dispersive = named_material_spectrum(n);
                } else if (!read_spectrum_file(resolve(n, p->loc), l, v)) {
                    p->loc.fail("\"" + n + "\" is neither a named spectrum nor a readable spectrum file");
                }
            } else {
                for (size_t i = 0; i + 1 < p->numbers.size(); i += 2)
                    l.push_back(float(p->numbers[i])), v.push_back(float(p->numbers[i + 1]));
            }
            if (!l.empty()) {
                for (size_t i = 1; i < l.size(); ++i)
                    if (!(l[i] > l[i - 1])) p->loc.fail("spectrum wavelengths must increase");
                for (float x : v)
                    if (!(x > 0)) p->loc.fail(d + ": eta must be positive at every wavelength");
                eta = sampled_spectrum_at(l, v, float(spectrum::kLineD));
                dispersive = spectrum::Distribution::tabulated(std::move(l), std::move(v));
            }
        } else {
            p->loc.fail("parameter '" + name + "' should be float or spectrum, not " + p->type);
        }
        if (!(eta > 0)) p->loc.fail(d + ": eta must be positive");
        if (dispersion) *dispersion = std::move(dispersive);
        return eta;
    };

    if (type == "diffuse") {
        m.diffuse = color_or_texture(params, "reflectance", Rgb(0.5f), &m.diffuse_texture, albedo, d);
    } else if (type == "coateddiffuse") {
        warn_once(
            "coateddiffuse", loc,
            d + " is approximated: diffuse base plus a Fresnel-weighted glossy coat (no interreflection)");
        m.diffuse = color_or_texture(params, "reflectance", Rgb(0.5f), &m.diffuse_texture, albedo, d);
        const float eta = eta_param("eta", 1.5f);
        const float f0 = (eta - 1) * (eta - 1) / ((eta + 1) * (eta + 1));
        m.specular = Rgb(f0);
        m.diffuse *= 1.0f - f0;
        m.shininess = roughness_shininess("");
        for (const char* p : {"thickness", "g", "maxdepth", "nsamples", "albedo"}) params.find(p);
    } else if (type == "conductor" || type == "coatedconductor") {
        const std::string pre = type == "conductor" ? "" : "conductor.";
        if (type == "coatedconductor") {
            warn_once("coatedconductor", loc,
                      d + " is approximated by its conductor base (the coat is ignored)");
            for (const char* p : {"interface.roughness", "interface.uroughness", "interface.vroughness",
                                  "interface.eta", "thickness", "g", "maxdepth", "nsamples", "albedo"})
                params.find(p);
        }
        m.shininess = roughness_shininess(pre);
        if (params.has(pre + "reflectance")) {
            int tex = -1;
            m.specular = color_or_texture(params, pre + "reflectance", Rgb(1.0f), &tex, albedo, d);
            if (tex >= 0) {
                warn(loc, d + ": a textured conductor reflectance is not supported; 1 is used");
                m.specular = Rgb(1.0f);
            }
        } else {
            m.conductor = true;
            m.specular = Rgb(1.0f);
            // Each of eta and k: as given, else pbrt-v4's default, copper; a named metal or a
            // sampled spectrum keeps its spectrum too.
            const auto part = [&](const std::string& pname, const std::string& copper, Rgb& rgb,
                                  std::optional<spectrum::Distribution>& measured) {
                if (const auto c = color(params, pname, SpectrumUse::Unbounded, &measured)) {
                    rgb = *c;
                } else {
                    rgb = *named_spectrum_rgb(copper, SpectrumUse::Unbounded);
                    measured = named_material_spectrum(copper);
                }
            };
            part(pre + "eta", "metal-Cu-eta", m.conductor_eta, m.conductor_eta_spectrum);
            part(pre + "k", "metal-Cu-k", m.conductor_k, m.conductor_k_spectrum);
        }
    } else if (type == "dielectric" || type == "thindielectric") {
        m.ior = eta_param("eta", 1.5f, &m.ior_spectrum);
        m.transmission = Rgb(1.0f);
        m.thin = type == "thindielectric";
        m.transmission_shininess = m.thin ? 1e6f : roughness_shininess("");
    } else if (type == "diffusetransmission") {
        const float s = params.get_float("scale", 1.0f);
        m.diffuse = color_or_texture(params, "reflectance", Rgb(0.25f), &m.diffuse_texture, albedo, d) * s;
        int tex = -1;
        m.diffuse_transmission = color_or_texture(params, "transmittance", Rgb(0.25f), &tex, albedo, d) * s;
        if (tex >= 0) {
            warn(loc, d + ": a textured transmittance is not supported; 0.25 is used");
            m.diffuse_transmission = Rgb(0.25f * s);
        }
    } else if (type == "interface" || type == "" || type == "none") {
        m.interface_only = true;
    } else if (type == "mix") {
        const std::vector<std::string> names = params.get_strings("materials");
        if (names.size() != 2) loc.fail(d + ": needs \"string materials\" with two names");
        const auto it = named_materials_.find(names[0]);
        if (it == named_materials_.end())
            params.find("materials")->loc.fail("unknown material \"" + names[0] + "\"");
        warn(loc, d + " is not supported; its first material \"" + names[0] + "\" is used");
        params.mark_all_used();
        m = scene_.materials[size_t(it->second)];
    } else {
        warn(loc, d + ": material type \"" + type + "\" is not supported; a grey diffuse material is used");
        params.mark_all_used();
        m.diffuse = Rgb(0.5f);
    }
    done(params, d);
    return m;
}

void SceneBuilder::material(const std::string& type, const ParamList& params, const Loc& loc) {
    require_world(true, "Material", loc);
    scene::Material m = make_material(type, params, loc, "Material \"" + type + "\"");
    m.name = type + "@" + std::to_string(loc.line);
    gs_.material = int(scene_.materials.size());
    scene_.materials.push_back(std::move(m));
}

void SceneBuilder::make_named_material(const std::string& name, const ParamList& params, const Loc& loc) {
    require_world(true, "MakeNamedMaterial", loc);
    if (named_materials_.count(name)) loc.fail("named material \"" + name + "\" defined twice");
    const Param* tp = params.find("type");
    if (!tp) loc.fail("MakeNamedMaterial \"" + name + "\": missing \"string type\"");
    const std::string type = params.get_string("type", "");
    scene::Material m = make_material(type, params, loc, "MakeNamedMaterial \"" + name + "\"");
    m.name = name;
    named_materials_[name] = int(scene_.materials.size());
    scene_.materials.push_back(std::move(m));
}

void SceneBuilder::named_material(const std::string& name, const Loc& loc) {
    require_world(true, "NamedMaterial", loc);
    const auto it = named_materials_.find(name);
    if (it == named_materials_.end()) loc.fail("NamedMaterial: unknown material \"" + name + "\"");
    gs_.material = it->second;
}

// pbrt-v4 materials' shading detail (shading/bump.h): "displacement", a float texture whose
// gradient bump-maps the shading normal (a constant displaces every point alike, which changes no
// normal: nothing to store), and "normalmap", an image file of tangent-space normals read as
// linear RGB (as pbrt-v4 reads it, whatever the file's encoding). pbrt-v4 uses the normal map when
// both are given.
void SceneBuilder::read_shading_detail(const ParamList& params, scene::Material& m, const std::string& d) {
    if (const Param* p = params.find("displacement")) {
        if (p->type == "texture") {
            const auto it = float_textures_.find(p->strings[0]);
            if (it == float_textures_.end())
                p->loc.fail(d + ": unknown float texture \"" + p->strings[0] + "\"");
            m.displacement_texture = it->second;
        } else if (!std::isfinite(params.get_float("displacement", 0.0f))) {
            p->loc.fail(d + ": \"displacement\" is not finite");
        }
    }
    if (const Param* p = params.find("normalmap")) {
        const std::string filename = params.get_string("normalmap", "");
        if (filename.empty()) return;  // pbrt-v4's default: no normal map
        const std::string path = resolve(filename, p->loc);
        Image img;
        try {
            img = read_image(path, false);
        } catch (const std::exception& e) {
            p->loc.fail(d + ": normal map: " + e.what());
        }
        try {
            m.normal_map = text::to_texture_image(std::move(img));
        } catch (const std::exception& e) {
            p->loc.fail(d + ": normal map: " + e.what());
        }
        if (m.displacement_texture >= 0)
            warn(p->loc,
                 d + ": both \"displacement\" and \"normalmap\": the normal map is used (as pbrt-v4 does)");
    }
}

}  // namespace phos::io::pbrt
