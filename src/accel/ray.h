// Surface hits and robust ray spawning shared by every integrator and the photon tracer (the ray
// itself is core/ray.h).
#pragma once

#include <emmintrin.h>

#include <cmath>

#include "core/frame.h"
#include "core/ray.h"
#include "core/vec.h"
#include "scene/medium.h"

namespace phos::accel {

// Everything shading needs to know about the closest hit.
struct SurfaceHit {
    float t = kInf;
    Vec3 p;              // world-space hit point
    Vec3 ng;             // unit geometric normal, pointing to the shape's outside (after reverse_orientation)
    Vec3 ns;             // unit shading normal (interpolated where the mesh has normals), same side as ng
    Vec2 uv;             // surface parameterisation (mesh uv, or the primitive's own)
    Vec3 dpdu;           // tangent along u (unit; arbitrary but consistent if the shape has none)
    int shape = -1;      // index into Scene::shapes, or of the instanced object's shape
    int instance = -1;   // index into Scene::instances, or -1 for top-level shapes
    int primitive = -1;  // triangle index within a mesh, 0 for analytic shapes
    int material = -1;
    int area_light = -1;  // index into Scene::lights when the surface emits
    scene::MediumInterface media;
    float error = 0.0f;  // conservative bound on the position error of p, for spawning
    // shading_frame(ng, ns, dpdu) where the accelerator keeps it for the primitive (flat
    // triangles: the same for every hit on them), else null. Whoever changes ng, ns or dpdu of a
    // hit must reset it.
    const ShadingFrame* shading = nullptr;
};

// Offsets `p` off the surface along the geometric normal towards the side `dir` points to, far
// enough that a ray from the result does not re-hit the same surface (no acne) and close enough not
// to skip touching geometry (no leaks). (Inline with spawn_ray: every bounce of every path.)
// offset_origin_reference is the same one coordinate at a time; this one computes the three with
// SSE selects instead of branches: which side and which rounding direction each coordinate takes
// depend on the surface and the sampled direction (callgrind's branch simulation mispredicted
// those branches almost once per call).
// Every lane runs the reference's IEEE operations, so the bits are the same
// (OffsetOrigin.LanesGiveTheReferenceBits).
inline Vec3 offset_origin(const SurfaceHit& hit, Vec3 dir) {
    // pbrt: distance = dot(|n|, error vector); with an isotropic bound that is error * |n|_1.
    const float d = hit.error * (std::fabs(hit.ng.x) + std::fabs(hit.ng.y) + std::fabs(hit.ng.z));
    const __m128 ng = _mm_setr_ps(hit.ng.x, hit.ng.y, hit.ng.z, 0.0f);
    const __m128 sign = _mm_castsi128_ps(_mm_set1_epi32(dot(dir, hit.ng) < 0 ? int(0x80000000u) : 0));
    const __m128 offset = _mm_xor_ps(_mm_mul_ps(ng, _mm_set1_ps(d)), sign);  // -offset flips the sign bits
    const __m128 x = _mm_add_ps(_mm_setr_ps(hit.p.x, hit.p.y, hit.p.z, 0.0f), offset);
    // Round away from p so that the float addition cannot land back on the surface: next_float(x,
    // +-kInf) where the offset is positive / negative, x itself where it is zero.
    const __m128 zero = _mm_setzero_ps();
    const __m128 up = _mm_cmpgt_ps(offset, zero), down = _mm_cmplt_ps(offset, zero);
    const __m128 toward = _mm_or_ps(_mm_and_ps(up, _mm_set1_ps(kInf)), _mm_andnot_ps(up, _mm_set1_ps(-kInf)));
    const __m128i bits = _mm_castps_si128(x);
    // next_float: one step away from zero where (x < toward) == (x > 0), else towards it ...
    const __m128i away = _mm_castps_si128(
        _mm_xor_ps(_mm_xor_ps(_mm_cmplt_ps(x, toward), _mm_cmpgt_ps(x, zero)), _mm_cmpeq_ps(zero, zero)));
    __m128i stepped =
        _mm_add_epi32(bits, _mm_sub_epi32(_mm_and_si128(away, _mm_set1_epi32(2)), _mm_set1_epi32(1)));
    // ... the smallest denormal of toward's sign from a zero of either sign ...
    const auto select = [](__m128i mask, __m128i a, __m128i b) {
        return _mm_or_si128(_mm_and_si128(mask, a), _mm_andnot_si128(mask, b));
    };
    stepped =
        select(_mm_castps_si128(_mm_cmpeq_ps(x, zero)),
               select(_mm_castps_si128(up), _mm_set1_epi32(1), _mm_set1_epi32(int(0x80000001u))), stepped);
    // ... toward itself where x equals it, x + toward for a NaN.
    stepped = select(_mm_castps_si128(_mm_cmpeq_ps(x, toward)), _mm_castps_si128(toward), stepped);
    stepped =
        select(_mm_castps_si128(_mm_cmpunord_ps(x, x)), _mm_castps_si128(_mm_add_ps(x, toward)), stepped);
    alignas(16) float out[4];
    _mm_store_ps(out, _mm_castsi128_ps(select(_mm_castps_si128(_mm_or_ps(up, down)), stepped, bits)));
    return {out[0], out[1], out[2]};
}
// The same, one coordinate at a time with branches: the definition the lanes above follow.
inline Vec3 offset_origin_reference(const SurfaceHit& hit, Vec3 dir) {
    const float d = hit.error * (std::fabs(hit.ng.x) + std::fabs(hit.ng.y) + std::fabs(hit.ng.z));
    Vec3 offset = hit.ng * d;
    if (dot(dir, hit.ng) < 0) offset = -offset;
    Vec3 po = hit.p + offset;
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0)
            po[i] = next_float(po[i], kInf);
        else if (offset[i] < 0)
            po[i] = next_float(po[i], -kInf);
    }
    return po;
}
// A ray leaving the surface in direction `dir`.
inline Ray spawn_ray(const SurfaceHit& hit, Vec3 dir) {
    Ray r;
    r.origin = offset_origin(hit, dir);
    r.dir = dir;
    return r;
}
// A shadow ray from the surface towards point `target` (stops just short of it).
Ray spawn_ray_to(const SurfaceHit& hit, Vec3 target);
// A shadow ray between two surface points, offset at both ends.
Ray spawn_ray_between(const SurfaceHit& from, const SurfaceHit& to);
// A shadow ray from a point off any surface (in a medium) towards point `target`.
Ray ray_to(Vec3 from, Vec3 target);

}  // namespace phos::accel
