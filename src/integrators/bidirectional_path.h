// The vertices of bidirectional methods (bdpt, vcm) and the light subpath walk they share: a
// vertex on a surface (its BSDF) or in a medium (its phase function), with the throughput that
// reached it and the recursive MIS state of its subpath (vcm_mis.h). A subpath carries its
// wavelengths: a pixel's light subpath and its first camera subpath share theirs
// (subpath_wavelengths), so that connecting them makes one path at one set of wavelengths.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "core/rng.h"
#include "core/stats.h"
#include "integrators/vcm_mis.h"
#include "render/prepared.h"
#include "shading/bsdf.h"
#include "shading/surface_walk.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)
}  // namespace phos::integrators

namespace phos::integrators::vcm {

// A vertex without its BSDF: what vcm keeps of an iteration's light subpaths (the BSDF, half the
// size, is built again from `hit` when a camera subpath connects to it: with_bsdf).
struct VertexCore {
    Vec3 p;
    Vec3 wo;                // unit, towards the previous vertex of its subpath
    Spectrum beta;          // throughput of the subpath up to (not including) this vertex
    Wavelengths lambda;     // the subpath's wavelengths at this vertex
    accel::SurfaceHit hit;  // surface vertices
    int medium = -1;        // a medium vertex: its medium; a surface vertex: the medium the path came in
    bool in_medium = false;
    bool mergeable = false;  // merging may happen here (a surface with a non-delta lobe, merging on)
    int length = 0;          // segments from the subpath's start (the light or the camera)
    // Light subpaths: every vertex between the light and this one scattered through a delta lobe
    // (true for the first vertex): for --layers, light arriving here is direct or caustic.
    bool delta_chain = true;
    SubpathMis mis;
};

struct Vertex : VertexCore {
    std::optional<shading::Bsdf> bsdf;  // surface vertices
};

// The vertex `c` with its BSDF built again (the same as when it was traced).
inline Vertex with_bsdf(const Prepared& P, const VertexCore& c) {
    Vertex v;
    static_cast<VertexCore&>(v) = c;
    if (!c.in_medium) v.bsdf.emplace(P.bsdf(c.hit));
    return v;
}

// What a vertex's scattering function does for a direction `wi` (unit, away from the vertex),
// given its wo: the value f (BSDF, or phase function in a medium), |cos| with the shading normal
// (1 in a medium), and the solid-angle pdfs of sampling wi from wo (dir) and wo from wi (rev).
struct Scattering {
    Spectrum f;  // at the wavelengths asked
    float cos = 1, pdf_dir = 0, pdf_rev = 0;
};
Scattering evaluate(const Prepared& P, const Vertex& v, Vec3 wi, shading::TransportMode mode,
                    const Wavelengths& lambda);

// The vertex a subpath's walk reached with `event` (Surface or Medium) after `length` segments,
// arriving with throughput `beta` (its MIS state is the caller's).
Vertex reach_vertex(const Prepared& P, shading::SurfaceWalk::Event event, const shading::SurfaceWalk& walk,
                    const Ray& ray, const accel::SurfaceHit& hit, int length, const Spectrum& beta,
                    const Wavelengths& lambda);
// |cos| of unit direction w with v's shading normal (1 in a medium).
inline float cos_at(const Vertex& v, Vec3 w) {
    return v.in_medium ? 1.0f : std::fabs(dot(v.bsdf->frame().n, w));
}
// What a subpath carries from vertex to vertex: its throughput, its MIS state and its wavelengths.
struct SubpathState {
    Spectrum beta;
    SubpathMis mis;
    Wavelengths lambda;
};
// The wavelengths of subpath j of an iteration, light or camera: pixel j's light subpath and its
// first camera subpath draw the same, the hero at point `iteration` of a padded 1D sequence of
// pixel j (core/low_discrepancy.h), so a pixel's wavelengths are stratified over the iterations.
Wavelengths subpath_wavelengths(uint64_t seed, uint64_t j, uint64_t iteration);
// The wavelengths a connection of a camera and a light subpath at the same wavelengths counts:
// the camera's, with the secondary ones terminated if either subpath terminated them.
inline Wavelengths joined(const Wavelengths& camera, const Wavelengths& light) {
    Wavelengths w = camera;
    if (light.secondary_terminated()) w.terminate_secondary();
    return w;
}
// How the MIS state takes a scattering at a vertex: the iteration's factors, whether merging at the
// vertex is a strategy (scatter's `mergeable`), and the probability with which the caller chose to
// go on from the vertex at all (a factor of the direction's density; the caller divides beta by
// it).
struct ScatterTerms {
    MisFactors factors;
    bool merge_here = false;
    float go_on = 1;
};
// A direction a subpath goes on in: unit wi, away from the vertex, and whether a delta lobe chose
// it.
struct Direction {
    Vec3 wi;
    bool delta = false;
};
// The subpath goes on from v: samples a direction (the BSDF in `mode`, the phase function in a
// medium), multiplies path.beta by its weight and updates path.mis (scatter or scatter_delta); a
// dispersive interface terminates path.lambda's secondary wavelengths. Nothing when nothing was
// sampled.
std::optional<Direction> continue_from(const Prepared& P, const Vertex& v, shading::TransportMode mode,
                                       const ScatterTerms& terms, Sampler& sampler, SubpathState& path);
// The ray leaving v in direction wi; the walk follows the medium change at a surface.
Ray leave_vertex(const Vertex& v, Vec3 wi, shading::SurfaceWalk& walk);

// Transmittance between two vertices (0 if blocked): media crossed included.
Spectrum transmittance_between(const Prepared& P, const Vertex& a, const Vertex& b, Sampler& sampler,
                               const Wavelengths& lambda);
// Transmittance from vertex `a` to a point `target` that is not on a surface a ray can hit (the
// lens, a point light), or to a sampled light point (short of it).
Spectrum transmittance_to(const Prepared& P, const Vertex& a, Vec3 target, Sampler& sampler,
                          const Wavelengths& lambda);

// Russian roulette on a subpath after three segments: survival in proportion to the throughput
// relative to its start (`beta0`), at least 5 %; survivors are reweighted.
bool survives(int length, Spectrum& beta, const Spectrum& beta0, Sampler& sampler);

// How light subpaths are traced: at most `max_segments` segments, the MIS `factors`; surface
// vertices at least `merge_from` segments from the light are mergeable (0: none). With
// `merge_terms`, merging at them is a strategy of the paths the subpath continues into (vcm merging
// at every camera vertex); without, a light vertex merges only as the camera's first non-delta
// vertex, which no longer light subpath reaches (vcm_mis.h).
struct LightSubpathRules {
    int max_segments = 1;
    MisFactors factors;
    int merge_from = 0;
    bool merge_terms = false;
};
// The light subpath of one light sample at wavelengths `lambda`: a light chosen by power, an
// emitted ray, a random walk. Appends the vertices connections and merging can use (those with a
// non-delta lobe, and medium vertices) to `out`. Returns false when no light emits.
bool trace_light_path(const Prepared& P, const LightSubpathRules& rules, Sampler& sampler,
                      const Wavelengths& lambda, std::vector<Vertex>& out, RayCounts& rays);

}  // namespace phos::integrators::vcm
