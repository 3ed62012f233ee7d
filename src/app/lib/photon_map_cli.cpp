// Command-line options of the photon-map integrator (registered on `phos render`); every option is
// described in docs/photon-mapping.md.
#include "app/lib/photon_map_cli.h"

#include <string>

namespace phos::app {
namespace {

// --NAME N, --NAME-samples K, --NAME-radius R, --NAME-filter none|cone|gauss (or cone:K),
// --NAME-cone-k K for one map.
void add_map_options(CLI::App& render, const std::string& name, integrators::PhotonMapSettings& s,
                     const std::string& what) {
    render
        .add_option("--" + name, s.photons,
                    "photonmap: stored photons wanted in the " + what + " map (default " +
                        std::to_string(s.photons) + ")")
        ->check(CLI::Range(uint64_t(0), uint64_t(1) << 31));
    render
        .add_option("--" + name + "-samples", s.samples,
                    "photonmap: photons per " + name + " radiance estimate (default " +
                        std::to_string(s.samples) + ")")
        ->check(CLI::Range(1u, 100000u));
    render
        .add_option("--" + name + "-radius", s.radius,
                    "photonmap: maximum " + name +
                        " estimate radius in scene units (default: a fraction of the scene radius)")
        ->check(CLI::Range(0.0f, 1e30f));
    auto* kind = &s;
    render.add_option_function<std::string>(
        "--" + name + "-filter",
        [kind](const std::string& v) {
            std::string k = v;
            const size_t colon = v.find(':');
            if (colon != std::string::npos) {
                k = v.substr(0, colon);
                try {
                    size_t used = 0;
                    kind->cone_k = std::stof(v.substr(colon + 1), &used);
                    if (used != v.size() - colon - 1) throw std::invalid_argument(v);
                } catch (const std::exception&) {
                    throw CLI::ValidationError("bad cone constant in '" + v + "'");
                }
                if (k != "cone")
                    throw CLI::ValidationError("only the cone filter takes a constant: '" + v + "'");
            }
            if (!photon::parse_filter_kind(k, kind->filter))
                throw CLI::ValidationError("unknown filter '" + v + "' (none, cone, cone:K, gauss)");
        },
        "photonmap: " + name + " estimate filter none|cone|cone:K|gauss (default " +
            photon::filter_name(s.filter) + ")");
    render
        .add_option("--" + name + "-cone-k", s.cone_k,
                    "photonmap: cone filter constant k >= 1 of the " + name + " estimate (default 1.1)")
        ->check(CLI::Range(1.0f, 1e6f));
}

}  // namespace

void add_photon_map_options(CLI::App& render, integrators::PhotonMapOptions& o) {
    add_map_options(render, "global", o.global, "global (final gather)");
    add_map_options(render, "caustic", o.caustic, "caustic");
    add_map_options(render, "indirect", o.indirect, "indirect (--fast-global)");
    render
        .add_option("--photons", o.photons,
                    "photonmap: photons to emit (default: until every map holds its budget)")
        ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
    render
        .add_option("--max-emitted", o.max_emitted,
                    "photonmap: stop emitting after this many photons even if a budget is unmet "
                    "(default 200 x the largest budget)")
        ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
    render
        .add_option("--max-photon-depth", o.max_photon_depth,
                    "photonmap: scattering events per photon path (default 16)")
        ->check(CLI::Range(0, 100000));
    render
        .add_option("--gather-rays", o.gather_rays,
                    "photonmap: final-gather rays per camera sample (default 8)")
        ->check(CLI::Range(1, 1 << 20));
    render.add_flag("--fast-global", o.fast_global,
                    "photonmap: indirect light from the indirect map at the first hit, no final gather");
    render.add_flag("--photon-viz", o.photon_viz,
                    "photonmap: show the global map's radiance estimate at the first hit (debug view)");
    render.add_flag("--irradiance-cache,!--no-irradiance-cache", o.irradiance_cache,
                    "photonmap: precomputed irradiance at global photons for the final gather (default on)");
    render
        .add_option("--caustic-min-radius-pixels", o.caustic_min_pixels,
                    "photonmap: the caustic estimate's radius never shrinks below this many pixel "
                    "footprints (default 1, 0 = plain k nearest)")
        ->check(CLI::Range(0.0f, 1e6f));
    render.add_flag("--projection-maps,!--no-projection-maps", o.projection_maps,
                    "photonmap: emit caustic photons only towards mirrors and glass, weighted by the "
                    "share of emission aimed there (default on)");
    render
        .add_option("--irradiance-cache-stride", o.cache_stride,
                    "photonmap: one irradiance cache point per this many global photons (default 4)")
        ->check(CLI::Range(1u, 1000000u));
    render
        .add_option("--photon-normal-cos", o.normal_cos,
                    "photonmap: surface test, minimum cosine between photon and query normals (default 0.9)")
        ->check(CLI::Range(-1.0f, 1.0f));
    render
        .add_option("--photon-flatness", o.flatness,
                    "photonmap: surface test, maximum |height| / distance of a photon off the tangent plane "
                    "(default 0.2, 0 = off)")
        ->check(CLI::Range(0.0f, 1.0f));
    render.add_flag("--no-direct{false}", o.direct, "photonmap: leave out direct light");
    render.add_flag("--no-caustic{false}", o.caustics, "photonmap: leave out caustics");
    render.add_flag("--no-indirect{false}", o.indirect_light, "photonmap: leave out indirect diffuse light");
    render.add_flag("--no-specular{false}", o.specular,
                    "photonmap: do not follow mirror reflections from the camera");
    render.add_flag("--no-transmissive{false}", o.transmissive,
                    "photonmap: do not follow refraction through glass from the camera");
}

}  // namespace phos::app
