// Perlin gradient noise, fbm and turbulence (see perlin_noise.h).
#include "scene/perlin_noise.h"

#include <array>
#include <cmath>

namespace phos::scene {
namespace {

// Perlin's permutation of 0..255 (the table of his reference implementation).
constexpr std::array<int, 256> kPermutation = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103, 30,
    69,  142, 8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,  197, 62,
    94,  252, 219, 203, 117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136,
    171, 168, 68,  175, 74,  165, 71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122,
    60,  211, 133, 230, 220, 105, 92,  41,  55,  46,  245, 40,  244, 102, 143, 54,  65,  25,  63,  161,
    1,   216, 80,  73,  209, 76,  132, 187, 208, 89,  18,  169, 200, 196, 135, 130, 116, 188, 159, 86,
    164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250, 124, 123, 5,   202, 38,  147, 118, 126,
    255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,  182, 189, 28,  42,  223, 183, 170, 213,
    119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,   129, 22,  39,  253,
    19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,  242, 193,
    238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,
    181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,
    222, 114, 67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180};

constexpr bool is_permutation(const std::array<int, 256>& p) {
    std::array<bool, 256> seen{};
    for (int v : p) {
        if (v < 0 || v > 255 || seen[size_t(v)]) return false;
        seen[size_t(v)] = true;
    }
    return true;
}
static_assert(is_permutation(kPermutation));

int perm(int i) { return kPermutation[size_t(i & 255)]; }

// The gradient of lattice corner (x, y, z) dotted with the offset (dx, dy, dz) from it: one of
// the twelve edge directions of a cube (four repeated), chosen by the corner's hash as pbrt-v4
// chooses it.
float gradient(int x, int y, int z, float dx, float dy, float dz) {
    const int h = perm(perm(perm(x) + y) + z) & 15;
    const float u = h < 8 || h == 12 || h == 13 ? dx : dy;
    const float v = h < 4 || h == 12 || h == 13 ? dy : dz;
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

// Perlin's quintic fade 6t^5 - 15t^4 + 10t^3 (C2 across cell faces).
float fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }

float lerp(float t, float a, float b) { return (1 - t) * a + t * b; }

}  // namespace

float perlin_noise(float x, float y, float z) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return 0;
    constexpr float kPeriod = float(1 << 30);
    x = std::fmod(x, kPeriod);
    y = std::fmod(y, kPeriod);
    z = std::fmod(z, kPeriod);
    const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const float dx = x - fx, dy = y - fy, dz = z - fz;
    const int ix = int(fx) & 255, iy = int(fy) & 255, iz = int(fz) & 255;

    const float w000 = gradient(ix, iy, iz, dx, dy, dz);
    const float w100 = gradient(ix + 1, iy, iz, dx - 1, dy, dz);
    const float w010 = gradient(ix, iy + 1, iz, dx, dy - 1, dz);
    const float w110 = gradient(ix + 1, iy + 1, iz, dx - 1, dy - 1, dz);
    const float w001 = gradient(ix, iy, iz + 1, dx, dy, dz - 1);
    const float w101 = gradient(ix + 1, iy, iz + 1, dx - 1, dy, dz - 1);
    const float w011 = gradient(ix, iy + 1, iz + 1, dx, dy - 1, dz - 1);
    const float w111 = gradient(ix + 1, iy + 1, iz + 1, dx - 1, dy - 1, dz - 1);

    const float wx = fade(dx), wy = fade(dy), wz = fade(dz);
    const float x00 = lerp(wx, w000, w100), x10 = lerp(wx, w010, w110);
    const float x01 = lerp(wx, w001, w101), x11 = lerp(wx, w011, w111);
    return lerp(wz, lerp(wy, x00, x10), lerp(wy, x01, x11));
}

float fbm(Vec3 p, float omega, int octaves) {
    float sum = 0, lambda = 1, o = 1;
    for (int i = 0; i < octaves; ++i) {
        sum += o * perlin_noise(p * lambda);
        lambda *= 1.99f;
        o *= omega;
    }
    return sum;
}

float turbulence(Vec3 p, float omega, int octaves) {
    float sum = 0, lambda = 1, o = 1;
    for (int i = 0; i < octaves; ++i) {
        sum += o * std::fabs(perlin_noise(p * lambda));
        lambda *= 1.99f;
        o *= omega;
    }
    return sum + o * 0.2f;
}

}  // namespace phos::scene
