// Texture evaluation (see texture_eval.h for the uv and wrap conventions).
#include "scene/texture_eval.h"

#include <cmath>

namespace phos::scene {
namespace {

// Maps an integer texel index to one inside [0, n) per wrap mode; -1 means "black".
int wrap_index(int i, int n, Texture::Wrap wrap) {
    if (i >= 0 && i < n) return i;
    switch (wrap) {
        case Texture::Wrap::Repeat: {
            const int m = i % n;
            return m < 0 ? m + n : m;
        }
        case Texture::Wrap::Clamp:
            return i < 0 ? 0 : n - 1;
        case Texture::Wrap::Black:
            return -1;
    }
    return -1;
}

Rgb texel(const scene::TextureImage& image, int x, int y, Texture::Wrap wrap) {
    const int xi = wrap_index(x, image.width, wrap), yi = wrap_index(y, image.height, wrap);
    if (xi < 0 || yi < 0) return Rgb(0.0f);
    return image.at(xi, yi);
}

Vec2 map_uv(const Texture& t, Vec2 uv) {
    return {uv.x * t.u_scale + t.u_offset, uv.y * t.v_scale + t.v_offset};
}

// Depth-limited so that a (malformed) cycle of checkerboard/scale references cannot recurse
// forever.
Rgb eval(const scene::Scene& scene, int index, Vec2 uv, int depth) {
    if (index < 0 || index >= int(scene.textures.size()) || depth > 32) return Rgb(1.0f);
    const Texture& t = scene.textures[size_t(index)];
    switch (t.kind) {
        case Texture::Kind::Constant:
            return t.value;
        case Texture::Kind::Image: {
            if (!t.image || t.image->width <= 0 || t.image->height <= 0 ||
                t.image->texels.size() < size_t(t.image->width) * size_t(t.image->height))
                return t.value;
            const Vec2 st = map_uv(t, uv);
            const float v = t.invert_v ? st.y : 1 - st.y;
            return t.value * lookup_bilinear(*t.image, st.x * float(t.image->width),
                                             v * float(t.image->height), t.wrap);
        }
        case Texture::Kind::Checkerboard: {
            const Vec2 st = map_uv(t, uv);
            const long parity = long(std::floor(st.x)) + long(std::floor(st.y));
            if (parity % 2 == 0) return t.tex1 >= 0 ? eval(scene, t.tex1, uv, depth + 1) : t.value;
            return t.tex2 >= 0 ? eval(scene, t.tex2, uv, depth + 1) : t.value2;
        }
        case Texture::Kind::Scale: {
            const Rgb a = t.tex1 >= 0 ? eval(scene, t.tex1, uv, depth + 1) : Rgb(1.0f);
            const Rgb b = t.tex2 >= 0 ? eval(scene, t.tex2, uv, depth + 1) : t.value;
            return a * b;
        }
    }
    return Rgb(1.0f);
}

}  // namespace

Rgb lookup_bilinear(const scene::TextureImage& image, float x, float y, Texture::Wrap wrap) {
    if (!std::isfinite(x) || !std::isfinite(y)) return Rgb(0.0f);
    // Shift so that integer positions are texel centres.
    const float fx = x - 0.5f, fy = y - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float tx = fx - x0f, ty = fy - y0f;
    // Keep the integer conversion in range for absurd uv values (Repeat wraps them anyway).
    const auto to_int = [](float f) { return int(std::fmod(f, 1073741824.0f)); };
    const int x0 = to_int(x0f), y0 = to_int(y0f);
    return texel(image, x0, y0, wrap) * ((1 - tx) * (1 - ty)) +
           texel(image, x0 + 1, y0, wrap) * (tx * (1 - ty)) +
           texel(image, x0, y0 + 1, wrap) * ((1 - tx) * ty) + texel(image, x0 + 1, y0 + 1, wrap) * (tx * ty);
}

Rgb eval_texture(const scene::Scene& scene, int texture, Vec2 uv) { return eval(scene, texture, uv, 0); }

}  // namespace phos::scene
