// The beam radiance estimate (Jarosz, Zwicker & Jensen 2008, "The Beam Radiance Estimate for
// Volumetric Photon Mapping", sec. 4): the light a camera ray gains along a whole stretch in a
// medium, int_0^s T(t) sigma_s int p L_i dt, from one query of the volume photons' spheres instead
// of a k-nearest search at every ray-marching step.
//
// Every photon gets its own radius r_p (the distance to its k-th nearest photon, at most the map's
// maximum radius: the paper's per-photon radius from a k-nearest query at the photon). The 3D volume estimate
// with those radii is  sum_p p(wo, wi_p) Phi_p [|x - x_p| < r_p] / (4/3 pi r_p^3)  (volume_estimate.h: photon
// powers carry sigma_s, so this is the in-scattered radiance per unit length), and its integral
// along the stretch is, photon by photon,
//   L_b = sum_p p(wo, wi_p) Phi_p / (4/3 pi r_p^3) * int_{t0_p}^{t1_p} T(t) dt,
// [t0_p, t1_p] the chord of the photon's ball clipped to [0, s]. Where T is constant over the
// chord and the chord lies inside the stretch this is the paper's
//   L_b = sum_p K(d_p, r_p) T(t_p) p(wo, wi_p) Phi_p,   K(d, r) = 2 sqrt(r^2 - d^2) / (4/3 pi r^3),
// d_p the photon's distance from the ray and t_p its projection on it: K is the normalised 2D
// kernel (int over the disc = 1) that the 3D box kernel projects to. We keep the chord integral
// rather than the paper's box 1/(pi r^2) or Silverman's biweight (its eq. 16-17), because
//  - the beam estimate is then exactly the ray integral of the 3D estimate above: what ray
//    marching with per-photon radii converges to as its step shrinks (so the two can be checked
//    against each other, and they share the 3D estimate's bias rather than adding another);
//  - a photon cut by an end of the stretch (the camera inside the fog, a wall) counts the part of
//    its ball inside [0, s], where T(t_p) with t_p clamped would count all of it or nothing;
//  - K falls continuously to 0 at the rim (the box kernel jumps).
// The cost is one exp per photon in grey media, as for T(t_p) (stretch_transmittance.h integrates
// T exactly over the chord).
// In expectation the k-th-neighbour radii differ from the k-nearest estimate of volume_estimate.h
// (a balloon estimator, high by about k / (k - 1) in a uniform density; the per-photon radii are
// unbiased there), by ~2 % at the default k.
#pragma once

#include <cstdint>
#include <vector>

#include "photon/beam_bvh.h"
#include "photon/kdtree.h"
#include "photon/open_ball.h"
#include "photon/stretch_transmittance.h"
#include "shading/phase.h"

namespace phos::photon {

// The photons of `map` with their kernel radii: the distance to the k-th nearest photon (itself
// included), `max_radius` where fewer than k lie within it, and never below max_radius / 1000 (so
// coincident photons keep their power). With `surfaces` (the surfaces that bound the media) each
// photon's power is divided by the open share of its ball (photon/open_ball.h): the part behind a
// wall or outside the medium is never crossed by a camera ray, and the 3D estimate above then
// loses nothing at boundaries to first order. In tree order; parallel, and the same at any thread
// count.
std::vector<PhotonSphere> photon_spheres(const PhotonKdTree& map, uint32_t k, float max_radius,
                                         const accel::EmbreeScene* surfaces = nullptr);

// L_b above along o + t d, t in [0, T.end()] (d unit): the in-scattered radiance the stretch adds
// towards -d, before what lies behind it. `n_used` (optional) receives the photons counted.
Rgb beam_radiance_estimate(const BeamBvh& map, Vec3 o, Vec3 d, const StretchTransmittance& T,
                           const shading::PhaseFunction& phase, uint32_t* n_used = nullptr);

}  // namespace phos::photon
