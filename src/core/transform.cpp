// Matrix product, inverse and the standard transform constructors.
#include "core/transform.h"

#include <cmath>
#include <stdexcept>

namespace phos {

Mat4 Mat4::operator*(const Mat4& o) const {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += double((*this)(i, k)) * double(o(k, j));
            r(i, j) = float(s);
        }
    return r;
}

Mat4 Mat4::transposed() const {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r(i, j) = (*this)(j, i);
    return r;
}

bool Mat4::inverse(Mat4& out) const {
    // Gauss-Jordan elimination with partial pivoting, in double precision.
    double a[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 8; ++j) a[i][j] = j < 4 ? double((*this)(i, j)) : (j - 4 == i ? 1.0 : 0.0);
    for (int c = 0; c < 4; ++c) {
        int pivot = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::fabs(a[r][c]) > std::fabs(a[pivot][c])) pivot = r;
        if (!(std::fabs(a[pivot][c]) > 1e-12)) return false;
        if (pivot != c)
            for (int j = 0; j < 8; ++j) std::swap(a[c][j], a[pivot][j]);
        const double inv = 1.0 / a[c][c];
        for (int j = 0; j < 8; ++j) a[c][j] *= inv;
        for (int r = 0; r < 4; ++r) {
            if (r == c) continue;
            const double f = a[r][c];
            if (f != 0)
                for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
        }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out(i, j) = float(a[i][j + 4]);
    return true;
}

Transform Transform::translate(Vec3 d) {
    Mat4 m, inv;
    m(0, 3) = d.x, m(1, 3) = d.y, m(2, 3) = d.z;
    inv(0, 3) = -d.x, inv(1, 3) = -d.y, inv(2, 3) = -d.z;
    return {m, inv};
}

Transform Transform::scale(Vec3 s) {
    if (s.x == 0 || s.y == 0 || s.z == 0) throw std::invalid_argument("scale by zero");
    Mat4 m, inv;
    m(0, 0) = s.x, m(1, 1) = s.y, m(2, 2) = s.z;
    inv(0, 0) = 1 / s.x, inv(1, 1) = 1 / s.y, inv(2, 2) = 1 / s.z;
    return {m, inv};
}

Transform Transform::rotate(float degrees, Vec3 axis) {
    if (!(length(axis) > 0)) throw std::invalid_argument("rotation about a zero axis");
    const Vec3 a = normalize(axis);
    const double theta = double(degrees) * 3.14159265358979323846 / 180.0;
    const float s = float(std::sin(theta)), c = float(std::cos(theta));
    Mat4 m;
    m(0, 0) = a.x * a.x + (1 - a.x * a.x) * c;
    m(0, 1) = a.x * a.y * (1 - c) - a.z * s;
    m(0, 2) = a.x * a.z * (1 - c) + a.y * s;
    m(1, 0) = a.x * a.y * (1 - c) + a.z * s;
    m(1, 1) = a.y * a.y + (1 - a.y * a.y) * c;
    m(1, 2) = a.y * a.z * (1 - c) - a.x * s;
    m(2, 0) = a.x * a.z * (1 - c) - a.y * s;
    m(2, 1) = a.y * a.z * (1 - c) + a.x * s;
    m(2, 2) = a.z * a.z + (1 - a.z * a.z) * c;
    return {m, m.transposed()};
}

Transform Transform::look_at(Vec3 eye, Vec3 target, Vec3 up) {
    const Vec3 dir = target - eye;
    if (!(length(dir) > 0)) throw std::invalid_argument("LookAt: eye and target coincide");
    const Vec3 d = normalize(dir);
    const Vec3 r = cross(normalize(up), d);
    if (!(length(r) > 0)) throw std::invalid_argument("LookAt: up vector parallel to viewing direction");
    const Vec3 right = normalize(r);
    const Vec3 new_up = cross(d, right);
    Mat4 cam_to_world;
    for (int i = 0; i < 3; ++i) {
        cam_to_world(i, 0) = right[i];
        cam_to_world(i, 1) = new_up[i];
        cam_to_world(i, 2) = d[i];
        cam_to_world(i, 3) = eye[i];
    }
    Mat4 world_to_cam;
    cam_to_world.inverse(world_to_cam);
    return {world_to_cam, cam_to_world};
}

bool Transform::swaps_handedness() const {
    const Mat4& a = m_;
    const float det = a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)) -
                      a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0)) +
                      a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
    return det < 0;
}

Vec3 Transform::point(Vec3 p) const {
    const Mat4& a = m_;
    const float x = a(0, 0) * p.x + a(0, 1) * p.y + a(0, 2) * p.z + a(0, 3);
    const float y = a(1, 0) * p.x + a(1, 1) * p.y + a(1, 2) * p.z + a(1, 3);
    const float z = a(2, 0) * p.x + a(2, 1) * p.y + a(2, 2) * p.z + a(2, 3);
    const float w = a(3, 0) * p.x + a(3, 1) * p.y + a(3, 2) * p.z + a(3, 3);
    return w == 1 ? Vec3(x, y, z) : Vec3(x, y, z) / w;
}

Vec3 Transform::vector(Vec3 v) const {
    const Mat4& a = m_;
    return {a(0, 0) * v.x + a(0, 1) * v.y + a(0, 2) * v.z, a(1, 0) * v.x + a(1, 1) * v.y + a(1, 2) * v.z,
            a(2, 0) * v.x + a(2, 1) * v.y + a(2, 2) * v.z};
}

Vec3 Transform::normal(Vec3 n) const {
    const Mat4& b = inv_;
    return {b(0, 0) * n.x + b(1, 0) * n.y + b(2, 0) * n.z, b(0, 1) * n.x + b(1, 1) * n.y + b(2, 1) * n.z,
            b(0, 2) * n.x + b(1, 2) * n.y + b(2, 2) * n.z};
}

}  // namespace phos
