// SceneBuilder: pbrt-v4's "subsurface" material as a random walk. pbrt-v4 renders it with a
// tabulated photon-beam-diffusion BSSRDF under a (rough) dielectric boundary; phos gives the shape
// that dielectric boundary and fills it with the homogeneous medium the BSSRDF describes (a
// Henyey-Greenstein phase function), which its integrators walk like any medium inside glass.
// The coefficients come as pbrt-v4's SubsurfaceMaterial::Create reads them: a named measured
// medium, sigma_a and sigma_s, or reflectance and mfp (inverted through the diffusion table,
// beam_diffusion.h), with "scale".
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <unordered_map>

#include "core/error.h"
#include "io/pbrt/beam_diffusion.h"
#include "io/pbrt/builder.h"

namespace phos::io::pbrt {
namespace {

// Measured scattering properties as pbrt-v4 names them (its GetMediumScatteringProperties): the
// reduced scattering coefficient sigma_s' and the absorption coefficient sigma_a, RGB, in 1/mm.
// pbrt-v4 uses them unconverted as 1/scene-unit, sigma_s' as sigma_s with g = 0.
struct MeasuredMedium {
    Rgb sigma_prime_s, sigma_a;
};
const std::map<std::string, MeasuredMedium>& measured_media() {
    static const std::map<std::string, MeasuredMedium> table = {
        // Jensen, Marschner, Levoy & Hanrahan 2001, "A Practical Model for Subsurface Light
        // Transport".
        {"Apple", {{2.29f, 2.39f, 1.97f}, {0.0030f, 0.0034f, 0.046f}}},
        {"Chicken1", {{0.15f, 0.21f, 0.38f}, {0.015f, 0.077f, 0.19f}}},
        {"Chicken2", {{0.19f, 0.25f, 0.32f}, {0.018f, 0.088f, 0.20f}}},
        {"Cream", {{7.38f, 5.47f, 3.15f}, {0.0002f, 0.0028f, 0.0163f}}},
        {"Ketchup", {{0.18f, 0.07f, 0.03f}, {0.061f, 0.97f, 1.45f}}},
        {"Marble", {{2.19f, 2.62f, 3.00f}, {0.0021f, 0.0041f, 0.0071f}}},
        {"Potato", {{0.68f, 0.70f, 0.55f}, {0.0024f, 0.0090f, 0.12f}}},
        {"Skimmilk", {{0.70f, 1.22f, 1.90f}, {0.0014f, 0.0025f, 0.0142f}}},
        {"Skin1", {{0.74f, 0.88f, 1.01f}, {0.032f, 0.17f, 0.48f}}},
        {"Skin2", {{1.09f, 1.59f, 1.79f}, {0.013f, 0.070f, 0.145f}}},
        {"Spectralon", {{11.6f, 20.4f, 14.9f}, {0.00f, 0.00f, 0.00f}}},
        {"Wholemilk", {{2.55f, 3.21f, 3.77f}, {0.0011f, 0.0024f, 0.014f}}},
        // Narasimhan, Gupta, Donner, Ramamoorthi, Nayar & Jensen 2006, "Acquiring Scattering
        // Properties of Participating Media by Dilution".
        {"Lowfat Milk", {{0.89187f, 1.5136f, 2.532f}, {0.002875f, 0.00575f, 0.0115f}}},
        {"Reduced Milk", {{2.4858f, 3.1669f, 4.5214f}, {0.0025556f, 0.0051111f, 0.012778f}}},
        {"Regular Milk", {{4.5513f, 5.8294f, 7.136f}, {0.0015333f, 0.0046f, 0.019933f}}},
        {"Espresso", {{0.72378f, 0.84557f, 1.0247f}, {4.7984f, 6.5751f, 8.8493f}}},
        {"Mint Mocha Coffee", {{0.31602f, 0.38538f, 0.48131f}, {3.772f, 5.8228f, 7.82f}}},
        {"Lowfat Soy Milk", {{0.30576f, 0.34233f, 0.61664f}, {0.0014375f, 0.0071875f, 0.035937f}}},
        {"Regular Soy Milk", {{0.59223f, 0.73866f, 1.4693f}, {0.0019167f, 0.0095833f, 0.065167f}}},
        {"Lowfat Chocolate Milk", {{0.64925f, 0.83916f, 1.1057f}, {0.0115f, 0.0368f, 0.1564f}}},
        {"Regular Chocolate Milk", {{1.4585f, 2.1289f, 2.9527f}, {0.010063f, 0.043125f, 0.14375f}}},
        {"Coke", {{8.9053e-05f, 8.372e-05f, 0.0f}, {0.10014f, 0.16503f, 0.2468f}}},
        {"Pepsi", {{6.1697e-05f, 4.2564e-05f, 0.0f}, {0.091641f, 0.14158f, 0.20729f}}},
        {"Sprite", {{6.0306e-06f, 6.4139e-06f, 6.5504e-06f}, {0.001886f, 0.0018308f, 0.0020025f}}},
        {"Gatorade", {{0.0024574f, 0.003007f, 0.0037325f}, {0.024794f, 0.019289f, 0.008878f}}},
        {"Chardonnay", {{1.7982e-05f, 1.3758e-05f, 1.2023e-05f}, {0.010782f, 0.011855f, 0.023997f}}},
        {"White Zinfandel", {{1.7501e-05f, 1.9069e-05f, 1.288e-05f}, {0.012072f, 0.016184f, 0.019843f}}},
        {"Merlot", {{2.1129e-05f, 0.0f, 0.0f}, {0.11632f, 0.25191f, 0.29434f}}},
        {"Budweiser Beer", {{2.4356e-05f, 2.4079e-05f, 1.0564e-05f}, {0.011492f, 0.024911f, 0.057786f}}},
        {"Coors Light Beer", {{5.0922e-05f, 4.301e-05f, 0.0f}, {0.006164f, 0.013984f, 0.034983f}}},
        {"Clorox", {{0.0024035f, 0.0031373f, 0.003991f}, {0.0033542f, 0.014892f, 0.026297f}}},
        {"Apple Juice", {{0.00013612f, 0.00015836f, 0.000227f}, {0.012957f, 0.023741f, 0.052184f}}},
        {"Cranberry Juice", {{0.00010402f, 0.00011646f, 7.8139e-05f}, {0.039437f, 0.094223f, 0.12426f}}},
        {"Grape Juice", {{5.382e-05f, 0.0f, 0.0f}, {0.10404f, 0.23958f, 0.29325f}}},
        {"Ruby Grapefruit Juice", {{0.011002f, 0.010927f, 0.011036f}, {0.085867f, 0.18314f, 0.25262f}}},
        {"White Grapefruit Juice", {{0.22826f, 0.23998f, 0.32748f}, {0.0138f, 0.018831f, 0.056781f}}},
        {"Shampoo", {{0.0007176f, 0.0008303f, 0.0009016f}, {0.014107f, 0.045693f, 0.061717f}}},
        {"Strawberry Shampoo", {{0.00015671f, 0.00015947f, 1.518e-05f}, {0.01449f, 0.05796f, 0.075823f}}},
        {"Head & Shoulders Shampoo", {{0.023805f, 0.028804f, 0.034306f}, {0.084621f, 0.15688f, 0.20365f}}},
        {"Lemon Tea Powder", {{0.040224f, 0.045264f, 0.051081f}, {2.4288f, 4.5757f, 7.2127f}}},
        {"Orange Powder", {{0.00015617f, 0.00017482f, 0.0001762f}, {0.001449f, 0.003441f, 0.007863f}}},
        {"Pink Lemonade Powder",
         {{0.00012103f, 0.00013073f, 0.00012528f}, {0.001165f, 0.002366f, 0.003195f}}},
        {"Cappuccino Powder", {{1.8436f, 2.5851f, 2.1662f}, {35.844f, 49.547f, 61.084f}}},
        {"Salt Powder", {{0.027333f, 0.032451f, 0.031979f}, {0.28415f, 0.3257f, 0.34148f}}},
        {"Sugar Powder", {{0.00022272f, 0.00025513f, 0.000271f}, {0.012638f, 0.031051f, 0.050124f}}},
        {"Suisse Mocha Powder", {{2.7979f, 3.5452f, 4.3365f}, {17.502f, 27.004f, 35.433f}}},
        {"Pacific Ocean Surface Water",
         {{0.0001764f, 0.00032095f, 0.00019617f}, {0.031845f, 0.031324f, 0.030147f}}},
    };
    return table;
}

// Whether a triangle mesh is closed: every edge, its vertices identified by position (meshes
// split at uv or normal seams repeat vertices), is shared by exactly two triangles.
bool mesh_is_closed(const scene::TriangleMesh& mesh) {
    if (mesh.indices.empty() || !mesh.patches.empty()) return mesh.indices.empty() && mesh.patches.empty();
    struct PositionHash {
        size_t operator()(const Vec3& p) const {
            const std::hash<float> h;
            return h(p.x) ^ (h(p.y) * 0x9e3779b97f4a7c15ull) ^ (h(p.z) * 0xbf58476d1ce4e5b9ull);
        }
    };
    struct PositionEqual {
        bool operator()(const Vec3& a, const Vec3& b) const { return a.x == b.x && a.y == b.y && a.z == b.z; }
    };
    std::unordered_map<Vec3, uint32_t, PositionHash, PositionEqual> ids;
    std::vector<uint32_t> id(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        id[i] = ids.emplace(mesh.positions[i], uint32_t(ids.size())).first->second;
    std::unordered_map<uint64_t, int> edges;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = id[mesh.indices[t + size_t(k)]], b = id[mesh.indices[t + size_t((k + 1) % 3)]];
            if (a > b) std::swap(a, b);
            ++edges[(uint64_t(a) << 32) | b];
        }
    for (const auto& [edge, count] : edges)
        if (count != 2) return false;
    return true;
}

}  // namespace

void SceneBuilder::subsurface_material(const ParamList& params, scene::Material& m, const Loc& loc,
                                       const std::string& d) {
    // The boundary: pbrt-v4's DielectricBxDF of index "eta" (a float, 1.33).
    const float eta = params.get_float("eta", 1.33f);
    if (!(eta > 0) || !std::isfinite(eta)) params.find("eta")->loc.fail(d + ": \"eta\" must be positive");
    m.ior = eta;
    m.transmission = Rgb(1.0f);

    // A coefficient parameter's colour (a constant texture gives its value; a homogeneous medium
    // holds one value, so other textures are refused).
    const auto coefficient = [&](const std::string& name, SpectrumUse use) -> std::optional<Rgb> {
        const Param* p = params.find(name);
        if (p && p->type == "texture") {
            const std::string& t = p->strings[0];
            int index = -1;
            if (const auto it = spectrum_textures_.find(t); it != spectrum_textures_.end())
                index = it->second;
            else if (const auto jt = float_textures_.find(t); jt != float_textures_.end())
                index = jt->second;
            if (index < 0) p->loc.fail(d + ": unknown texture \"" + t + "\"");
            const scene::Texture& tex = scene_.textures[size_t(index)];
            if (tex.kind != scene::Texture::Kind::Constant)
                p->loc.fail(d + ": a textured \"" + name +
                            "\" is not supported (the material's medium is homogeneous); give a value");
            return tex.value;
        }
        return color(params, name, use);
    };

    scene::Medium medium;
    medium.name = "subsurface " + loc.str();
    float g = params.get_float("g", 0.0f);
    if (!(g > -1 && g < 1)) params.find("g")->loc.fail(d + ": \"g\" must be in (-1, 1)");
    const float scale = params.get_float("scale", 1.0f);
    if (!(scale >= 0) || !std::isfinite(scale))
        params.find("scale")->loc.fail(d + ": \"scale\" must be finite and >= 0");
    medium.scale = scale;
    const std::string name = params.get_string("name", "");
    if (!name.empty()) {
        // 1. A named measured medium: reduced coefficients, so g is 0 (pbrt-v4 warns about another g).
        const auto it = measured_media().find(name);
        if (it == measured_media().end()) {
            std::string names;
            for (const auto& [n, mm] : measured_media()) names += (names.empty() ? "" : ", ") + n;
            params.find("name")->loc.fail(d + ": unknown named medium \"" + name + "\" (pbrt-v4 names " +
                                          names + ")");
        }
        if (g != 0)
            warn(params.find("g")->loc, d + ": a non-zero \"g\" is ignored with a named medium (g = 0)");
        g = 0;
        medium.sigma_a = it->second.sigma_a;
        medium.sigma_s = it->second.sigma_prime_s;
    } else {
        // 2. sigma_a and sigma_s, both or neither.
        const auto sigma_a = coefficient("sigma_a", SpectrumUse::Unbounded);
        const auto sigma_s = coefficient("sigma_s", SpectrumUse::Unbounded);
        if (sigma_a.has_value() != sigma_s.has_value())
            params.find(sigma_a ? "sigma_a" : "sigma_s")
                ->loc.fail(d + ": \"" + std::string(sigma_a ? "sigma_a" : "sigma_s") + "\" needs \"" +
                           std::string(sigma_a ? "sigma_s" : "sigma_a") + "\" too");
        if (sigma_a) {
            medium.sigma_a = *sigma_a;
            medium.sigma_s = *sigma_s;
        } else if (const auto reflectance = coefficient("reflectance", SpectrumUse::Albedo)) {
            // 3. The diffuse reflectance and mean free path (times scale): the albedo whose
            // photon-beam-diffusion effective albedo is the reflectance, per channel.
            const Rgb mfp = coefficient("mfp", SpectrumUse::Unbounded).value_or(Rgb(1.0f)) * scale;
            const BeamDiffusionTable table(g, eta);
            for (int c = 0; c < 3; ++c) {
                const float rho = table.albedo_for(std::clamp((*reflectance)[c], 0.0f, 1.0f));
                const float sigma_t = mfp[c] > 0 ? 1 / mfp[c] : 0.0f;
                medium.sigma_s[c] = rho * sigma_t;
                medium.sigma_a[c] = (1 - rho) * sigma_t;
            }
            medium.scale = 1;  // "scale" multiplied the mean free path
        } else {
            // 4. Nothing given: pbrt-v4's defaults (whole milk's coefficients, 1/mm).
            medium.sigma_a = Rgb(0.0011f, 0.0024f, 0.014f);
            medium.sigma_s = Rgb(2.55f, 3.21f, 3.77f);
        }
    }
    for (int c = 0; c < 3; ++c)
        if (!(medium.sigma_a[c] >= 0) || !(medium.sigma_s[c] >= 0) || !std::isfinite(medium.sigma_a[c]) ||
            !std::isfinite(medium.sigma_s[c]))
            loc.fail(d + ": the medium's coefficients must be finite and not negative");
    medium.g = g;
    m.subsurface_medium = int(scene_.media.size());
    scene_.media.push_back(std::move(medium));
}

void SceneBuilder::subsurface_interior(scene::Shape& shape, const Loc& loc) {
    // The material's medium, or the first one a mix reaches (depth-limited: mixes may nest).
    int medium = -1;
    const auto find = [&](auto&& self, int material, int depth) -> void {
        if (medium >= 0 || material < 0 || size_t(material) >= scene_.materials.size() || depth > 16) return;
        const scene::Material& m = scene_.materials[size_t(material)];
        if (m.subsurface_medium >= 0) medium = m.subsurface_medium;
        if (m.is_mix()) self(self, m.mix_a, depth + 1), self(self, m.mix_b, depth + 1);
    };
    find(find, shape.material, 0);
    if (medium < 0) return;
    if (shape.media.inside >= 0 && shape.media.inside != medium)
        warn(loc,
             "a subsurface material's shape: its medium replaces the MediumInterface's inside medium \"" +
                 scene_.media[size_t(shape.media.inside)].name +
                 "\" (pbrt-v4's BSSRDF never enters the shape's interior either)");
    shape.media.inside = medium;
    using Kind = scene::Shape::Kind;
    const bool closed = shape.kind == Kind::Mesh       ? mesh_is_closed(shape.mesh)
                        : shape.kind == Kind::Sphere   ? !shape.partial
                        : shape.kind == Kind::Box      ? true
                        : shape.kind == Kind::Cylinder ? shape.capped
                                                       : false;
    if (!closed)
        warn(loc,
             "a subsurface material on a surface that does not enclose a volume: light that enters "
             "it travels in the material's medium until it meets another surface");
}

}  // namespace phos::io::pbrt
