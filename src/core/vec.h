// Small fixed-size vector types (Vec2, Vec3) and RGB colour used everywhere in phos.
// Single-precision on purpose: Embree, the film and the photon record all work in float.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace phos {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInf = 1e30f;

// std::nextafter(x, toward) for floats without the library call (hot in ray spawning): the same
// value for every input, NaN and signed zeros included.
inline float next_float(float x, float toward) {
    if (x == toward) return toward;
    if (x != x || toward != toward) return x + toward;
    if (x == 0) return toward > 0 ? 0x1p-149f : -0x1p-149f;
    uint32_t b;
    std::memcpy(&b, &x, 4);
    b = (x < toward) == (x > 0) ? b + 1 : b - 1;  // away from zero, or towards it
    std::memcpy(&x, &b, 4);
    return x;
}

struct Vec2 {
    float x = 0, y = 0;
    constexpr Vec2() = default;
    constexpr Vec2(float x_, float y_) : x(x_), y(y_) {}
    constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
    constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
    constexpr Vec2 operator*(float s) const { return {x * s, y * s}; }
    constexpr bool operator==(const Vec2&) const = default;
};

struct Vec3 {
    float x = 0, y = 0, z = 0;
    constexpr Vec3() = default;
    constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}

    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3 operator+(Vec3 o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3 operator-(Vec3 o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3 operator*(Vec3 o) const { return {x * o.x, y * o.y, z * o.z}; }
    constexpr Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator/(float s) const { return {x / s, y / s, z / s}; }
    constexpr Vec3& operator+=(Vec3 o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    constexpr Vec3& operator-=(Vec3 o) {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    constexpr Vec3& operator*=(float s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    constexpr bool operator==(const Vec3&) const = default;
};

constexpr Vec3 operator*(float s, Vec3 v) { return v * s; }
constexpr float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 v) { return std::sqrt(dot(v, v)); }
constexpr float length_squared(Vec3 v) { return dot(v, v); }
inline Vec3 normalize(Vec3 v) { return v / length(v); }
inline Vec3 min(Vec3 a, Vec3 b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
inline Vec3 max(Vec3 a, Vec3 b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
inline Vec3 abs(Vec3 v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }
inline float max_component(Vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }
inline bool is_finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
// Mirror direction of `wo` about normal `n` (both pointing away from the surface).
constexpr Vec3 reflect(Vec3 wo, Vec3 n) { return 2.0f * dot(wo, n) * n - wo; }

// Linear RGB radiometric quantity (radiance, flux, albedo...), one value per channel.
struct Rgb {
    float r = 0, g = 0, b = 0;
    constexpr Rgb() = default;
    constexpr explicit Rgb(float s) : r(s), g(s), b(s) {}
    constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}

    constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    constexpr float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
    constexpr Rgb operator+(Rgb o) const { return {r + o.r, g + o.g, b + o.b}; }
    constexpr Rgb operator-(Rgb o) const { return {r - o.r, g - o.g, b - o.b}; }
    constexpr Rgb operator*(Rgb o) const { return {r * o.r, g * o.g, b * o.b}; }
    constexpr Rgb operator/(Rgb o) const { return {r / o.r, g / o.g, b / o.b}; }
    constexpr Rgb operator*(float s) const { return {r * s, g * s, b * s}; }
    constexpr Rgb operator/(float s) const { return {r / s, g / s, b / s}; }
    constexpr Rgb& operator+=(Rgb o) {
        r += o.r;
        g += o.g;
        b += o.b;
        return *this;
    }
    constexpr Rgb& operator*=(Rgb o) {
        r *= o.r;
        g *= o.g;
        b *= o.b;
        return *this;
    }
    constexpr Rgb& operator*=(float s) {
        r *= s;
        g *= s;
        b *= s;
        return *this;
    }
    constexpr bool operator==(const Rgb&) const = default;

    constexpr bool is_black() const { return r == 0 && g == 0 && b == 0; }
    constexpr float max() const { return std::max(r, std::max(g, b)); }
    constexpr float average() const { return (r + g + b) * (1.0f / 3.0f); }
    constexpr float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
    bool is_finite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};
constexpr Rgb operator*(float s, Rgb c) { return c * s; }
inline Rgb max(Rgb a, Rgb b) { return {std::max(a.r, b.r), std::max(a.g, b.g), std::max(a.b, b.b)}; }
inline Rgb exp(Rgb a) { return {std::exp(a.r), std::exp(a.g), std::exp(a.b)}; }

}  // namespace phos
