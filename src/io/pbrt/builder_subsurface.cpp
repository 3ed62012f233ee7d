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
#include "io/pbrt/measured_media.h"

namespace phos::io::pbrt {
namespace {

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
