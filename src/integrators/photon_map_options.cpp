// The option table of the two-pass photon mapper (see photon_map_options.h).
#include "integrators/photon_map_options.h"

#include <algorithm>
#include <string>

#include "integrators/registry.h"

namespace phos::integrators {
namespace {

using options::at_least;
using options::between;
using options::ValueError;
using B = options::TableBuilder<PhotonMapOptions>;

// Every option of the table is for the photon mapper alone.
constexpr options::IntegratorSet kPhotonMap = integrator_set({IntegratorKind::PhotonMap});

// --NAME N, --NAME-samples K, --NAME-radius R, --NAME-filter none|cone|cone:K|gauss, --NAME-cone-k K.
void add_map(B& b, const std::string& name, PhotonMapSettings PhotonMapOptions::*map, const std::string& what,
             const std::string& radius_default) {
    auto& n = b.number(
        name, [map](auto& o) -> auto& { return (o.*map).photons; }, "N", between(0, 2147483648.0),
        "stored photons wanted in the " + what + " map");
    n.applies_to = kPhotonMap;
    n.effect = options::Effect::Image;
    b.number(
         name + "-samples", [map](auto& o) -> auto& { return (o.*map).samples; }, "K", between(1, 100000),
         "photons per " + name + " radiance estimate (k nearest)")
        .applies_to = kPhotonMap;
    auto& r = b.number(
        name + "-radius", [map](auto& o) -> auto& { return (o.*map).radius; }, "R", between(0, 1e30),
        "maximum " + name + " estimate radius in scene units (0 = automatic)");
    r.applies_to = kPhotonMap;
    r.default_text = "automatic: " + radius_default + " x the scene's bounding-sphere radius";
    auto& f = b.custom(
        name + "-filter", "KIND", 1, name + " estimate filter (cone:K also sets the cone constant)",
        [map](PhotonMapOptions& o, const std::vector<std::string>& v) {
            PhotonMapSettings& s = o.*map;
            std::string k = v.at(0);
            const size_t colon = k.find(':');
            float cone_k = s.cone_k;
            if (colon != std::string::npos) {
                cone_k = float(options::parse_number(k.substr(colon + 1)));
                k = k.substr(0, colon);
                if (k != "cone") throw ValueError("only the cone filter takes a constant: '" + v[0] + "'");
                B::check_range(cone_k, at_least(1));
            }
            photon::FilterKind kind;
            if (!photon::parse_filter_kind(k, kind))
                throw ValueError("'" + v[0] + "' is not one of none, cone, cone:K, gauss");
            s.filter = kind;
            s.cone_k = cone_k;
        },
        [map](const PhotonMapOptions& o) { return std::string(photon::filter_name((o.*map).filter)); });
    f.applies_to = kPhotonMap;
    f.range_text = "none|cone|cone:K|gauss";
    b.number(
         name + "-cone-k", [map](auto& o) -> auto& { return (o.*map).cone_k; }, "K", between(1, 1e6),
         "cone filter constant k of the " + name + " estimate")
        .applies_to = kPhotonMap;
}

// --NAME N, --NAME-samples K, --NAME-radius R for a volume map (always a box kernel).
void add_volume_map(B& b, const std::string& name, PhotonMapSettings PhotonMapOptions::*map,
                    const std::string& what, const std::string& radius_default) {
    auto& n = b.number(
        name + "-photons", [map](auto& o) -> auto& { return (o.*map).photons; }, "N",
        between(0, 2147483648.0), "stored photons wanted in the " + what + " map (scenes with media)");
    n.applies_to = kPhotonMap;
    n.effect = options::Effect::Image;
    b.number(
         name + "-samples", [map](auto& o) -> auto& { return (o.*map).samples; }, "K", between(1, 100000),
         "photons per " + what + " radiance estimate (k nearest)")
        .applies_to = kPhotonMap;
    auto& r = b.number(
        name + "-radius", [map](auto& o) -> auto& { return (o.*map).radius; }, "R", between(0, 1e30),
        "maximum " + what + " estimate radius in scene units (0 = automatic)");
    r.applies_to = kPhotonMap;
    r.default_text = "automatic: " + radius_default + " x the scene's bounding-sphere radius";
}

}  // namespace

const options::Table& photon_map_options() {
    static const options::Table table = [] {
        B b("Photon map", "two-pass photon mapping (--integrator photonmap), see docs/photon-mapping.md");
        add_map(b, "global", &PhotonMapOptions::global, "global (final gather)", "0.1");
        add_map(b, "caustic", &PhotonMapOptions::caustic, "caustic", "0.05");
        add_map(b, "indirect", &PhotonMapOptions::indirect, "indirect (--fast-global)", "0.1");
        add_volume_map(b, "volume", &PhotonMapOptions::volume, "volume (multiple scattering)", "0.1");
        add_volume_map(b, "volume-caustic", &PhotonMapOptions::volume_caustic, "volume caustic", "0.05");
        auto pm = [&](options::Option& o) -> options::Option& {
            o.applies_to = kPhotonMap;
            return o;
        };
        pm(b.choice("volume-estimate", &PhotonMapOptions::volume_estimate,
                    {{VolumeEstimate::Beam, "beam"}, {VolumeEstimate::March, "march"}},
                    "volume estimate along camera rays in media: beam (one beam radiance estimate per "
                    "stretch, each photon's radius from its --volume-samples nearest) or march (ray "
                    "marching, a k-nearest estimate every --volume-step)"))
            .value_name = "KIND";
        pm(b.number("volume-step", &PhotonMapOptions::volume_step, "D", between(0, 1e30),
                    "ray-marching step along camera rays in media, scene units (0 = automatic); with "
                    "--volume-estimate beam, the step of the transmittance table in grid media"))
            .default_text = "automatic: the volume radius / 2";
        pm(b.number("photons", &PhotonMapOptions::photons, "N", between(0, 1099511627776.0),
                    "photons to emit (0 = until every map holds its budget)"))
            .default_text = "0 (until every map holds its budget)";
        pm(b.number("max-emitted", &PhotonMapOptions::max_emitted, "N", between(0, 1099511627776.0),
                    "stop emitting after this many photons even if a budget is unmet (0 = automatic)"))
            .default_text = "automatic: 200 x the largest budget, at least 10^6";
        pm(b.number("max-photon-depth", &PhotonMapOptions::max_photon_depth, "N", between(0, 100000),
                    "scattering events per photon path"));
        pm(b.number("gather-rays", &PhotonMapOptions::gather_rays, "N", between(1, 1 << 20),
                    "final-gather rays per camera sample"));
        pm(b.flag("fast-global", &PhotonMapOptions::fast_global,
                  "indirect light from the indirect map at the first hit, no final gather"));
        pm(b.flag("photon-viz", &PhotonMapOptions::photon_viz,
                  "show the global map's radiance estimate at the first hit (debug view)"));
        pm(b.flag("irradiance-cache", &PhotonMapOptions::irradiance_cache,
                  "precomputed irradiance at global photons (and in-scattered light at volume photons) for "
                  "the final gather",
                  true, "no-irradiance-cache"));
        pm(b.number("caustic-min-radius-pixels", &PhotonMapOptions::caustic_min_pixels, "P", between(0, 1e6),
                    "the caustic estimate's radius never shrinks below this many pixel footprints (0 = plain "
                    "k nearest)"));
        pm(b.flag("projection-maps", &PhotonMapOptions::projection_maps,
                  "emit caustic photons only towards mirrors and glass, weighted by the share of emission "
                  "aimed there",
                  true, "no-projection-maps"));
        pm(b.number("irradiance-cache-stride", &PhotonMapOptions::cache_stride, "N", between(1, 1000000),
                    "one irradiance cache point per this many global photons"));
        pm(b.number("photon-normal-cos", &PhotonMapOptions::normal_cos, "C", between(-1, 1),
                    "surface test: minimum cosine between photon and query normals"));
        pm(b.number("photon-flatness", &PhotonMapOptions::flatness, "F", between(0, 1),
                    "surface test: maximum |height| / distance of a photon off the tangent plane (0 = off)"));
        pm(b.flag("no-direct", &PhotonMapOptions::direct, "leave out direct light", false));
        pm(b.flag("no-caustic", &PhotonMapOptions::caustics, "leave out caustics", false));
        pm(b.flag("no-indirect", &PhotonMapOptions::indirect_light, "leave out indirect diffuse light",
                  false));
        pm(b.flag("no-specular", &PhotonMapOptions::specular,
                  "do not follow mirror reflections from the camera", false));
        pm(b.flag("no-transmissive", &PhotonMapOptions::transmissive,
                  "do not follow refraction through glass from the camera", false));
        // The seed renderer's spellings (-no_direct, -photon_viz...): the same switches.
        for (const char* name : {"no-direct", "no-caustic", "no-indirect", "no-specular", "no-transmissive",
                                 "photon-viz", "fast-global"}) {
            std::string seed = name;
            std::replace(seed.begin(), seed.end(), '-', '_');
            for (options::Option& o : b.options())
                if (o.name == name) o.aliases.push_back(seed);
        }
        return b.build();
    }();
    return table;
}

}  // namespace phos::integrators
