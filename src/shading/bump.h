// Bump and normal mapping (pbrt-v4's BumpMap and NormalMap, PBR 4th ed. sec. 10.5.2 and 10.5.3;
// Blinn 1978): the shading normal and tangent of a hit perturbed by a material's "displacement"
// float texture or "normalmap" image, before its BSDF is placed there.
#pragma once

#include "accel/ray.h"
#include "accel/surface_derivatives.h"
#include "scene/material.h"
#include "scene/scene.h"
#include "scene/texture.h"

namespace phos::shading {

// Whether `material` perturbs its shading normal (a displacement texture or a normal map).
inline bool has_shading_detail(const scene::Material& material) {
    return material.displacement_texture >= 0 || material.normal_map != nullptr;
}

// pbrt-v4's BumpMap without ray differentials: with d the displacement texture (its grey value)
// and du = dv = 0.0005, dpdu' = dpdu + (d(u + du, v) - d(u, v)) / du * ns and dpdv' = dpdv +
// (d(u, v + dv) - d(u, v)) / dv * ns (the d * dn/du curvature terms are left out: phos has no
// dn/du; they vanish on planes and only rescale the tangents elsewhere). `d` holds the hit's
// dpdu, dpdv (accel/surface_derivatives.h) and is replaced by the displaced pair.
void bump_map(const scene::Scene& scene, int displacement_texture, const accel::SurfaceHit& hit,
              accel::SurfaceDerivatives& d);

// pbrt-v4's NormalMap: the image (linear RGB, looked up bilinearly at (u, 1 - v) with repeat
// wrapping) holds a tangent-space normal 2 rgb - 1 in the frame (dpdu made perpendicular to ns,
// ns x that, ns); `d` is replaced by dpdu' = that normal's Gram-Schmidt of dpdu scaled to |dpdu|
// and dpdv' = (normal x dpdu') scaled to |dpdv|, whose cross product is the mapped normal.
void normal_map(const scene::TextureImage& image, const accel::SurfaceHit& hit, accel::SurfaceDerivatives& d);

// The hit as the material's BSDF sees it: unchanged without shading detail; else (pbrt-v4's
// SetShadingGeometry after BumpMap or NormalMap, the normal map taking precedence) ns =
// normalize(dpdu' x dpdv') turned to ng's side, dpdu = normalize(dpdu'), and `shading` reset (the
// accelerator's cached frame no longer applies). ng and everything else are kept.
accel::SurfaceHit with_shading_detail(const scene::Scene& scene, const scene::Material& material,
                                      const accel::SurfaceHit& hit);

}  // namespace phos::shading
