// Texture evaluation (see texture_eval.h for what each kind gives and the image conventions).
#include "scene/texture_eval.h"

#include <cmath>

#include "scene/mip_map.h"
#include "scene/perlin_noise.h"
#include "scene/procedural_textures.h"

namespace phos::scene {

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

namespace {

Rgb texel(const scene::TextureImage& image, int x, int y, Texture::Wrap wrap) {
    const int xi = wrap_index(x, image.width, wrap), yi = wrap_index(y, image.height, wrap);
    if (xi < 0 || yi < 0) return Rgb(0.0f);
    return image.at(xi, yi);
}

// Depth-limited so that a (malformed) cycle of texture references cannot recurse forever.
Rgb eval(const scene::Scene& scene, int index, const TextureContext& ctx, int depth) {
    if (index < 0 || index >= int(scene.textures.size()) || depth > 32) return Rgb(1.0f);
    const Texture& t = scene.textures[size_t(index)];
    const auto sub = [&](int i) { return eval(scene, i, ctx, depth + 1); };
    // (1 - w) a + w b, evaluating only the textures with a non-zero weight (as pbrt does).
    const auto blend = [&](float w, int a, int b) {
        Rgb out(0.0f);
        if (w != 1) out += sub(a) * (1 - w);
        if (w != 0) out += sub(b) * w;
        return out;
    };
    switch (t.kind) {
        case Texture::Kind::Constant:
            return t.value;
        case Texture::Kind::Image: {
            if (!t.image || t.image->width <= 0 || t.image->height <= 0 ||
                t.image->texels.size() < size_t(t.image->width) * size_t(t.image->height))
                return t.value;
            const Vec2 st = map_2d(t, ctx);
            const float v = t.invert_v ? st.y : 1 - st.y;
            if (t.filter != Texture::Filter::Bilinear && t.mip_map && t.mip_map->levels() > 0) {
                // The footprint in image coordinates (y down unless invert_v).
                const St2Derivatives d = map_2d_derivatives(t, ctx);
                const float flip = t.invert_v ? 1.0f : -1.0f;
                return t.value * t.mip_map->filter(t.filter, Vec2(st.x, v), Vec2(d.dsdx, flip * d.dtdx),
                                                   Vec2(d.dsdy, flip * d.dtdy), t.max_anisotropy);
            }
            return t.value * lookup_bilinear(*t.image, st.x * float(t.image->width),
                                             v * float(t.image->height), t.wrap);
        }
        case Texture::Kind::Checkerboard: {
            const bool odd = t.dimension == 3 ? checker_odd(map_3d(t, ctx)) : checker_odd(map_2d(t, ctx));
            if (!odd) return t.tex1 >= 0 ? sub(t.tex1) : t.value;
            return t.tex2 >= 0 ? sub(t.tex2) : t.value2;
        }
        case Texture::Kind::Scale: {
            const Rgb b = t.tex2 >= 0 ? sub(t.tex2) : t.value;
            if (b.is_black()) return Rgb(0.0f);
            return (t.tex1 >= 0 ? sub(t.tex1) : Rgb(1.0f)) * b;
        }
        case Texture::Kind::Mix:
            return blend(t.amount >= 0 ? sub(t.amount).average() : t.amount_value, t.tex1, t.tex2);
        case Texture::Kind::DirectionMix:
            return blend(1 - std::fabs(dot(ctx.n, t.direction)), t.tex1, t.tex2);
        case Texture::Kind::Bilerp: {
            const Vec2 st = map_2d(t, ctx);
            const float s0 = 1 - st.x, t0 = 1 - st.y;
            return t.corners[0] * (s0 * t0) + t.corners[1] * (s0 * st.y) + t.corners[2] * (st.x * t0) +
                   t.corners[3] * (st.x * st.y);
        }
        case Texture::Kind::UV: {
            const Vec2 st = map_2d(t, ctx);
            return {st.x - std::floor(st.x), st.y - std::floor(st.y), 0.0f};
        }
        case Texture::Kind::Dots:
            return sub(inside_polka_dot(map_2d(t, ctx)) ? t.tex1 : t.tex2);
        case Texture::Kind::FBm:
            return Rgb(fbm(map_3d(t, ctx), t.roughness, t.octaves));
        case Texture::Kind::Wrinkled:
            return Rgb(turbulence(map_3d(t, ctx), t.roughness, t.octaves));
        case Texture::Kind::Windy:
            return Rgb(windy(map_3d(t, ctx)));
        case Texture::Kind::Marble:
            return marble(map_3d(t, ctx), t.marble_scale, t.variation, t.roughness, t.octaves);
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

Rgb eval_texture(const scene::Scene& scene, int texture, const TextureContext& ctx) {
    return eval(scene, texture, ctx, 0);
}

bool reads_footprint(const scene::Scene& scene) {
    for (const Texture& t : scene.textures)
        if (t.kind == Texture::Kind::Image && t.filter != Texture::Filter::Bilinear && t.mip_map) return true;
    return false;
}

Rgb eval_texture(const scene::Scene& scene, int texture, Vec2 uv) {
    TextureContext ctx;
    ctx.uv = uv;
    return eval(scene, texture, ctx, 0);
}

}  // namespace phos::scene
