// Direct lighting at a surface point by light sampling with shadow rays, shared by the whitted,
// path and photon-map integrators.
#pragma once

#include "core/rng.h"
#include "core/stats.h"
#include "render/prepared.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

// Every value is at the path's wavelengths `lambda`.
//
// One light chosen in proportion to its power, one point on it, one shadow ray. With `mis`, area
// and infinite lights are weighted against BSDF sampling by the power heuristic (the caller then
// adds BSDF-sampled emission with the complementary weight). `medium` is the medium the path
// arrived in: shadow rays are attenuated by the media they cross (shadow_transmittance).
Spectrum sample_one_light(const Prepared& P, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf, Vec3 wo,
                          Sampler& sampler, const Wavelengths& lambda, RayCounts& rays, bool mis,
                          int medium = -1);
// The same with the light choice `u_choose` and the point on the light `u` given (stratified
// sequences); `sampler` serves only media along the shadow ray.
Spectrum sample_one_light(const Prepared& P, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf, Vec3 wo,
                          float u_choose, Vec2 u, Sampler& sampler, const Wavelengths& lambda,
                          RayCounts& rays, bool mis, int medium = -1);

// Every light, one sample each (no MIS): the classic Whitted / photon-map direct term.
Spectrum sample_all_lights(const Prepared& P, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf,
                           Vec3 wo, Sampler& sampler, const Wavelengths& lambda, RayCounts& rays,
                           int medium = -1);

// In-scattered direct light at point p inside `medium` (wo towards the viewer): one light chosen
// by power, phase * L * transmittance / pdf, weighted against phase sampling with `mis`.
Spectrum sample_one_light_in_medium(const Prepared& P, Vec3 p, Vec3 wo, int medium, Sampler& sampler,
                                    const Wavelengths& lambda, RayCounts& rays, bool mis);

// The length of a stretch of ray that ends at t_end, or for an escaping ray (t_end = kInf) where
// it leaves the scene's bounding sphere (nothing lies beyond to scatter light back).
float finite_stretch(const Prepared& P, Vec3 o, Vec3 d, float t_end);

// Single scattering along the stretch o + t d, t in [0, t_end) (d unit, kInf: up to the scene's
// bounding sphere) of a camera ray in `medium`: int T(t) sigma_s(t) int p L_light T_light dt,
// estimated with one light chosen by power and one distance, sampled equiangularly (Kulla &
// Fajardo 2012, eq. 6) towards point and spot lights, proportionally to exp(-sigma_t t) otherwise.
Spectrum single_scattering(const Prepared& P, int medium, Vec3 o, Vec3 d, float t_end, Sampler& sampler,
                           const Wavelengths& lambda, RayCounts& rays);

// The unoccluded part of that estimate for one given light sample direction: used where the
// caller chose the point itself (equiangular sampling along a camera ray).
Spectrum light_in_medium(const Prepared& P, const shading::LightLiSample& ls, Vec3 p, Vec3 wo, int medium,
                         Sampler& sampler, const Wavelengths& lambda, RayCounts& rays);

}  // namespace phos::integrators
