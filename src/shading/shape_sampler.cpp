// Shape sampling for area lights: every shape becomes a list of world-space patches that can each
// be sampled uniformly by area; a patch is picked in proportion to its area, so the whole surface
// is sampled uniformly (pdf = 1 / total area). Spheres seen from outside are sampled by solid angle.
#include "shading/shape_sampler.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/frame.h"
#include "core/rng.h"
#include "core/warp.h"
#include "scene/bilinear_patch.h"

namespace phos::shading {
namespace {

// Tessellation resolution of curved parts under non-similarity transforms (see the header).
constexpr int kSpherePhi = 128, kSphereTheta = 64, kRingSegments = 256;

// sin^2 of 1.5 degrees: below it the cap is so small that 1 - cos(theta_max) loses all precision
// in float, and the cone is sampled through sin^2 instead.
constexpr float kSmallCapSin2 = 0.00068523f;

// True if the linear part of `t` is a rotation (possibly mirrored) times a uniform scale; `scale`
// receives that scale.
bool is_similarity(const Transform& t, float& scale) {
    const Vec3 c0 = t.vector({1, 0, 0}), c1 = t.vector({0, 1, 0}), c2 = t.vector({0, 0, 1});
    const float l0 = length_squared(c0), l1 = length_squared(c1), l2 = length_squared(c2);
    const float tol = 1e-5f * l0;
    if (!(l0 > 0) || std::fabs(l1 - l0) > tol || std::fabs(l2 - l0) > tol) return false;
    if (std::fabs(dot(c0, c1)) > tol || std::fabs(dot(c0, c2)) > tol || std::fabs(dot(c1, c2)) > tol)
        return false;
    scale = std::sqrt(l0);
    return true;
}

float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }

// Cone of directions subtended by a sphere seen from outside: 1 - cos(theta_max), computed the same
// way by sample() and pdf() so the two agree exactly.
float one_minus_cos_max(float sin2_max) {
    if (sin2_max < kSmallCapSin2) return sin2_max / 2;
    return 1 - safe_sqrt(1 - sin2_max);
}

}  // namespace

ShapeSampler::ShapeSampler(const scene::Shape& s) : to_world_(s.to_world) {
    sign_ = (s.reverse_orientation != s.to_world.swaps_handedness()) ? -1.0f : 1.0f;
    using K = scene::Shape::Kind;
    switch (s.kind) {
        case K::Mesh:
            add_mesh(s);
            break;
        case K::Box:
            add_box(s);
            break;
        case K::Disk:
            add_disk(s, s.center, s.normal, s.radius, s.inner_radius);
            break;
        case K::Sphere:
            add_curved(s, Projection::Sphere);
            break;
        case K::Cylinder: {
            add_curved(s, Projection::CylinderSide);
            if (s.capped) {
                const Vec3 a = normalize(s.axis);
                add_disk(s, s.center + a * (0.5f * s.height), a, s.radius, 0);
                add_disk(s, s.center - a * (0.5f * s.height), -a, s.radius, 0);
            }
            break;
        }
        case K::Cone: {
            add_curved(s, Projection::ConeSide);
            if (s.capped) {
                const Vec3 a = normalize(s.axis);
                add_disk(s, s.center - a * (0.5f * s.height), -a, s.radius, 0);
            }
            break;
        }
        case K::Curves:  // never emits (pbrt-v4 cannot sample curves): no parts
            break;
    }
    if (!std::isfinite(area_)) throw InputError("area light on shape " + s.origin + ": non-finite area");
    by_area_ = Distribution1D(areas_);
}

void ShapeSampler::add_patch(const Patch& patch, float area) {
    if (!(area > 0) || !std::isfinite(area)) return;  // degenerate pieces are never sampled
    patches_.push_back(patch);
    areas_.push_back(area);
    area_ += area;
}

Vec3 ShapeSampler::world_normal(Vec3 n_object) const { return normalize(to_world_.normal(n_object)) * sign_; }

void ShapeSampler::add_mesh(const scene::Shape& s) {
    const auto& m = s.mesh;
    const float flip = sign_;  // the world cross product, flipped if reverse XOR swaps (accel layer)
    const bool identity = s.to_world.is_identity();
    if (!m.normals.empty() && m.normals.size() == m.positions.size()) {
        shading_normals_.resize(m.normals.size());
        for (size_t i = 0; i < m.normals.size(); ++i) {
            const Vec3 n = s.to_world.normal(m.normals[i]);
            const float len = length(n);
            shading_normals_[i] =
                len > 0 && std::isfinite(len) ? n / len * (s.reverse_orientation ? -1.0f : 1.0f) : Vec3(0.0f);
        }
        indices_ = m.indices;
        patch_indices_ = m.patches;
    }
    // A vertex in world space, its index checked.
    const auto corner = [&](uint32_t idx) {
        if (idx >= m.positions.size())
            throw InputError("area light on shape " + s.origin + ": vertex index out of range");
        return identity ? m.positions[idx] : s.to_world.point(m.positions[idx]);
    };
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        Vec3 v[3];
        for (int k = 0; k < 3; ++k) v[k] = corner(m.indices[3 * t + size_t(k)]);
        Patch p;
        p.kind = PatchKind::Triangle;
        p.triangle = uint32_t(t);
        p.o = v[0];
        p.e1 = v[1] - v[0];
        p.e2 = v[2] - v[0];
        const Vec3 c = cross(p.e1, p.e2);
        const float len = length(c);
        if (!(len > 0)) continue;
        p.n = c / len * flip;
        add_patch(p, 0.5f * len);
    }
    // Exact bilinear patches: sampled uniformly by area (sample_bilinear), picked by their area.
    for (size_t q = 0; q < m.patch_count(); ++q) {
        scene::PatchCorners c;
        for (size_t k = 0; k < 4; ++k) c[k] = corner(m.patches[4 * q + k]);
        Patch p;
        p.kind = PatchKind::Bilinear;
        p.triangle = uint32_t(q);
        p.o = c[0];
        p.e1 = c[1] - c[0];
        p.e2 = c[2] - c[0];
        p.n = c[3] - c[1] - c[2] + c[0];  // the twist: p(u, v) = o + e1 u + e2 v + n u v
        p.b = m.patches_flipped ? -flip : flip;
        // |dp/du x dp/dv| is the norm of a function affine in (u, v), so convex: largest at a corner.
        for (float u : {0.0f, 1.0f})
            for (float v : {0.0f, 1.0f}) p.a = std::max(p.a, length(cross(p.e1 + p.n * v, p.e2 + p.n * u)));
        add_patch(p, float(scene::patch_area(c)));
    }
}

void ShapeSampler::add_box(const scene::Shape& s) {
    const Vec3 lo = min(s.box_min, s.box_max), hi = max(s.box_min, s.box_max);
    for (int axis = 0; axis < 3; ++axis) {
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            Vec3 corner = lo, e1{0.0f}, e2{0.0f}, n{0.0f};
            corner[axis] = side ? hi[axis] : lo[axis];
            e1[a1] = hi[a1] - lo[a1];
            e2[a2] = hi[a2] - lo[a2];
            n[axis] = side ? 1.0f : -1.0f;
            Patch p;
            p.kind = PatchKind::Parallelogram;
            p.o = s.to_world.point(corner);
            p.e1 = s.to_world.vector(e1);
            p.e2 = s.to_world.vector(e2);
            // The accel layer meshes boxes, so the mesh rule applies: outward unless reversed.
            p.n = normalize(s.to_world.normal(n)) * (s.reverse_orientation ? -1.0f : 1.0f);
            add_patch(p, length(cross(p.e1, p.e2)));
        }
    }
}

void ShapeSampler::add_disk(const scene::Shape& s, Vec3 center, Vec3 normal, float radius, float inner) {
    if (!(radius > 0)) return;
    const Vec3 n_obj = normalize(normal);
    const Frame f(n_obj);
    Patch p;
    p.kind = PatchKind::Annulus;
    p.o = s.to_world.point(center);
    p.e1 = s.to_world.vector(f.s * radius);
    p.e2 = s.to_world.vector(f.t * radius);
    p.n = world_normal(n_obj);
    p.a = std::clamp(inner / radius, 0.0f, 1.0f);
    // An affine image of a disk is an ellipse with semi-axes e1, e2: area pi |e1 x e2|.
    add_patch(p, kPi * (1 - p.a * p.a) * length(cross(p.e1, p.e2)));
}

void ShapeSampler::add_curved(const scene::Shape& s, Projection kind) {
    obj_center_ = s.center;
    obj_axis_ = normalize(s.axis);
    obj_radius_ = s.radius;
    obj_height_ = s.height;
    if (!(s.radius > 0) || (kind != Projection::Sphere && !(s.height > 0))) return;
    if (kind == Projection::Sphere && s.partial) {
        // Clamped as the accel layer and pbrt-v4 do.
        obj_partial_ = true;
        obj_z_min_ = std::clamp(std::min(s.z_min, s.z_max), -s.radius, s.radius);
        obj_z_max_ = std::clamp(std::max(s.z_min, s.z_max), -s.radius, s.radius);
        obj_phi_max_ = std::clamp(s.phi_max, 0.0f, 2 * kPi);
        if (!(obj_z_max_ > obj_z_min_) || !(obj_phi_max_ > 0)) return;
    }
    float scale = 1;
    if (!is_similarity(s.to_world, scale)) {
        tessellate(s, kind);
        return;
    }
    Patch p;
    p.o = s.to_world.point(s.center);
    p.a = s.radius * scale;
    p.b = sign_;
    if (kind == Projection::Sphere && obj_partial_) {
        // Archimedes: z uniform in [z_min, z_max] and phi uniform in [0, phi_max] is uniform by
        // area, and a similarity scales every area by scale^2.
        p.kind = PatchKind::PartialSphere;
        add_patch(p, obj_phi_max_ * s.radius * (obj_z_max_ - obj_z_min_) * scale * scale);
        return;
    }
    if (kind == Projection::Sphere) {
        p.kind = PatchKind::Sphere;
        sphere_cone_ = true;
        sphere_center_ = p.o;
        sphere_radius_ = p.a;
        add_patch(p, 4 * kPi * p.a * p.a);
        return;
    }
    const Vec3 axis = normalize(s.to_world.vector(obj_axis_));
    const Frame f(axis);
    const float r = p.a, h = s.height * scale;
    p.n = axis;
    p.e1 = f.s * r;
    p.e2 = f.t * r;
    p.a = h;
    if (kind == Projection::CylinderSide) {
        p.kind = PatchKind::CylinderSide;
        add_patch(p, 2 * kPi * r * h);
    } else {
        p.kind = PatchKind::ConeSide;
        p.o = p.o + axis * (0.5f * h);  // the apex
        add_patch(p, kPi * r * std::sqrt(r * r + h * h));
    }
}

void ShapeSampler::tessellate(const scene::Shape& s, Projection kind) {
    projection_ = kind;
    auto add_triangle = [&](Vec3 a, Vec3 b, Vec3 c) {
        Patch p;
        p.kind = PatchKind::Triangle;
        p.project = true;
        p.o = s.to_world.point(a);
        p.e1 = s.to_world.point(b) - p.o;
        p.e2 = s.to_world.point(c) - p.o;
        add_patch(p, 0.5f * length(cross(p.e1, p.e2)));  // the normal comes from the projection
    };
    const Vec3 c = obj_center_, ax = obj_axis_;
    const float r = obj_radius_, h = obj_height_;
    if (kind == Projection::Sphere) {
        // The whole sphere, or a partial sphere's theta and phi ranges (its frame: Frame(axis)).
        const float theta0 = obj_partial_ ? std::acos(std::clamp(obj_z_max_ / r, -1.0f, 1.0f)) : 0.0f;
        const float theta1 = obj_partial_ ? std::acos(std::clamp(obj_z_min_ / r, -1.0f, 1.0f)) : kPi;
        const float phi1 = obj_partial_ ? obj_phi_max_ : 2 * kPi;
        const Frame frame(ax);
        auto at = [&](int i, int j) {
            const float phi = phi1 * float(i) / kSpherePhi,
                        theta = theta0 + (theta1 - theta0) * float(j) / kSphereTheta;
            if (!obj_partial_)
                return c + Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                std::cos(theta)) *
                               r;
            return c + frame.to_world(Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                           std::cos(theta))) *
                           r;
        };
        for (int j = 0; j < kSphereTheta; ++j)
            for (int i = 0; i < kSpherePhi; ++i) {
                add_triangle(at(i, j), at(i, j + 1), at(i + 1, j + 1));
                add_triangle(at(i, j), at(i + 1, j + 1), at(i + 1, j));
            }
        return;
    }
    const Frame f(ax);
    auto ring = [&](int i, float rr, float z) {
        const float phi = 2 * kPi * float(i) / kRingSegments;
        return c + ax * z + (f.s * std::cos(phi) + f.t * std::sin(phi)) * rr;
    };
    for (int i = 0; i < kRingSegments; ++i) {
        if (kind == Projection::CylinderSide) {
            add_triangle(ring(i, r, -h / 2), ring(i + 1, r, -h / 2), ring(i + 1, r, h / 2));
            add_triangle(ring(i, r, -h / 2), ring(i + 1, r, h / 2), ring(i, r, h / 2));
        } else {
            add_triangle(c + ax * (h / 2), ring(i, r, -h / 2), ring(i + 1, r, -h / 2));
        }
    }
}

void ShapeSampler::project(Vec3& p, Vec3& n) const {
    const Vec3 q = to_world_.inverse().point(p);
    const Vec3 c = obj_center_, ax = obj_axis_;
    const float r = obj_radius_, h = obj_height_;
    Vec3 p_obj = q, n_obj = ax;
    auto radial_unit = [&](Vec3 v) {
        const float len = length(v);
        return len > 0 ? v / len : Frame(ax).s;
    };
    switch (projection_) {
        case Projection::Sphere: {
            const Vec3 d = q - c;
            n_obj = length(d) > 0 ? normalize(d) : ax;
            if (obj_partial_) {
                // Keep the projected point on the partial surface: clamp z and phi to its ranges.
                const Frame frame(ax);
                const Vec3 l = frame.to_local(n_obj * r);
                const float z = std::clamp(l.z, obj_z_min_, obj_z_max_);
                float phi = std::atan2(l.y, l.x);
                if (phi < 0) phi += 2 * kPi;
                if (phi > obj_phi_max_) phi = phi - obj_phi_max_ < 2 * kPi - phi ? obj_phi_max_ : 0.0f;
                const float rho = safe_sqrt(r * r - z * z);
                n_obj = frame.to_world(Vec3(rho * std::cos(phi), rho * std::sin(phi), z)) / r;
            }
            p_obj = c + n_obj * r;
            break;
        }
        case Projection::CylinderSide: {
            const float z = dot(q - c, ax);
            n_obj = radial_unit(q - c - ax * z);
            p_obj = c + ax * z + n_obj * r;
            break;
        }
        case Projection::ConeSide: {
            const Vec3 apex = c + ax * (h / 2);
            const float depth = std::clamp(-dot(q - apex, ax), 0.0f, h);
            const Vec3 ru = radial_unit(q - apex + ax * depth);
            p_obj = apex - ax * depth + ru * (r * depth / h);
            n_obj = normalize(ru * h + ax * r);
            break;
        }
        case Projection::None:
            return;
    }
    p = to_world_.point(p_obj);
    n = world_normal(n_obj);
}

ShapeSample ShapeSampler::sample_patch(const Patch& pt, Vec2 u) const {
    ShapeSample out;
    switch (pt.kind) {
        case PatchKind::Triangle: {
            const Vec2 b = warp::uniform_triangle(u);
            out.p = pt.o + pt.e1 * b.x + pt.e2 * b.y;
            out.n = pt.n;
            if (!pt.project) {
                out.triangle = int(pt.triangle);
                out.barycentric = b;
            }
            if (!shading_normals_.empty() && !pt.project) {
                // As the accel layer does: the geometric normal follows the interpolated shading one.
                const uint32_t* idx = &indices_[3 * size_t(pt.triangle)];
                const Vec3 ns = shading_normals_[idx[0]] * (1 - b.x - b.y) + shading_normals_[idx[1]] * b.x +
                                shading_normals_[idx[2]] * b.y;
                if (dot(ns, out.n) < 0) out.n = -out.n;
            }
            break;
        }
        case PatchKind::Parallelogram:
            out.p = pt.o + pt.e1 * u.x + pt.e2 * u.y;
            out.n = pt.n;
            break;
        case PatchKind::Annulus: {
            // Uniform in the unit annulus, then the affine map keeps it uniform.
            const float rho = std::sqrt(pt.a * pt.a + u.x * (1 - pt.a * pt.a));
            const float phi = 2 * kPi * u.y;
            out.p = pt.o + pt.e1 * (rho * std::cos(phi)) + pt.e2 * (rho * std::sin(phi));
            out.n = pt.n;
            break;
        }
        case PatchKind::Sphere: {
            const Vec3 d = warp::uniform_sphere(u);
            out.p = pt.o + d * pt.a;
            out.n = d * pt.b;
            break;
        }
        case PatchKind::Bilinear: {
            const Vec2 uv = sample_bilinear(pt, u);
            out.p = pt.o + pt.e1 * uv.x + pt.e2 * uv.y + pt.n * (uv.x * uv.y);
            out.n = normalize(cross(pt.e1 + pt.n * uv.y, pt.e2 + pt.n * uv.x)) * pt.b;
            if (!patch_indices_.empty()) {
                // As the accel layer does: the geometric normal follows the interpolated shading one.
                const uint32_t* idx = &patch_indices_[4 * size_t(pt.triangle)];
                const Vec3 ns = shading_normals_[idx[0]] * ((1 - uv.x) * (1 - uv.y)) +
                                shading_normals_[idx[1]] * (uv.x * (1 - uv.y)) +
                                shading_normals_[idx[2]] * ((1 - uv.x) * uv.y) +
                                shading_normals_[idx[3]] * (uv.x * uv.y);
                if (dot(ns, out.n) < 0) out.n = -out.n;
            }
            break;
        }
        case PatchKind::PartialSphere: {
            const float z = obj_z_min_ + (obj_z_max_ - obj_z_min_) * u.x, phi = obj_phi_max_ * u.y;
            const float rho = safe_sqrt(obj_radius_ * obj_radius_ - z * z);
            const Vec3 d = Frame(obj_axis_).to_world(Vec3(rho * std::cos(phi), rho * std::sin(phi), z));
            out.p = to_world_.point(obj_center_ + d);
            out.n = world_normal(d);
            break;
        }
        case PatchKind::CylinderSide: {
            const float phi = 2 * kPi * u.x;
            const Vec3 radial = pt.e1 * std::cos(phi) + pt.e2 * std::sin(phi);
            out.p = pt.o + pt.n * ((u.y - 0.5f) * pt.a) + radial;
            out.n = normalize(radial) * pt.b;
            break;
        }
        case PatchKind::ConeSide: {
            // Area grows linearly with the distance t from the apex, so t = sqrt(u) is uniform.
            const float t = std::sqrt(u.x), phi = 2 * kPi * u.y;
            const float r = length(pt.e1), h = pt.a;
            const Vec3 ru = (pt.e1 * std::cos(phi) + pt.e2 * std::sin(phi)) / r;
            out.p = pt.o - pt.n * (h * t) + ru * (r * t);
            out.n = normalize(ru * h + pt.n * r) * pt.b;
            break;
        }
    }
    if (pt.project) project(out.p, out.n);
    return out;
}

Vec2 ShapeSampler::sample_bilinear(const Patch& pt, Vec2 u) {
    // Rejection sampling: (s, t) uniform, kept with probability J(s, t) / J_max, has density
    // proportional to the area element J = |dp/du x dp/dv|, i.e. uniform by area. The first try
    // uses u itself; later ones, and every acceptance test, numbers keyed by u's bits (a function of
    // u, so the result is deterministic).
    Sampler rng(0x62696c696e656172ull, std::bit_cast<uint32_t>(u.x), std::bit_cast<uint32_t>(u.y));
    Vec2 st = u;
    for (int tries = 0; tries < 64; ++tries) {
        const float j = length(cross(pt.e1 + pt.n * st.y, pt.e2 + pt.n * st.x));
        if (rng.next() * pt.a <= j) break;
        st = rng.next2();
    }
    return st;
}

ShapeSample ShapeSampler::sample_area(Vec2 u) const {
    if (patches_.empty()) return {};
    float remapped = 0;
    const size_t i = by_area_.sample_discrete(u.x, nullptr, &remapped);
    ShapeSample s = sample_patch(patches_[i], {remapped, u.y});
    s.pdf = 1 / area_;
    return s;
}

// Cone sampling needs a reference point strictly outside the sphere. A point ON the sphere (a hit on
// the emitter itself, whose position is only accurate to a few ulps and may land just outside)
// would see a "cap" of almost a hemisphere and find its own surface, losing all its light; such
// points, and points inside, use area sampling, which is valid everywhere.
constexpr float kConeSamplingMargin = 1.0001f;

ShapeSample ShapeSampler::sample(Vec3 ref, Vec2 u) const {
    if (sphere_cone_) {
        const Vec3 to_c = sphere_center_ - ref;
        const float dc2 = length_squared(to_c), r2 = sphere_radius_ * sphere_radius_;
        if (dc2 > r2 * kConeSamplingMargin) {
            // Uniform over the cone of the visible cap; the point is found from the angle alpha at
            // the centre between (centre -> ref) and (centre -> point).
            const float dc = std::sqrt(dc2);
            const float sin2_max = r2 / dc2, sin_max = std::sqrt(sin2_max);
            const float omc = one_minus_cos_max(sin2_max);
            float cos_t, sin2_t;
            if (sin2_max < kSmallCapSin2) {
                sin2_t = sin2_max * u.x;
                cos_t = std::sqrt(1 - sin2_t);
            } else {
                cos_t = 1 - u.x * omc;
                sin2_t = 1 - cos_t * cos_t;
            }
            const float cos_alpha = sin2_t / sin_max + cos_t * safe_sqrt(1 - sin2_t / sin2_max);
            const float sin_alpha = safe_sqrt(1 - cos_alpha * cos_alpha);
            const float phi = 2 * kPi * u.y;
            const Frame f(to_c / dc);
            const Vec3 n_out =
                f.to_world({-sin_alpha * std::cos(phi), -sin_alpha * std::sin(phi), -cos_alpha});
            ShapeSample s;
            s.p = sphere_center_ + n_out * sphere_radius_;
            s.n = n_out * sign_;
            s.pdf = 1 / (2 * kPi * omc);
            return s;
        }
    }
    ShapeSample s = sample_area(u);
    if (s.pdf == 0) return s;
    const Vec3 d = s.p - ref;
    const float dist2 = length_squared(d);
    if (!(dist2 > 0)) return s.pdf = 0, s;
    const float cos_l = std::fabs(dot(s.n, d)) / std::sqrt(dist2);
    s.pdf = cos_l > 0 ? s.pdf * dist2 / cos_l : 0;
    return s;
}

float ShapeSampler::pdf(Vec3 ref, Vec3 wi, Vec3 p, Vec3 n) const {
    if (patches_.empty()) return 0;
    if (sphere_cone_) {
        const float dc2 = length_squared(sphere_center_ - ref), r2 = sphere_radius_ * sphere_radius_;
        if (dc2 > r2 * kConeSamplingMargin) return 1 / (2 * kPi * one_minus_cos_max(r2 / dc2));
    }
    const float dist2 = length_squared(p - ref);
    const float cos_l = std::fabs(dot(n, wi));
    return cos_l > 0 && dist2 > 0 ? dist2 / (area_ * cos_l) : 0;
}

}  // namespace phos::shading
