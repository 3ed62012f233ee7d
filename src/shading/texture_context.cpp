// Texture contexts of hits with pbrt-v4's camera footprint (see texture_context.h).
#include "shading/texture_context.h"

#include "accel/surface_derivatives.h"

namespace phos::shading {

scene::TextureContext texture_context(const scene::Scene& scene, const accel::SurfaceHit& hit,
                                      const scene::CameraFootprint* footprint) {
    scene::TextureContext ctx{hit.uv, hit.p, hit.ng, {}};
    if (!footprint) return ctx;
    scene::approximate_dp_dxy(*footprint, hit.p, hit.ng, ctx.dpdx, ctx.dpdy);
    const accel::SurfaceDerivatives d = accel::surface_derivatives(scene, hit);
    const scene::UvDerivatives uv = scene::uv_derivatives(d.dpdu, d.dpdv, ctx.dpdx, ctx.dpdy);
    ctx.dudx = uv.dudx;
    ctx.dudy = uv.dudy;
    ctx.dvdx = uv.dvdx;
    ctx.dvdy = uv.dvdy;
    return ctx;
}

}  // namespace phos::shading
