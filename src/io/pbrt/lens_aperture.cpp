// pbrt-v4's aperture shapes for the realistic camera (as RealisticCamera::Create builds them): the
// named diaphragms rasterised over [-1, 1]^2, images averaged to one channel, each turned so that
// its rows run from the stop's -y to its +y and scaled to a circle's mean transmission, pi/4.
#include "io/pbrt/lens_aperture.h"

#include <array>
#include <cmath>
#include <span>
#include <vector>

#include "core/vec.h"

namespace phos::io::pbrt {

namespace {

constexpr int kResolution = 256;

// Scales `a` to mean pi/4; false when it is black.
bool normalise(scene::ApertureImage& a) {
    double sum = 0;
    for (const float v : a.values) sum += double(v);
    if (!(sum > 0)) return false;
    const double scale = (kPi / 4) / (sum / double(a.values.size()));
    for (float& v : a.values) v = float(double(v) * scale);
    return true;
}

// Whether p is inside the polygon: a non-zero winding number (each edge crossing the horizontal
// line through p counted +1 upwards with p on its left, -1 downwards with p on its right).
bool inside(std::span<const Vec2> poly, Vec2 p) {
    int winding = 0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        const float side = (b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y);
        if (a.y <= p.y && b.y > p.y && side > 0) ++winding;
        if (a.y > p.y && b.y <= p.y && side < 0) --winding;
    }
    return winding != 0;
}

// A shape given as its value at points of [-1, 1]^2. pbrt-v4 rasterises it with rows going up in
// y and then flips the image, so the stop's row at height y shows the shape at -y.
template <typename Shape>
scene::ApertureImage rasterise(Shape shape) {
    scene::ApertureImage a;
    a.width = a.height = kResolution;
    a.values.resize(size_t(kResolution) * kResolution);
    for (int y = 0; y < kResolution; ++y)
        for (int x = 0; x < kResolution; ++x) {
            const Vec2 p(-1 + 2 * (float(x) + 0.5f) / kResolution, -1 + 2 * (float(y) + 0.5f) / kResolution);
            a.values[size_t(y) * kResolution + size_t(x)] = shape(Vec2(p.x, -p.y));
        }
    return a;
}

}  // namespace

std::optional<scene::ApertureImage> named_aperture(const std::string& name) {
    scene::ApertureImage a;
    if (name == "gaussian") {
        a = rasterise(
            [](Vec2 p) { return std::max(0.0f, std::exp(-(p.x * p.x + p.y * p.y)) - std::exp(-1.0f)); });
    } else if (name == "square") {
        // pbrt-v4 fills pixels [64, 192) of each side: |p| < 0.5.
        a = rasterise([](Vec2 p) { return std::fabs(p.x) < 0.5f && std::fabs(p.y) < 0.5f ? 4.0f : 0.0f; });
    } else if (name == "pentagon") {
        // A regular pentagon with a vertex at +y, radius 0.8 (MathWorld's coordinates).
        const float c1 = (std::sqrt(5.0f) - 1) / 4, c2 = (std::sqrt(5.0f) + 1) / 4;
        const float s1 = std::sqrt(10 + 2 * std::sqrt(5.0f)) / 4,
                    s2 = std::sqrt(10 - 2 * std::sqrt(5.0f)) / 4;
        std::array<Vec2, 5> v = {Vec2(0, 1), Vec2(s1, c1), Vec2(s2, -c2), Vec2(-s2, -c2), Vec2(-s1, c1)};
        for (Vec2& p : v) p = p * 0.8f;
        a = rasterise([&](Vec2 p) { return inside(v, p) ? 1.0f : 0.0f; });
    } else if (name == "star") {
        // Ten vertices alternating between the outer radius 1 and the inner cos 72° / cos 36°.
        std::array<Vec2, 10> v;
        const float inner = std::cos(0.4f * kPi) / std::cos(0.2f * kPi);
        for (int i = 0; i < 10; ++i) {
            const float r = (i & 1) ? 1.0f : inner, phi = kPi * float(i) / 5;
            v[size_t(9 - i)] = Vec2(r * std::cos(phi), r * std::sin(phi));
        }
        a = rasterise([&](Vec2 p) { return inside(v, p) ? 1.0f : 0.0f; });
    } else {
        return std::nullopt;
    }
    normalise(a);
    return a;
}

std::optional<scene::ApertureImage> aperture_from_image(const Image& image) {
    scene::ApertureImage a;
    a.width = image.width;
    a.height = image.height;
    a.values.resize(size_t(image.width) * size_t(image.height));
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            a.values[size_t(y) * size_t(image.width) + size_t(x)] =
                std::max(0.0f, image.at(x, image.height - 1 - y).average());
    if (!normalise(a)) return std::nullopt;
    return a;
}

}  // namespace phos::io::pbrt
