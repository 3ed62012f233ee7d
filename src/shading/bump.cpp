// Bump and normal mapping as pbrt-v4 defines them (see bump.h).
#include "shading/bump.h"

#include <cmath>

#include "scene/texture_eval.h"

namespace phos::shading {

namespace {

// pbrt-v4's offset for the finite differences when there are no ray differentials.
constexpr float kBumpDelta = 0.0005f;

float displacement_at(const scene::Scene& scene, int texture, Vec2 uv) {
    return scene::eval_texture(scene, texture, uv).average();
}

// v - n (n . v) for unit n.
Vec3 perpendicular(Vec3 v, Vec3 n) { return v - n * dot(n, v); }

}  // namespace

void bump_map(const scene::Scene& scene, int displacement_texture, const accel::SurfaceHit& hit,
              accel::SurfaceDerivatives& d) {
    const float du = kBumpDelta, dv = kBumpDelta;
    const float displace = displacement_at(scene, displacement_texture, hit.uv);
    const float u_displace = displacement_at(scene, displacement_texture, hit.uv + Vec2(du, 0));
    const float v_displace = displacement_at(scene, displacement_texture, hit.uv + Vec2(0, dv));
    d.dpdu = d.dpdu + hit.ns * ((u_displace - displace) / du);
    d.dpdv = d.dpdv + hit.ns * ((v_displace - displace) / dv);
}

void normal_map(const scene::TextureImage& image, const accel::SurfaceHit& hit,
                accel::SurfaceDerivatives& d) {
    if (image.width <= 0 || image.height <= 0) return;
    // Texel centres at half-integers, row 0 at the top: (u, 1 - v) in texel units.
    const Rgb c = scene::lookup_bilinear(image, hit.uv.x * float(image.width),
                                         (1 - hit.uv.y) * float(image.height), scene::Texture::Wrap::Repeat);
    Vec3 local(2 * c.r - 1, 2 * c.g - 1, 2 * c.b - 1);
    if (!(length_squared(local) > 0) || !is_finite(local)) return;
    local = normalize(local);
    // pbrt-v4's Frame::FromXZ(normalize(dpdu), ns): x = dpdu, y = ns x dpdu, z = ns.
    const Vec3 z = hit.ns;
    Vec3 x = perpendicular(d.dpdu, z);
    if (!(length_squared(x) > 0)) return;
    x = normalize(x);
    const Vec3 y = cross(z, x);
    const Vec3 n = normalize(x * local.x + y * local.y + z * local.z);
    const float ulen = length(d.dpdu), vlen = length(d.dpdv);
    Vec3 s = perpendicular(d.dpdu, n);
    if (!(length_squared(s) > 0)) s = perpendicular(cross(n, z), n);  // dpdu along the mapped normal
    if (!(length_squared(s) > 0)) return;
    d.dpdu = normalize(s) * ulen;
    d.dpdv = normalize(cross(n, d.dpdu)) * vlen;
}

accel::SurfaceHit with_shading_detail(const scene::Scene& scene, const scene::Material& material,
                                      const accel::SurfaceHit& hit) {
    if (!has_shading_detail(material)) return hit;
    accel::SurfaceDerivatives d = accel::surface_derivatives(scene, hit);
    if (material.normal_map)
        normal_map(*material.normal_map, hit, d);
    else
        bump_map(scene, material.displacement_texture, hit, d);
    Vec3 ns = cross(d.dpdu, d.dpdv);
    if (!(length_squared(ns) > 0) || !is_finite(ns)) return hit;
    ns = normalize(ns);
    if (dot(ns, hit.ng) < 0) ns = -ns;  // pbrt-v4: FaceForward(shading.n, n)
    accel::SurfaceHit out = hit;
    out.ns = ns;
    out.dpdu = normalize(d.dpdu);
    out.shading = nullptr;
    return out;
}

}  // namespace phos::shading
