// Orthonormal basis around a unit normal, for moving directions to and from local shading space
// (local z = the normal). Uses the branchless construction of Duff et al. 2017. Also the shading
// frame of a surface point built from its normals and tangent (what a BSDF works in).
#pragma once

#include "core/vec.h"

namespace phos {

struct Frame {
    Vec3 s, t, n;

    Frame() : s(1, 0, 0), t(0, 1, 0), n(0, 0, 1) {}
    explicit Frame(Vec3 normal) : n(normal) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        s = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
        t = Vec3(b, sign + n.y * n.y * a, -n.y);
    }
    Frame(Vec3 s_, Vec3 t_, Vec3 n_) : s(s_), t(t_), n(n_) {}

    Vec3 to_local(Vec3 v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3 to_world(Vec3 v) const { return s * v.x + t * v.y + n * v.z; }
};

// The shading frame of a surface point and its unit geometric normal, from a hit's geometric
// normal ng, shading normal ns and tangent dpdu (none need be unit): n = ns turned to ng's side,
// s = dpdu made orthogonal to n (Gram-Schmidt) when dpdu is usable, else Duff et al.'s basis.
// Unusable normals (zero, not finite) fall back to +z and to ng.
struct ShadingFrame {
    Frame frame;
    Vec3 ng;
};
inline ShadingFrame shading_frame(Vec3 ng_in, Vec3 ns, Vec3 dpdu) {
    const auto usable = [](Vec3 v) { return is_finite(v) && length_squared(v) > 1e-20f; };
    ShadingFrame f;
    f.ng = usable(ng_in) ? normalize(ng_in) : Vec3(0, 0, 1);
    Vec3 n = usable(ns) ? normalize(ns) : f.ng;
    if (dot(n, f.ng) < 0) n = -n;  // ns is specified on ng's side; guard against loaders that flip
    f.frame = Frame(n);
    if (usable(dpdu)) {
        const Vec3 s = dpdu - n * dot(n, dpdu);
        if (length_squared(s) > 1e-12f * length_squared(dpdu)) {
            const Vec3 su = normalize(s);
            f.frame = Frame(su, cross(n, su), n);
        }
    }
    return f;
}

}  // namespace phos
