// SceneBuilder: colours and textured parameters, the Texture directive and pbrt materials mapped
// onto phos's layered scene::Material (approximations are warned about once per material type).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/log.h"
#include "io/bsdf/rgl_bsdf_file.h"
#include "io/image/image_io.h"
#include "io/pbrt/builder.h"
#include "io/text/image_texture.h"
#include "scene/mip_map.h"
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
    // pbrt evaluates texture-space mappings and 3D textures in the space of the CTM at this
    // directive.
    t.texture_from_world = gs_.ctm.inverse();
    const auto finite_float = [&](const std::string& pname, float def) {
        const float v = params.get_float(pname, def);
        if (!std::isfinite(v)) params.find(pname)->loc.fail(d + ": \"" + pname + "\" must be finite");
        return v;
    };
    const auto finite_vector = [&](const std::string& pname, Vec3 def) {
        const Vec3 v = params.get_point3(pname, def);
        if (!is_finite(v)) params.find(pname)->loc.fail(d + ": \"" + pname + "\" must be finite");
        return v;
    };
    // pbrt-v4's 2D mappings (TextureMapping2D::Create): each reads only its own parameters.
    const auto mapping_2d = [&] {
        const std::string mapping = params.get_string("mapping", "uv");
        if (mapping == "uv") {
            t.mapping = scene::Texture::Mapping::UV;
            t.u_scale = finite_float("uscale", 1.0f);
            t.v_scale = finite_float("vscale", 1.0f);
            t.u_offset = finite_float("udelta", 0.0f);
            t.v_offset = finite_float("vdelta", 0.0f);
        } else if (mapping == "spherical") {
            t.mapping = scene::Texture::Mapping::Spherical;
        } else if (mapping == "cylindrical") {
            t.mapping = scene::Texture::Mapping::Cylindrical;
        } else if (mapping == "planar") {
            t.mapping = scene::Texture::Mapping::Planar;
            t.planar_s = finite_vector("v1", Vec3(1, 0, 0));
            t.planar_t = finite_vector("v2", Vec3(0, 1, 0));
            t.u_offset = finite_float("udelta", 0.0f);
            t.v_offset = finite_float("vdelta", 0.0f);
        } else {
            params.find("mapping")->loc.fail(d + ": unknown mapping \"" + mapping +
                                             "\" (uv, spherical, cylindrical or planar)");
        }
    };
    // A texture name: among this texture's type first (pbrt keeps float and spectrum names apart),
    // then the other type's.
    const auto named_texture = [&](const Param& p, bool want_float) {
        const std::string& tn = p.strings[0];
        const auto& first = want_float ? float_textures_ : spectrum_textures_;
        const auto& second = want_float ? spectrum_textures_ : float_textures_;
        if (const auto it = first.find(tn); it != first.end()) return it->second;
        if (const auto it = second.find(tn); it != second.end()) return it->second;
        p.loc.fail(d + ": unknown texture \"" + tn + "\"");
    };
    // A texture-or-value parameter as a texture index (a value gets a constant texture; a float
    // texture's value is a float, a spectrum texture's a colour).
    const auto tex_arg = [&](const std::string& pname, float def) {
        const Param* p = params.find(pname);
        if (p && p->type == "texture") return named_texture(*p, grey);
        return constant_texture(grey ? Rgb(finite_float(pname, def))
                                     : color(params, pname, use).value_or(Rgb(def)));
    };
    // A float texture-or-value parameter: sets *index (a texture) or returns the value.
    const auto float_arg = [&](const std::string& pname, float def, int* index) {
        *index = -1;
        const Param* p = params.find(pname);
        if (p && p->type == "texture") {
            *index = named_texture(*p, true);
            return def;
        }
        return finite_float(pname, def);
    };
    // The octave count of a noise texture: at least 0; beyond 32 the octaves' frequencies (1.99^i)
    // exceed float precision and their weights are negligible, so 32 are evaluated.
    const auto octaves = [&] {
        const int n = params.get_int("octaves", 8);
        if (n < 0) params.find("octaves")->loc.fail(d + ": \"octaves\" must not be negative");
        if (n > 32) {
            warn(params.find("octaves")->loc,
                 d + ": " + std::to_string(n) + " octaves: the first 32 are used");
            return 32;
        }
        return n;
    };

    if (cls == "constant") {
        t.kind = scene::Texture::Kind::Constant;
        t.value = grey ? Rgb(finite_float("value", 1.0f)) : color(params, "value", use).value_or(Rgb(1.0f));
    } else if (cls == "scale") {
        t.kind = scene::Texture::Kind::Scale;
        t.tex1 = tex_arg("tex", 1.0f);
        int idx = -1;
        t.value = color_or_texture(params, "scale", Rgb(1.0f), &idx, use, d);
        t.tex2 = idx;
    } else if (cls == "mix") {
        t.kind = scene::Texture::Kind::Mix;
        t.tex1 = tex_arg("tex1", 0.0f);
        t.tex2 = tex_arg("tex2", 1.0f);
        t.amount_value = float_arg("amount", 0.5f, &t.amount);
    } else if (cls == "directionmix") {
        t.kind = scene::Texture::Kind::DirectionMix;
        t.tex1 = tex_arg("tex1", 0.0f);
        t.tex2 = tex_arg("tex2", 1.0f);
        const Vec3 dir = gs_.ctm.vector(finite_vector("dir", Vec3(0, 1, 0)));
        if (!(length(dir) > 0) || !is_finite(dir))
            (params.find("dir") ? params.find("dir")->loc : loc).fail(d + ": \"dir\" must not be zero");
        t.direction = normalize(dir);
    } else if (cls == "bilerp") {
        t.kind = scene::Texture::Kind::Bilerp;
        mapping_2d();
        const auto corner = [&](const std::string& pname, float def) {
            return grey ? Rgb(finite_float(pname, def)) : color(params, pname, use).value_or(Rgb(def));
        };
        t.corners = {corner("v00", 0.0f), corner("v01", 1.0f), corner("v10", 0.0f), corner("v11", 1.0f)};
    } else if (cls == "checkerboard") {
        t.kind = scene::Texture::Kind::Checkerboard;
        t.dimension = params.get_int("dimension", 2);
        if (t.dimension != 2 && t.dimension != 3)
            params.find("dimension")->loc.fail(d + ": \"dimension\" must be 2 or 3");
        if (t.dimension == 2) mapping_2d();
        t.tex1 = tex_arg("tex1", 1.0f);
        t.tex2 = tex_arg("tex2", 0.0f);
    } else if (cls == "dots") {
        t.kind = scene::Texture::Kind::Dots;
        mapping_2d();
        // pbrt-v4 (as pbrt-v3) hands "inside" to its DotsTexture's outside-the-dot slot and
        // "outside" to the inside one: the dots show "outside" (default 0) on "inside" (default 1).
        t.tex1 = tex_arg("outside", 0.0f);
        t.tex2 = tex_arg("inside", 1.0f);
    } else if (cls == "fbm" || cls == "wrinkled") {
        t.kind = cls == "fbm" ? scene::Texture::Kind::FBm : scene::Texture::Kind::Wrinkled;
        t.octaves = octaves();
        t.roughness = finite_float("roughness", 0.5f);
    } else if (cls == "windy") {
        t.kind = scene::Texture::Kind::Windy;
    } else if (cls == "marble") {
        if (grey) loc.fail(d + ": \"marble\" is a spectrum texture (pbrt-v4 has no float marble)");
        t.kind = scene::Texture::Kind::Marble;
        t.octaves = octaves();
        t.roughness = finite_float("roughness", 0.5f);
        t.marble_scale = finite_float("scale", 1.0f);
        t.variation = finite_float("variation", 0.2f);
    } else if (cls == "imagemap") {
        t.kind = scene::Texture::Kind::Image;
        mapping_2d();
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
        // pbrt-v4's filters (MIPMap::Filter; ParseFilter's names).
        const std::string filter = params.get_string("filter", "bilinear");
        if (filter == "bilinear")
            t.filter = scene::Texture::Filter::Bilinear;
        else if (filter == "point")
            t.filter = scene::Texture::Filter::Point;
        else if (filter == "trilinear")
            t.filter = scene::Texture::Filter::Trilinear;
        else if (filter == "ewa" || filter == "EWA")
            t.filter = scene::Texture::Filter::Ewa;
        else
            params.find("filter")->loc.fail(d + ": unknown filter \"" + filter +
                                            "\" (point, bilinear, trilinear or ewa)");
        t.max_anisotropy = finite_float("maxanisotropy", 8.0f);
        if (!(t.max_anisotropy > 0))
            params.find("maxanisotropy")->loc.fail(d + ": \"maxanisotropy\" must be positive");
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
        // One image (and one MIP map per wrap mode) for the textures that read the same texels.
        for (const scene::Texture& o : scene_.textures) {
            if (o.kind != scene::Texture::Kind::Image || o.filename != path || !o.image ||
                o.image->width != t.image->width || o.image->height != t.image->height ||
                !std::equal(o.image->texels.begin(), o.image->texels.end(), t.image->texels.begin(),
                            t.image->texels.end(), [](const Rgb& a, const Rgb& b) {
                                return a.r == b.r && a.g == b.g && a.b == b.b;
                            }))
                continue;
            t.image = o.image;
            if (o.mip_map && o.wrap == t.wrap) t.mip_map = o.mip_map;
        }
        if (t.filter != scene::Texture::Filter::Bilinear && !t.mip_map)
            t.mip_map = std::make_shared<const scene::MipMap>(*t.image, t.wrap);
        t.invert_v = false;  // pbrt looks images up at (s, 1 - t), i.e. v = 0 is the bottom row: our default
    } else if (cls == "uv") {  // pbrt-v3's (pbrt-v4 has none): the 2D mapping's (s, t) as colour
        t.kind = scene::Texture::Kind::UV;
        mapping_2d();
    } else if (cls == "ptex") {
        // Ptex needs Disney's Ptex library, which Debian does not package.
        warn(loc, d + ": ptex textures are not supported (no Ptex library); a constant 0.5 is used");
        params.mark_all_used();
        t.kind = scene::Texture::Kind::Constant;
        t.value = Rgb(0.5f);
    } else {
        loc.fail(
            d + ": unknown texture class \"" + cls +
            "\" (constant, scale, mix, directionmix, bilerp, imagemap, checkerboard, dots, fbm, wrinkled, "
            "windy, marble, ptex, or pbrt-v3's uv)");
    }
    done(params, d);
    scene_.textures.push_back(std::move(t));
    names[name] = int(scene_.textures.size()) - 1;
}

// ---- materials ----

scene::Material SceneBuilder::make_material(const std::string& type, const ParamList& params, const Loc& loc,
                                            const std::string& d) {
    scene::Material m;
    read_shading_detail(params, m, d);
    const SpectrumUse albedo = SpectrumUse::Albedo;
    // pbrt's roughness parameters (`roughness`, or `uroughness` and `vroughness`, each a float or a
    // float texture; `remaproughness`) as the material's Trowbridge-Reitz roughness.
    auto microfacet_roughness = [&](const std::string& prefix) {
        m.microfacet = true;
        m.remap_roughness = params.get_bool("remaproughness", true);
        const auto rough = [&](const std::string& name, float def, int def_texture, int& texture) {
            texture = def_texture;
            const Param* p = params.find(name);
            if (!p) return def;
            if (p->type == "texture") {
                const auto it = float_textures_.find(p->strings[0]);
                if (it == float_textures_.end())
                    p->loc.fail(d + ": unknown float texture \"" + p->strings[0] + "\"");
                texture = it->second;
                return 0.0f;
            }
            const float v = params.get_float(name, def);
            if (!(v >= 0) || !std::isfinite(v)) p->loc.fail(d + ": \"" + name + "\" must be finite and >= 0");
            return v;
        };
        int texture = -1;
        const float r = rough(prefix + "roughness", 0.0f, -1, texture);
        m.roughness_u = rough(prefix + "uroughness", r, texture, m.roughness_u_texture);
        m.roughness_v = rough(prefix + "vroughness", r, texture, m.roughness_v_texture);
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

    // A conductor's parameters (pbrt-v4's ConductorMaterial, under `prefix`): `reflectance` (a
    // value or texture), else `eta` and `k`, each defaulting to copper's measured spectra.
    auto conductor_base = [&](const std::string& pre) {
        if (params.has(pre + "reflectance")) {
            m.conductor_from_reflectance = true;
            m.specular =
                color_or_texture(params, pre + "reflectance", Rgb(1.0f), &m.specular_texture, albedo, d);
            return;
        }
        m.conductor = true;
        m.specular = Rgb(1.0f);
        // Each of eta and k: as given, else pbrt-v4's default, copper; a named metal or a sampled
        // spectrum keeps its spectrum too.
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
    };
    // The slab of pbrt-v4's coated materials: `thickness` (0.01), the medium's `albedo` (0: none)
    // and `g` (0), `maxdepth` (10) and `nsamples` (1).
    auto layer_slab = [&] {
        m.layer_thickness = float_param(params, "thickness", 0.01f, d);
        if (!(m.layer_thickness >= 0) || !std::isfinite(m.layer_thickness))
            params.find("thickness")->loc.fail(d + ": \"thickness\" must be finite and >= 0");
        m.layer_albedo = color_or_texture(params, "albedo", Rgb(0.0f), &m.layer_albedo_texture, albedo, d);
        m.layer_g = float_param(params, "g", 0.0f, d);
        if (!(m.layer_g >= -1 && m.layer_g <= 1))
            params.find("g")->loc.fail(d + ": \"g\" must be in [-1, 1]");
        m.layer_max_depth = params.get_int("maxdepth", 10);
        if (m.layer_max_depth < 0 || m.layer_max_depth > 10000)
            params.find("maxdepth")->loc.fail(d + ": \"maxdepth\" must be in [0, 10000]");
        m.layer_samples = params.get_int("nsamples", 1);
        if (m.layer_samples < 1 || m.layer_samples > 4096)
            params.find("nsamples")->loc.fail(d + ": \"nsamples\" must be in [1, 4096]");
    };

    if (type == "diffuse") {
        m.diffuse = color_or_texture(params, "reflectance", Rgb(0.5f), &m.diffuse_texture, albedo, d);
    } else if (type == "coateddiffuse") {
        m.layered = true;
        m.diffuse = color_or_texture(params, "reflectance", Rgb(0.5f), &m.diffuse_texture, albedo, d);
        m.coat_eta = eta_param("eta", 1.5f);
        microfacet_roughness("");
        m.microfacet = false;  // the roughness is the coat's (Material::layered)
        layer_slab();
    } else if (type == "conductor") {
        microfacet_roughness("");
        conductor_base("");
    } else if (type == "coatedconductor") {
        m.layered = true;
        m.layered_conductor_base = true;
        microfacet_roughness("conductor.");
        m.base_roughness_u = m.roughness_u;
        m.base_roughness_v = m.roughness_v;
        m.base_roughness_u_texture = m.roughness_u_texture;
        m.base_roughness_v_texture = m.roughness_v_texture;
        microfacet_roughness("interface.");
        m.microfacet = false;  // the roughnesses are the coat's and the base's (Material::layered)
        m.coat_eta = eta_param("interface.eta", 1.5f);
        conductor_base("conductor.");
        layer_slab();
    } else if (type == "dielectric" || type == "thindielectric") {
        m.ior = eta_param("eta", 1.5f, &m.ior_spectrum);
        m.transmission = Rgb(1.0f);
        m.thin = type == "thindielectric";
        if (!m.thin) microfacet_roughness("");
    } else if (type == "subsurface") {
        subsurface_material(params, m, loc, d);  // builder_subsurface.cpp
        microfacet_roughness("");
    } else if (type == "diffusetransmission") {
        const float s = params.get_float("scale", 1.0f);
        m.diffuse = color_or_texture(params, "reflectance", Rgb(0.25f), &m.diffuse_texture, albedo, d) * s;
        m.diffuse_transmission = color_or_texture(params, "transmittance", Rgb(0.25f),
                                                  &m.diffuse_transmission_texture, albedo, d) *
                                 s;
        // pbrt-v4 clamps scale x value to [0, 1] (a textured one at each hit: Bsdf).
        const auto unit = [](Rgb c) {
            return Rgb(std::clamp(c.r, 0.0f, 1.0f), std::clamp(c.g, 0.0f, 1.0f), std::clamp(c.b, 0.0f, 1.0f));
        };
        if (m.diffuse_texture < 0) m.diffuse = unit(m.diffuse);
        if (m.diffuse_transmission_texture < 0) m.diffuse_transmission = unit(m.diffuse_transmission);
    } else if (type == "measured") {
        // pbrt-v4's MeasuredMaterial: an RGL .bsdf file (Dupuy & Jakob 2018), read and checked here.
        const Param* fp = params.find("filename");
        if (!fp) loc.fail(d + ": missing \"string filename\"");
        const std::string path = resolve(params.get_string("filename", ""), fp->loc);
        auto& cached = measured_files_[path];
        try {
            if (!cached) cached = io::read_rgl_bsdf(path);
        } catch (ParseError& e) {  // the file's own message, located where it is named
            fp->loc.add_to(e);
            throw;
        }
        m.measured = cached;
    } else if (type == "hair") {
        // pbrt-v4's HairMaterial: the absorption from `sigma_a`, else `reflectance` (pbrt-v3:
        // `color`), else the melanin concentrations, else eumelanin 1.3; what is given besides the
        // one used is ignored with a warning, as pbrt-v4 does.
        m.hair = true;
        const Param* sigma = params.find("sigma_a");
        const Param* refl = params.find("reflectance") ? params.find("reflectance") : params.find("color");
        const Param* eu = params.find("eumelanin");
        const Param* pheo = params.find("pheomelanin");
        const auto ignored = [&](const Param* p, const char* because) {
            if (p) warn(p->loc, d + ": \"" + p->name + "\" is ignored since \"" + because + "\" is given");
        };
        using C = scene::Material::HairColour;
        if (sigma) {
            m.hair_colour = C::SigmaA;
            int tex = -1;
            m.hair_sigma_a = color_or_texture(params, "sigma_a", Rgb(0.0f), &tex, SpectrumUse::Unbounded, d);
            if (tex >= 0) {  // a constant texture's value (pbrt-v4 also takes varying ones)
                const scene::Texture& t = scene_.textures[size_t(tex)];
                if (t.kind != scene::Texture::Kind::Constant)
                    sigma->loc.fail(d + ": a textured \"sigma_a\" must be a constant texture");
                m.hair_sigma_a = t.value;
            }
            ignored(refl, "sigma_a");
            ignored(eu, "sigma_a");
            ignored(pheo, "sigma_a");
        } else if (refl) {
            m.hair_colour = C::Reflectance;
            m.hair_reflectance =
                color_or_texture(params, refl->name, Rgb(0.0f), &m.hair_reflectance_texture, albedo, d);
            ignored(eu, "reflectance");
            ignored(pheo, "reflectance");
        } else {
            m.hair_colour = C::Melanin;
            m.hair_eumelanin = eu || pheo ? float_param(params, "eumelanin", 0.0f, d) : 1.3f;
            m.hair_pheomelanin = float_param(params, "pheomelanin", 0.0f, d);
        }
        m.hair_eta = float_param(params, "eta", 1.55f, d);
        m.hair_beta_m = float_param(params, "beta_m", 0.3f, d);
        m.hair_beta_n = float_param(params, "beta_n", 0.3f, d);
        m.hair_alpha = float_param(params, "alpha", 2.0f, d);
        for (const char* name : {"eta", "beta_m", "beta_n", "alpha", "eumelanin", "pheomelanin"}) {
            const Param* p = params.find(name);
            if (p && p->type != "texture" && !std::isfinite(params.get_float(name, 0.0f)))
                p->loc.fail(d + ": \"" + name + "\" must be finite");
        }
        if (!(m.hair_eta > 0)) params.find("eta")->loc.fail(d + ": \"eta\" must be positive");
    } else if (type == "interface" || type == "" || type == "none") {
        m.interface_only = true;
    } else if (type == "mix") {
        const std::vector<std::string> names = params.get_strings("materials");
        if (names.size() != 2) loc.fail(d + ": needs \"string materials\" with two names");
        int index[2];
        for (int k = 0; k < 2; ++k) {
            const auto it = named_materials_.find(names[size_t(k)]);
            if (it == named_materials_.end())
                params.find("materials")->loc.fail(d + ": unknown material \"" + names[size_t(k)] + "\"");
            index[k] = it->second;
        }
        m.mix_a = index[0];
        m.mix_b = index[1];
        if (const Param* p = params.find("amount"); p && p->type == "texture") {
            const auto it = float_textures_.find(p->strings[0]);
            if (it == float_textures_.end())
                p->loc.fail(d + ": unknown float texture \"" + p->strings[0] + "\"");
            m.mix_amount = 1;
            m.mix_amount_texture = it->second;
        } else if (p) {
            m.mix_amount = float_param(params, "amount", 0.5f, d);
            if (!std::isfinite(m.mix_amount)) p->loc.fail(d + ": \"amount\" must be finite");
        }
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
