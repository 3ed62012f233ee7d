// `.mat` files: a surface (diffuse, mirror, Fresnel dielectric, texture, emission) and the
// homogeneous medium inside objects made of it. A `.mat` named by many objects is read once.
#include <cmath>

#include "core/error.h"
#include "core/format.h"
#include "core/log.h"
#include "core/spelling.h"
#include "io/scene_format/reader.h"
#include "io/text/image_texture.h"

namespace phos::io::scene_format {

namespace {

const std::vector<std::string> kMatKeys = {"diffuse",    "specular",   "transmission", "ior",     "texture",
                                           "absorption", "scattering", "phase",        "emission"};

const char* channel_name(int c) { return c == 0 ? "red" : c == 1 ? "green" : "blue"; }

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
            fail(l.keyword,
                 "unknown key '" + k + "' in a .mat file" +
                     (guess.empty() ? "" : "; did you mean '" + guess + "'?") +
                     " (keys: diffuse, specular, transmission, ior, texture, absorption, scattering, "
                     "phase, emission)");
        }
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
    if (m.ior != 1.0f && m.transmission.is_black())
        log::warn(file().name + ": ior is set but transmission is 0: the ior has no effect");

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
