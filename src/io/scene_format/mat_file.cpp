// `.mat` files: a surface (diffuse, mirror, Fresnel dielectric, dispersive or not, texture,
// emission) and the homogeneous medium inside objects made of it. A `.mat` named by many objects
// is read once. (spectrum::Distribution and the named glasses come with scene/material.h, whose
// Material holds the dispersion.)
#include <cmath>

#include "core/error.h"
#include "core/format.h"
#include "core/log.h"
#include "core/spelling.h"
#include "io/scene_format/reader.h"
#include "io/text/image_texture.h"
#include "spectrum/dispersion.h"
#include "spectrum/distribution.h"

namespace phos::io::scene_format {

namespace {

const std::vector<std::string> kMatKeys = {"diffuse",    "specular",  "transmission", "ior",     "abbe",
                                           "cauchy",     "sellmeier", "glass",        "texture", "absorption",
                                           "scattering", "phase",     "emission"};

const char* channel_name(int c) { return c == 0 ? "red" : c == 1 ? "green" : "blue"; }

// The named glasses as a .mat names them: "BK7" for pbrt-v4's "glass-BK7".
std::vector<std::string> glass_names() {
    std::vector<std::string> names;
    for (const spectrum::NamedGlass& g : spectrum::named_glasses()) names.push_back(g.name.substr(6));
    return names;
}

std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

}  // namespace

const MatFile& Reader::read_mat(const FileArg& f) {
    const std::string key = f.canonical.string();
    if (const auto it = mats_.find(key); it != mats_.end()) return it->second;

    open(f);
    std::map<std::string, int> seen;
    scene::Material m;
    m.name = f.name;
    Rgb sigma_a(0.0f), sigma_s(0.0f), emission(0.0f);
    float g = 0;
    int texture_index = -1;
    // The last of the diffuse / specular / transmission lines, where an energy error is reported.
    const Line* last_term = nullptr;
    // The dispersion key (abbe, cauchy, sellmeier or glass; one at most) and what it gives: the
    // index over wavelength, or for abbe the Abbe number that `ior` completes.
    const Line* dispersion_line = nullptr;
    std::optional<spectrum::Distribution> dispersion;
    double abbe = 0;
    const Line* ior_line = nullptr;
    const auto dispersion_key = [&](const Line& l) -> std::optional<spectrum::Distribution> {
        const std::string& k = l.keyword.text;
        if (k == "abbe") {
            abbe = numbers(l, 1, "V_d")[0];
            if (!(abbe > 0))
                fail(l.args[0], "abbe: the Abbe number V_d must be positive, got '" + l.args[0].text + "'");
            return std::nullopt;  // completed by `ior` after the last line
        }
        if (k == "cauchy") {
            const std::vector<double> v = numbers(l, 2, "A B (B in um^2)");
            for (size_t i = 0; i < 2; ++i)
                if (!(v[i] > 0))
                    fail(l.args[i], std::string("cauchy: ") + (i == 0 ? "A" : "B") +
                                        " must be positive, got '" + l.args[i].text + "'");
            return spectrum::Distribution::cauchy(float(v[0]), float(v[1]));
        }
        if (k == "sellmeier") {
            const std::vector<double> v = numbers(l, 6, "B1 B2 B3 C1 C2 C3 (C in um^2)");
            require_non_negative(l, v, 0, 6);
            if (!(v[0] + v[1] + v[2] > 0))
                fail(l.args[0], "sellmeier: B1, B2 and B3 are all 0 (no dispersion)");
            spectrum::Sellmeier sm;
            for (size_t i = 0; i < 3; ++i) sm.B[i] = v[i], sm.C[i] = v[i + 3];
            // A resonance (lambda^2 = C) inside the visible range makes the index infinite there.
            for (size_t i = 3; i < 6; ++i) {
                const double nm = std::sqrt(v[i]) * 1e3;
                if (nm >= 360 && nm <= 830)
                    fail(l.args[i], "sellmeier: C" + std::to_string(i - 2) + " = " + l.args[i].text +
                                        " um^2 puts a resonance at " + printf_string("%.0f", nm) +
                                        " nm, inside the visible range (360-830 nm)");
            }
            for (int nm = 360; nm <= 830; ++nm)
                if (const double n = sm.ior(nm); !(std::isfinite(n) && n > 0))
                    fail(l.keyword,
                         "sellmeier: the index is not a positive number at " + std::to_string(nm) + " nm");
            return spectrum::Distribution::sellmeier(sm);
        }
        require_args(l, 1, "1 argument: a glass name");  // glass
        const std::string& name = l.args[0].text;
        const std::string bare = name.rfind("glass-", 0) == 0 ? name.substr(6) : name;
        if (const auto g = spectrum::named_glass("glass-" + bare))
            return spectrum::Distribution::sellmeier(*g);
        const std::string guess = nearest_name(bare, glass_names());
        fail(l.args[0], "glass: unknown glass '" + name + "'" +
                            (guess.empty() ? "" : "; did you mean '" + guess + "'?") +
                            " (glasses: " + join(glass_names()) + ")");
    };
    for (const Line& l : file().lines) {
        const std::string& k = l.keyword.text;
        const auto colour = [&] {
            reject_duplicate(l, seen);
            const std::vector<double> v = numbers(l, 3, "r g b");
            require_non_negative(l, v, 0, 3);
            return rgb_at(v, 0);
        };
        if (k == "diffuse") {
            m.diffuse = colour();
            last_term = &l;
        } else if (k == "specular") {
            m.specular = colour();
            m.shininess = scene::Material::kMirrorShininess;  // a perfect mirror
            last_term = &l;
        } else if (k == "transmission") {
            m.transmission = colour();
            last_term = &l;
        } else if (k == "absorption") {
            sigma_a = colour();
        } else if (k == "scattering") {
            sigma_s = colour();
        } else if (k == "emission") {
            emission = colour();
        } else if (k == "ior") {
            reject_duplicate(l, seen);
            const double n = numbers(l, 1, "n")[0];
            if (!(n > 0))
                fail(l.args[0],
                     "ior: the index of refraction must be positive, got '" + l.args[0].text + "'");
            m.ior = float(n);
            ior_line = &l;
        } else if (k == "abbe" || k == "cauchy" || k == "sellmeier" || k == "glass") {
            reject_duplicate(l, seen);
            if (dispersion_line)
                fail(l.keyword, k + ": the dispersion is already given by '" + dispersion_line->keyword.text +
                                    "' (line " + std::to_string(dispersion_line->keyword.line) +
                                    "); a material takes one of abbe, cauchy, sellmeier, glass");
            dispersion_line = &l;
            dispersion = dispersion_key(l);
        } else if (k == "phase") {
            reject_duplicate(l, seen);
            const double v = numbers(l, 1, "g")[0];
            if (!(v > -1 && v < 1))
                fail(l.args[0],
                     "phase: the Henyey-Greenstein g must be in (-1, 1), got '" + l.args[0].text + "'");
            g = float(v);
        } else if (k == "texture") {
            reject_duplicate(l, seen);
            require_args(l, 1, "1 argument: an image file");
            texture_index = texture(file_argument(l, 0, "texture"));
        } else {
            const std::string guess = nearest_name(k, kMatKeys);
            fail(l.keyword, "unknown key '" + k + "' in a .mat file" +
                                (guess.empty() ? "" : "; did you mean '" + guess + "'?") +
                                " (keys: " + join(kMatKeys) + ")");
        }
    }
    if (dispersion_line) {
        const Token& at = dispersion_line->keyword;
        if (at.text == "abbe") {
            // The Abbe number describes the dispersion around the index `ior` gives at the d line.
            if (!ior_line)
                fail(at,
                     "abbe: needs 'ior', the index n_d at the d line (587.6 nm) that the Abbe number "
                     "V_d completes");
            if (!(m.ior > 1))
                fail(ior_line->args[0],
                     "ior: with 'abbe' the index n_d must exceed 1, got '" + ior_line->args[0].text + "'");
            dispersion = spectrum::Distribution::abbe(m.ior, float(abbe));
        } else {
            const float n_d = (*dispersion)(float(spectrum::kLineD));
            if (ior_line)
                fail(ior_line->keyword,
                     "ior: the index is given by '" + at.text + "' (line " + std::to_string(at.line) + "), " +
                         printf_string("%.5g", double(n_d)) + " at the d line (587.6 nm); give one of them");
            m.ior = n_d;
        }
        m.ior_spectrum = dispersion;
    }
    // The dissertation's Russian roulette picks diffuse, specular or transmission with these as
    // probabilities: their sum must not exceed 1 (small rounding in the file tolerated).
    const Rgb sum = m.diffuse + m.specular + m.transmission;
    for (int c = 0; c < 3; ++c)
        if (sum[c] > 1.0f + 1e-5f) {
            fail(last_term->keyword, "diffuse + specular + transmission is " +
                                         printf_string("%g", double(sum[c])) + " in the " + channel_name(c) +
                                         " channel; it must not exceed 1 (energy conservation)");
        }
    if (texture_index >= 0) {
        m.diffuse_texture = texture_index;
        if (m.diffuse.is_black())
            log::warn(file().name +
                      ": the texture multiplies diffuse, which is 0: the surface is black (add "
                      "'diffuse 1 1 1' to see the texture's colours)");
    }
    if ((m.ior != 1.0f || m.ior_spectrum) && m.transmission.is_black()) {
        const std::string key = dispersion_line ? dispersion_line->keyword.text : "ior";
        log::warn(file().name + ": " + key + " is set but transmission is 0: the " + key + " has no effect");
    }

    MatFile mat;
    mat.textured = texture_index >= 0;
    mat.emission = emission;
    const bool has_medium = !(sigma_a + sigma_s).is_black();
    if (has_medium) {
        scene::Medium medium;
        medium.name = f.name;
        medium.kind = scene::Medium::Kind::Homogeneous;
        medium.sigma_a = sigma_a;
        medium.sigma_s = sigma_s;
        medium.g = g;
        mat.medium = int(scene_.media.size());
        scene_.media.push_back(std::move(medium));
    } else if (seen.count("phase")) {
        log::warn(file().name + ": phase is set but the material has no absorption or scattering");
    }
    // Nothing but a medium: the boundary is invisible (smoke, fog, milk).
    m.interface_only = has_medium && sum.is_black() && emission.is_black() && texture_index < 0;
    mat.boundary = has_medium || !m.transmission.is_black();
    mat.material = int(scene_.materials.size());
    scene_.materials.push_back(std::move(m));
    close();
    return mats_.emplace(key, mat).first->second;
}

int Reader::texture(const FileArg& f) {
    const std::string key = f.canonical.string();
    if (const auto it = textures_.find(key); it != textures_.end()) return it->second;
    scene::Texture tex;
    try {
        tex = text::read_image_texture(f.path.string());
    } catch (ParseError& e) {
        add_includers(e, f.token);
        throw;
    } catch (const std::exception& e) {  // InputError, or a decoder library's own exception
        fail(f.token, "texture: cannot read '" + f.token.text + "': " + e.what());
    }
    const int index = int(scene_.textures.size());
    scene_.textures.push_back(std::move(tex));
    textures_[key] = index;
    return index;
}

}  // namespace phos::io::scene_format
