// Affine transforms as 4x4 row-major matrices with their inverse kept alongside, for instancing,
// `.scn` groups and pbrt's transform directives. Normals transform by the inverse transpose.
#pragma once

#include <array>

#include "core/vec.h"

namespace phos {

struct Mat4 {
    std::array<float, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // row-major

    float operator()(int r, int c) const { return m[size_t(r * 4 + c)]; }
    float& operator()(int r, int c) { return m[size_t(r * 4 + c)]; }
    Mat4 operator*(const Mat4& o) const;
    bool operator==(const Mat4&) const = default;
    Mat4 transposed() const;
    // Inverse by Gauss-Jordan elimination; returns false (and leaves `out` untouched) when singular.
    bool inverse(Mat4& out) const;
    bool is_identity() const { return *this == Mat4{}; }
};

class Transform {
public:
    Transform() = default;
    Transform(const Mat4& m, const Mat4& inv) : m_(m), inv_(inv) {}

    static Transform translate(Vec3 d);
    static Transform scale(Vec3 s);
    // Rotation by `degrees` about `axis` (right-handed).
    static Transform rotate(float degrees, Vec3 axis);
    // pbrt-style LookAt: camera-to-world inverse (world-to-camera), left-handed camera space.
    static Transform look_at(Vec3 eye, Vec3 target, Vec3 up);

    Transform operator*(const Transform& o) const { return {m_ * o.m_, o.inv_ * inv_}; }
    Transform inverse() const { return {inv_, m_}; }
    const Mat4& matrix() const { return m_; }
    bool is_identity() const { return m_.is_identity(); }
    bool swaps_handedness() const;

    Vec3 point(Vec3 p) const;
    Vec3 vector(Vec3 v) const;
    // Transforms a normal (inverse transpose); not normalised.
    Vec3 normal(Vec3 n) const;

private:
    Mat4 m_{};
    Mat4 inv_{};
};

}  // namespace phos
