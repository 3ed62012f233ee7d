// Photon maps to point-cloud columns (see photon_cloud.h), with the colour mapping that makes each
// map visible whatever its photon count: powers scale with 1 / emitted, so one scale per map.
#include "app/lib/photon_cloud.h"

#include <algorithm>
#include <span>

#include "core/error.h"
#include "core/format.h"
#include "io/image/tonemap.h"

namespace phos::app {
namespace {

// The kColourPercentile value of the photons' largest channel (1 for a map of black photons).
float colour_reference(std::span<const photon::Photon> photons) {
    std::vector<float> largest;
    largest.reserve(photons.size());
    for (const photon::Photon& p : photons) largest.push_back(p.colour().max());
    if (largest.empty()) return 1.0f;
    const auto at = largest.begin() + ptrdiff_t(kColourPercentile * double(largest.size() - 1));
    std::nth_element(largest.begin(), at, largest.end());
    return *at > 0 ? *at : 1.0f;
}

}  // namespace

const char* photon_map_label(int kind) {
    static const char* const names[photon::kMapCount] = {"global", "caustic", "indirect", "volume",
                                                         "volume-caustic"};
    return kind >= 0 && kind < photon::kMapCount ? names[kind] : "unknown";
}

std::vector<int> parse_photon_maps(const std::string& list) {
    std::vector<int> kinds;
    size_t at = 0;
    while (at <= list.size()) {
        size_t end = list.find(',', at);
        if (end == std::string::npos) end = list.size();
        const std::string name = list.substr(at, end - at);
        int kind = -1;
        for (int m = 0; m < photon::kMapCount; ++m)
            if (name == photon_map_label(m)) kind = m;
        if (kind < 0)
            throw InputError("--maps: '" + name +
                             "' is not one of global, caustic, indirect, volume, volume-caustic");
        if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) kinds.push_back(kind);
        at = end + 1;
    }
    return kinds;
}

io::PointCloud photon_cloud(const integrators::PhotonMaps& maps, const std::vector<int>& kinds) {
    io::PointCloud cloud;
    std::string ids = "map ids:";
    for (int m = 0; m < photon::kMapCount; ++m)
        ids += std::string(m ? ", " : " ") + std::to_string(m) + " " + photon_map_label(m);
    cloud.comments = {
        ids,
        "power_r power_g power_b: the photon's power in W as stored (the light's flux share / the photons "
        "emitted for its map)",
        "red green blue: power / the map's " + printf_string("%g", 100 * kColourPercentile) +
            "th-percentile largest channel (scaled down to keep the hue where a channel exceeds 1), sRGB",
        "dx dy dz: unit direction towards where the photon came from",
        "nx ny nz: surface normal at the photon (0 0 0: none, photons in media)"};

    size_t n = 0;
    for (const int m : kinds) n += maps.map[m].size();
    // Pointers stay valid: every column is added before any is used.
    cloud.columns.reserve(17);
    std::vector<io::PointColumn*> c;
    for (const char* name : {"x", "y", "z"}) c.push_back(&cloud.add_floats(name));
    for (const char* name : {"red", "green", "blue"}) c.push_back(&cloud.add_bytes(name));
    for (const char* name : {"power_r", "power_g", "power_b", "dx", "dy", "dz", "nx", "ny", "nz"})
        c.push_back(&cloud.add_floats(name));
    c.push_back(&cloud.add_bytes("map"));
    // Bounce counts when the maps were built with them (PhotonMapIntegrator::build_maps).
    bool bounces = true;
    for (const int m : kinds) bounces &= maps.bounces[m].size() == maps.map[m].size();
    if (bounces) {
        c.push_back(&cloud.add_bytes("bounces"));
        cloud.comments.push_back(
            "bounces: scattering events before the photon was stored (0: straight from a light; at most "
            "255)");
    }
    for (io::PointColumn* col : c) {
        if (col->is_float)
            col->floats.reserve(n);
        else
            col->bytes.reserve(n);
    }

    for (const int m : kinds) {
        const std::span<const photon::Photon> photons = maps.map[m].photons();
        const float reference = colour_reference(photons);
        double total[3] = {0, 0, 0};
        for (const photon::Photon& p : photons) {
            const Rgb power = p.colour();
            const Vec3 wi = p.wi(), normal = p.normal();
            Rgb shown = power * (1.0f / reference);
            if (shown.max() > 1) shown = shown * (1.0f / shown.max());
            const float f[] = {p.position.x, p.position.y, p.position.z};
            for (int k = 0; k < 3; ++k) c[size_t(k)]->floats.push_back(f[k]);
            c[3]->bytes.push_back(io::linear_to_srgb8(shown.r));
            c[4]->bytes.push_back(io::linear_to_srgb8(shown.g));
            c[5]->bytes.push_back(io::linear_to_srgb8(shown.b));
            const float g[] = {power.r, power.g, power.b, wi.x, wi.y, wi.z, normal.x, normal.y, normal.z};
            for (int k = 0; k < 9; ++k) c[size_t(6 + k)]->floats.push_back(g[k]);
            c[15]->bytes.push_back(uint8_t(m));
            if (bounces) c[16]->bytes.push_back(maps.bounces[m][size_t(&p - photons.data())]);
            total[0] += power.r, total[1] += power.g, total[2] += power.b;
        }
        cloud.comments.push_back(
            "map " + std::to_string(m) + " " + photon_map_label(m) + ": " + std::to_string(photons.size()) +
            " photons from " + std::to_string(maps.emitted[m]) + " emitted, total power" +
            printf_string(" %.6g", total[0]) + printf_string(" %.6g", total[1]) +
            printf_string(" %.6g W", total[2]) + ", colour 1 at" + printf_string(" %.6g W", reference));
    }
    return cloud;
}

const std::vector<std::string>& photon_text_columns() {
    static const std::vector<std::string> columns{"x",       "y",  "z",  "power_r", "power_g",
                                                  "power_b", "dx", "dy", "dz"};
    return columns;
}

}  // namespace phos::app
