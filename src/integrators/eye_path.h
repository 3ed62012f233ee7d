// The eye path of PPM and SPPM, which vcm's pilot uses too: from the camera through mirrors and
// glass to the first non-specular surface (or a scattering event in a medium), where a visible
// point is stored and direct light is sampled.
#pragma once

#include <cstdint>
#include <optional>

#include "core/rng.h"
#include "core/stats.h"
#include "render/prepared.h"
#include "shading/bsdf.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

// Where a camera path met its first non-specular surface (after following specular bounces), or
// scattered in a participating medium (free-flight sampling): a volume visible point, whose
// statistics use a 3D kernel (a ball) instead of a disc (Knaus & Zwicker 2011, sec. 4.3: the same
// progressive radius reduction with the kernel's dimension d = 3).
struct VisiblePoint {
    Vec3 p;
    Vec3 wo;
    Spectrum beta;       // camera-path throughput (over the path's selection probabilities), at `lambda`
    Wavelengths lambda;  // the camera path's wavelengths (as they were when it stopped)
    int depth = 0;       // specular bounces before it (limits photon bounces: total ≤ max_depth)
    float path_length = 0;
    std::optional<shading::Bsdf> bsdf;  // a surface visible point
    int material = -1;                  // its material (Bsdf::rebind)
    int medium = -1;                    // >= 0: a volume visible point in this medium
    bool present() const { return bsdf || medium >= 0; }
    bool volume() const { return medium >= 0; }
};

// The stratified per-pixel sequences of iteration i's eye path (n light samples per path), as
// padded dimensions of its pixel (core/low_discrepancy.h) keyed by `key`: light sample k is point
// i × n + k of the light choice (1D) and of the point on the light (2D), the path's hero
// wavelength point i of a third (1D). A pixel's light samples and wavelengths over all iterations
// are then stratified sequences: soft shadows and colour converge faster than with independent
// samples while every iteration stays unbiased.
struct PixelSequences {
    uint32_t iteration = 0;
    uint64_t key = 0;
};

// Traces a camera ray: adds emission seen along the specular chain, and at the first non-specular
// hit stores `vp` and adds the average of `direct_samples` light samples. Mixed materials choose
// between their non-specular part (visible point) and specular part (continue) at random, in
// proportion to the lobes' albedos. Returns emission + direct light (throughput included), as
// colour: the path draws its wavelengths first from `sampler` (render::camera_wavelengths).
// With `sequences`, the wavelengths and the light samples come from stratified per-pixel
// sequences instead of `sampler` (see PixelSequences).
Rgb trace_eye_path(const Prepared& P, Ray ray, Sampler& sampler, int direct_samples, VisiblePoint& vp,
                   RayCounts& rays, const PixelSequences* sequences = nullptr);

}  // namespace phos::integrators
