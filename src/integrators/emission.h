// What a camera path sees where it meets a scattering surface: the surface's own light (area
// emitter) and the .scn glow and ambient terms, with the one rule for which rays see which.
#pragma once

#include "render/prepared.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

// The scattering vertex a ray was BSDF-sampled from (a non-delta lobe), for weighting emission it
// finds against light sampling at that vertex (multiple importance sampling, power heuristic).
struct BsdfSampledFrom {
    Vec3 p;     // the vertex
    float pdf;  // solid-angle pdf of the sampled direction
};

// Radiance times `beta` that the path sees leaving `hit` towards `wo` (unit, away from the surface):
// - the area light's emission, MIS-weighted against sampling that light when `from` is given (the
//   ray's last bounce sampled a non-delta lobe);
// - on the camera's specular chain (`camera_chain`: the camera ray and rays after delta bounces
//   only) also the .scn glow `e` and, with --ambient, ka x ambient. Both are non-physical surface
//   terms that are "not a light" (docs/formats/scn.md): like a colour painted on the surface they
//   are seen wherever the surface itself is seen, directly, in a mirror or through glass, but they
//   light nothing, so a path that has been through a diffuse or glossy bounce never sees them.
//   Being paint, they are colours (the file's RGB), seen through beta as spectrum::colour_through
//   says: exactly their colour through clear glass and grey mirrors.
struct SeenEmission {
    Spectrum light;  // the area light's, at the path's wavelengths
    Rgb glow;        // the glow and ambient terms, as colour
};
SeenEmission seen_emission(const Prepared& P, const accel::SurfaceHit& hit, Vec3 wo, const Spectrum& beta,
                           const Wavelengths& lambda, bool camera_chain = true,
                           const BsdfSampledFrom* from = nullptr);

// Radiance times `beta` that a ray from `origin` leaving the scene in direction `dir` (unit) sees: the
// infinite lights' emission, MIS-weighted against sampling them when `from` is given (the ray's last bounce
// sampled a non-delta lobe), and the background, which only rays without such a bounce see (mirror and glass
// chains from the camera) unless --background-light makes it light the scene.
Spectrum escaped_emission(const Prepared& P, Vec3 origin, Vec3 dir, const Spectrum& beta,
                          const Wavelengths& lambda, const BsdfSampledFrom* from = nullptr);

}  // namespace phos::integrators
