// MIP map construction and filtered lookups (see mip_map.h).
#include "scene/mip_map.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "scene/texture_eval.h"

namespace phos::scene {
namespace {

bool is_power_of_2(int n) { return n > 0 && (n & (n - 1)) == 0; }
int round_up_power_of_2(int n) {
    int p = 1;
    while (p < n) p *= 2;
    return p;
}

// sin(pi x) / (pi x), 1 at 0.
float sinc(float x) {
    const float px = kPi * x;
    return 1 - px * px == 1 ? 1.0f : std::sin(px) / px;
}
// The Lanczos windowed sinc of radius `radius` and window `tau` (PBR 4th ed., sec. 8.8.4).
float windowed_sinc(float x, float radius, float tau) {
    if (std::fabs(x) > radius) return 0;
    return sinc(x) * sinc(x / tau);
}

// Four-tap resampling weights from old_res to new_res pixels (pbrt-v4's Image::ResampleWeights).
struct ResampleWeight {
    int first = 0;
    std::array<float, 4> w{};
};
std::vector<ResampleWeight> resample_weights(int old_res, int new_res) {
    std::vector<ResampleWeight> wt(static_cast<size_t>(new_res));
    const float radius = 2, tau = 2;
    for (int i = 0; i < new_res; ++i) {
        ResampleWeight& r = wt[size_t(i)];
        const float centre = (float(i) + 0.5f) * float(old_res) / float(new_res);
        r.first = int(std::floor((centre - radius) + 0.5f));
        for (int j = 0; j < 4; ++j)
            r.w[size_t(j)] = windowed_sinc(float(r.first + j) + 0.5f - centre, radius, tau);
        const float inv_sum = 1 / (r.w[0] + r.w[1] + r.w[2] + r.w[3]);
        for (float& w : r.w) w *= inv_sum;
    }
    return wt;
}

// The EWA filter's Gaussian exp(-alpha r2) - exp(-alpha) with alpha = 2 at r2 = i / 127.
constexpr int kWeightTableSize = 128;
const std::array<float, kWeightTableSize>& ewa_weights() {
    static const std::array<float, kWeightTableSize> table = [] {
        std::array<float, kWeightTableSize> t{};
        const float alpha = 2;
        for (int i = 0; i < kWeightTableSize; ++i) {
            const float r2 = float(i) / float(kWeightTableSize - 1);
            t[size_t(i)] = std::exp(-alpha * r2) - std::exp(-alpha);
        }
        return t;
    }();
    return table;
}

float length_squared2(Vec2 v) { return v.x * v.x + v.y * v.y; }

// Texel coordinates this far out lose all precision and would overflow int: such lookups are black.
constexpr float kMaxTexelCoordinate = 1e9f;

}  // namespace

TextureImage resample_up(const TextureImage& image, int new_width, int new_height, Texture::Wrap wrap) {
    const std::vector<ResampleWeight> xw = resample_weights(image.width, new_width);
    const std::vector<ResampleWeight> yw = resample_weights(image.height, new_height);
    // Along x: every source row to new_width texels (rows outside the image are wrapped below).
    std::vector<Rgb> rows(size_t(new_width) * size_t(image.height));
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < new_width; ++x) {
            const ResampleWeight& r = xw[size_t(x)];
            Rgb v[4];
            for (int j = 0; j < 4; ++j) {
                const int xi = wrap_index(r.first + j, image.width, wrap);
                v[j] = xi < 0 ? Rgb(0.0f) : image.at(xi, y);
            }
            rows[size_t(y) * size_t(new_width) + size_t(x)] =
                v[0] * r.w[0] + v[1] * r.w[1] + v[2] * r.w[2] + v[3] * r.w[3];
        }
    // Along y, clamping negative lobes' results to 0.
    TextureImage out;
    out.width = new_width;
    out.height = new_height;
    out.texels.resize(size_t(new_width) * size_t(new_height));
    for (int y = 0; y < new_height; ++y) {
        const ResampleWeight& r = yw[size_t(y)];
        int yi[4];
        for (int j = 0; j < 4; ++j) yi[j] = wrap_index(r.first + j, image.height, wrap);
        for (int x = 0; x < new_width; ++x) {
            Rgb v[4];
            for (int j = 0; j < 4; ++j)
                v[j] = yi[j] < 0 ? Rgb(0.0f) : rows[size_t(yi[j]) * size_t(new_width) + size_t(x)];
            const Rgb s = v[0] * r.w[0] + v[1] * r.w[1] + v[2] * r.w[2] + v[3] * r.w[3];
            out.texels[size_t(y) * size_t(new_width) + size_t(x)] =
                Rgb(std::max(0.0f, s.r), std::max(0.0f, s.g), std::max(0.0f, s.b));
        }
    }
    return out;
}

MipMap::MipMap(const TextureImage& image, Texture::Wrap wrap) : wrap_(wrap) {
    if (image.width <= 0 || image.height <= 0 ||
        image.texels.size() < size_t(image.width) * size_t(image.height))
        return;
    TextureImage level =
        is_power_of_2(image.width) && is_power_of_2(image.height)
            ? image
            : resample_up(image, round_up_power_of_2(image.width), round_up_power_of_2(image.height), wrap);
    while (true) {
        levels_.push_back(level);
        if (level.width == 1 && level.height == 1) break;
        TextureImage next;
        next.width = std::max(1, level.width / 2);
        next.height = std::max(1, level.height / 2);
        next.texels.resize(size_t(next.width) * size_t(next.height));
        // The 2x2 block at (2x, 2y); a side of 1 reads its single texel twice.
        const int dx = level.width == 1 ? 0 : 1, dy = level.height == 1 ? 0 : 1;
        for (int y = 0; y < next.height; ++y)
            for (int x = 0; x < next.width; ++x) {
                const int x0 = 2 * x, y0 = 2 * y;
                next.texels[size_t(y) * size_t(next.width) + size_t(x)] =
                    (level.at(x0, y0) + level.at(x0 + dx, y0) + level.at(x0, y0 + dy) +
                     level.at(x0 + dx, y0 + dy)) /
                    4.0f;
            }
        level = std::move(next);
    }
}

Rgb MipMap::texel(int level, int x, int y) const {
    const TextureImage& im = levels_[size_t(std::clamp(level, 0, levels() - 1))];
    const int xi = wrap_index(x, im.width, wrap_), yi = wrap_index(y, im.height, wrap_);
    if (xi < 0 || yi < 0) return Rgb(0.0f);
    return im.at(xi, yi);
}

Rgb MipMap::bilerp(int level, Vec2 st) const {
    const TextureImage& im = levels_[size_t(std::clamp(level, 0, levels() - 1))];
    return lookup_bilinear(im, st.x * float(im.width), st.y * float(im.height), wrap_);
}

Rgb MipMap::ewa(int level, Vec2 st, Vec2 dst0, Vec2 dst1) const {
    if (level >= levels()) return texel(levels() - 1, 0, 0);
    const TextureImage& im = levels_[size_t(level)];
    // To the level's texel units, texel centres at integers.
    const float w = float(im.width), h = float(im.height);
    const float s = st.x * w - 0.5f, t = st.y * h - 0.5f;
    dst0 = Vec2(dst0.x * w, dst0.y * h);
    dst1 = Vec2(dst1.x * w, dst1.y * h);
    // The implicit ellipse A s^2 + B s t + C t^2 < 1 whose conjugate axes are dst0 and dst1, each
    // grown by a texel (PBR 4th ed., eq. 10.13).
    float A = dst0.y * dst0.y + dst1.y * dst1.y + 1;
    float B = -2 * (dst0.x * dst0.y + dst1.x * dst1.y);
    float C = dst0.x * dst0.x + dst1.x * dst1.x + 1;
    const float inv_f = 1 / (A * C - B * B * 0.25f);
    A *= inv_f;
    B *= inv_f;
    C *= inv_f;
    // Its bounding box.
    const float det = -B * B + 4 * A * C, inv_det = 1 / det;
    const float u_sqrt = std::sqrt(std::max(0.0f, det * C)), v_sqrt = std::sqrt(std::max(0.0f, A * det));
    const float fs0 = std::ceil(s - 2 * inv_det * u_sqrt), fs1 = std::floor(s + 2 * inv_det * u_sqrt);
    const float ft0 = std::ceil(t - 2 * inv_det * v_sqrt), ft1 = std::floor(t + 2 * inv_det * v_sqrt);
    if (!(std::fabs(fs0) < kMaxTexelCoordinate && std::fabs(fs1) < kMaxTexelCoordinate &&
          std::fabs(ft0) < kMaxTexelCoordinate && std::fabs(ft1) < kMaxTexelCoordinate))
        return Rgb(0.0f);
    const int s0 = int(fs0), s1 = int(fs1), t0 = int(ft0), t1 = int(ft1);
    const std::array<float, kWeightTableSize>& weights = ewa_weights();
    Rgb sum(0.0f);
    float sum_weights = 0;
    for (int it = t0; it <= t1; ++it) {
        const float tt = float(it) - t;
        for (int is = s0; is <= s1; ++is) {
            const float ss = float(is) - s;
            const float r2 = A * ss * ss + B * ss * tt + C * tt * tt;
            if (r2 < 1) {
                const int index = std::min(int(r2 * float(kWeightTableSize)), kWeightTableSize - 1);
                const float weight = weights[size_t(std::max(index, 0))];
                sum += texel(level, is, it) * weight;
                sum_weights += weight;
            }
        }
    }
    if (!(sum_weights > 0)) return bilerp(level, st);
    return sum / sum_weights;
}

Rgb MipMap::filter(Texture::Filter f, Vec2 st, Vec2 dst0, Vec2 dst1, float max_anisotropy) const {
    if (levels_.empty()) return Rgb(0.0f);
    if (!std::isfinite(st.x) || !std::isfinite(st.y)) return Rgb(0.0f);
    const auto finite = [](Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y) ? v : Vec2(0, 0); };
    dst0 = finite(dst0);
    dst1 = finite(dst1);
    const int n = levels();
    if (f != Texture::Filter::Ewa) {
        const float width =
            2 * std::max({std::fabs(dst0.x), std::fabs(dst0.y), std::fabs(dst1.x), std::fabs(dst1.y)});
        const float l = float(n - 1) + std::log2(std::max(width, 1e-8f));
        if (l >= float(n - 1)) return texel(n - 1, 0, 0);
        const int i = std::max(0, int(std::floor(l)));
        switch (f) {
            case Texture::Filter::Point: {
                const TextureImage& im = levels_[size_t(i)];
                const float x = std::round(st.x * float(im.width) - 0.5f),
                            y = std::round(st.y * float(im.height) - 0.5f);
                if (!(std::fabs(x) < kMaxTexelCoordinate && std::fabs(y) < kMaxTexelCoordinate))
                    return Rgb(0.0f);
                return texel(i, int(x), int(y));
            }
            case Texture::Filter::Bilinear:
                return bilerp(i, st);
            default:  // Trilinear
                if (i == 0) return bilerp(0, st);
                {
                    const float d = l - float(i);
                    return bilerp(i, st) * (1 - d) + bilerp(i + 1, st) * d;
                }
        }
    }
    // EWA: dst0 the longer axis.
    if (length_squared2(dst0) < length_squared2(dst1)) std::swap(dst0, dst1);
    const float longer = std::sqrt(length_squared2(dst0));
    float shorter = std::sqrt(length_squared2(dst1));
    if (shorter * max_anisotropy < longer && shorter > 0) {
        const float scale = longer / (shorter * max_anisotropy);
        dst1 = dst1 * scale;
        shorter *= scale;
    }
    if (shorter == 0) return bilerp(0, st);
    const float lod = std::max(0.0f, float(n - 1) + std::log2(shorter));
    if (!(lod < float(n))) return texel(n - 1, 0, 0);
    const int il = int(std::floor(lod));
    const float d = lod - float(il);
    return ewa(il, st, dst0, dst1) * (1 - d) + ewa(il + 1, st, dst0, dst1) * d;
}

}  // namespace phos::scene
