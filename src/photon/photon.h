// The compact 20-byte photon record stored in photon maps, and the encodings it is built from:
// shared-exponent RGB power (RGBE with rounding) and octahedral unit vectors (16-bit incident
// direction, 14-bit surface normal), plus the 2-bit k-d tree split axis.
#pragma once

#include <immintrin.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/vec.h"
#include "photon/octahedral_lanes.h"

namespace phos::photon {

// ---- Shared-exponent RGB (Ward's RGBE layout: r, g, b mantissa bytes, then a biased exponent) ----
//
// We round instead of truncating, so for power c with max channel m every channel has
//   |decoded_i - c_i| <= half a mantissa step <= m / 255.5
// (2^-9 * 2^e with m >= 2^(e-1); m / 255.5 when rounding carried m into the next exponent): the
// largest channel has relative error <= 0.39 % and the smaller ones an absolute error of at most
// 0.39 % of the largest, without bias (Ward's truncating encoder: 0.78 %, always darker).
// Negative and NaN channels encode as 0; +inf and values beyond ~2^127 saturate; maxima below
// 2^-127 encode as black. The all-zero word is black.
inline constexpr float kRgbeMaxRelativeError = 1.0f / 255.0f;

inline uint32_t encode_rgbe_reference(Rgb c) {
    // NaN fails every comparison, so `!(x > 0)` maps NaN and negatives to 0.
    const float r = c.r > 0 ? std::fmin(c.r, 3e38f) : 0.0f;
    const float g = c.g > 0 ? std::fmin(c.g, 3e38f) : 0.0f;
    const float b = c.b > 0 ? std::fmin(c.b, 3e38f) : 0.0f;
    const float m = std::fmax(r, std::fmax(g, b));
    if (!(m > 0)) return 0;
    int e;
    std::frexp(m, &e);  // m = f * 2^e, f in [0.5, 1)
    if (e < -127) return 0;
    // Mantissas are c * 2^(8-e); the largest lands in [128, 256). Rounding may carry it to 256, in
    // which case the exponent grows by one (the rounded value 128 * 2^(e+1-8) is then exact).
    float scale = std::ldexp(1.0f, 8 - e);
    if (std::nearbyint(m * scale) >= 256.0f) {
        ++e;
        scale *= 0.5f;
    }
    if (e > 127) {  // saturate rather than wrap around
        e = 127;
        scale = std::ldexp(1.0f, 8 - e);
    }
    auto q = [&](float v) { return uint32_t(std::fmin(std::nearbyint(v * scale), 255.0f)); };
    return q(r) | (q(g) << 8) | (q(b) << 16) | (uint32_t(e + 128) << 24);
}

// Rounds each lane to the nearest whole number, ties to even, by adding and subtracting 2^23 (exact
// for 0 <= x < 2^23 in the default rounding mode; the scalar round_even below, lane by lane).
inline __m128 round_even_lanes(__m128 x) {
    const __m128 two23 = _mm_set1_ps(0x1p23f);
    return _mm_sub_ps(_mm_add_ps(x, two23), two23);
}

// The same words as encode_rgbe_reference (photon_record_test.cpp compares them), without its
// libm calls where the maximum channel is a normal float well inside the exponent range (every
// photon in practice): the exponent from the bits, powers of two built from bits, and round to
// nearest even by adding and subtracting 2^23 (exact for 0 <= x < 2^23 in the default rounding
// mode, which nearbyint also uses). The photon tracer encodes every stored photon twice.
// The three channels travel in the lanes of one SSE register (r, g, b, 0): each lane's clamp,
// product and rounding are the scalar operations, and the maximum of three non-negative,
// non-NaN values is the same whichever way it is taken.
inline uint32_t encode_rgbe(Rgb c) {
    const __m128 raw = _mm_setr_ps(c.r, c.g, c.b, 0.0f);
    // c > 0 ? min(c, 3e38) : 0 per channel (NaN fails the comparison).
    const __m128 v = _mm_and_ps(_mm_cmpgt_ps(raw, _mm_setzero_ps()), _mm_min_ps(raw, _mm_set1_ps(3e38f)));
    const __m128 m2 = _mm_max_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
    const float m = _mm_cvtss_f32(_mm_max_ps(m2, _mm_shuffle_ps(m2, m2, _MM_SHUFFLE(1, 0, 3, 2))));
    const int biased = int(std::bit_cast<uint32_t>(m) >> 23);  // m >= 0: no sign bit
    if (!(m > 0) || biased < 16 || biased > 240) return encode_rgbe_reference(c);
    int e = biased - 126;  // frexp's exponent for a normal float
    const auto pow2 = [](int k) { return std::bit_cast<float>(uint32_t(k + 127) << 23); };
    // (IEEE semantics, no -ffast-math: the compiler may not fold the sum and difference away.)
    const auto round_even = [](float x) { return (x + 0x1p23f) - 0x1p23f; };
    float scale = pow2(8 - e);
    if (round_even(m * scale) >= 256.0f) {
        ++e;
        scale *= 0.5f;
    }
    const __m128 x = round_even_lanes(_mm_mul_ps(v, _mm_set1_ps(scale)));
    // min(x, 255) as whole numbers, then the low bytes of the four lanes (the fourth is 0).
    const __m128i q = _mm_cvttps_epi32(_mm_min_ps(x, _mm_set1_ps(255.0f)));
    const __m128i bytes = _mm_packus_epi16(_mm_packs_epi32(q, q), _mm_setzero_si128());
    return uint32_t(_mm_cvtsi128_si32(bytes)) | (uint32_t(e + 128) << 24);
}

inline Rgb decode_rgbe(uint32_t w) {
    const int eb = int(w >> 24);
    if (eb == 0) return Rgb(0.0f);
    // 2^(e-8) with e = eb - 128, built from its bit pattern (normal floats need e-8 >= -126); the
    // few tinier exponents take ldexp.
    const int e2 = eb - 128 - 8;
    const float scale = e2 >= -126 ? std::bit_cast<float>(uint32_t(e2 + 127) << 23) : std::ldexp(1.0f, e2);
    return {float(w & 0xff) * scale, float((w >> 8) & 0xff) * scale, float((w >> 16) & 0xff) * scale};
}

// encode_rgbe(decode_rgbe(w[k]) * s) for four words at once, one per SSE lane, each lane doing the
// two scalar functions' IEEE operations in their order (photon_record_test.cpp compares them). A
// group with a word outside their fast paths (black, or an exponent near either end of the range)
// takes the scalar functions. The photon tracer rescales every stored photon's power by 1 / N so.
inline void scale_rgbe4(uint32_t w[4], float s) {
    const __m128i word = _mm_loadu_si128(reinterpret_cast<const __m128i*>(w));
    const __m128i eb = _mm_srli_epi32(word, 24), byte = _mm_set1_epi32(0xff);
    // decode_rgbe: 2^(eb - 136) from its bits (eb >= 10 keeps it a normal float), times the mantissas.
    const __m128 dscale = _mm_castsi128_ps(_mm_slli_epi32(_mm_sub_epi32(eb, _mm_set1_epi32(9)), 23));
    const __m128 sv = _mm_set1_ps(s), zero = _mm_setzero_ps(), big = _mm_set1_ps(3e38f);
    __m128 c[3];
    for (int k = 0; k < 3; ++k) {
        const __m128 m = _mm_cvtepi32_ps(_mm_and_si128(_mm_srli_epi32(word, 8 * k), byte));
        const __m128 v = _mm_mul_ps(_mm_mul_ps(m, dscale), sv);
        c[k] = _mm_and_ps(_mm_cmpgt_ps(v, zero), _mm_min_ps(v, big));  // encode_rgbe's clamp
    }
    const __m128 m = _mm_max_ps(c[0], _mm_max_ps(c[1], c[2]));
    const __m128i biased = _mm_srli_epi32(_mm_castps_si128(m), 23);
    // The fast paths: decoded exponent normal, and the maximum a normal float in [2^-111, 2^113].
    const __m128i out = _mm_or_si128(_mm_cmplt_epi32(eb, _mm_set1_epi32(10)),
                                     _mm_or_si128(_mm_cmplt_epi32(biased, _mm_set1_epi32(16)),
                                                  _mm_cmpgt_epi32(biased, _mm_set1_epi32(240))));
    if (_mm_movemask_epi8(out) != 0 || _mm_movemask_ps(_mm_cmpgt_ps(m, zero)) != 0xf) {
        for (int k = 0; k < 4; ++k) w[k] = encode_rgbe(decode_rgbe(w[k]) * s);
        return;
    }
    // e = biased - 126 and scale = 2^(8 - e); a maximum rounding up to 256 moves both one step.
    __m128i e = _mm_sub_epi32(biased, _mm_set1_epi32(126));
    __m128 scale = _mm_castsi128_ps(_mm_slli_epi32(_mm_sub_epi32(_mm_set1_epi32(261), biased), 23));
    const __m128 carry = _mm_cmpge_ps(round_even_lanes(_mm_mul_ps(m, scale)), _mm_set1_ps(256.0f));
    e = _mm_sub_epi32(e, _mm_castps_si128(carry));  // carry lanes are all ones: -(-1)
    scale = _mm_or_ps(_mm_and_ps(carry, _mm_mul_ps(scale, _mm_set1_ps(0.5f))), _mm_andnot_ps(carry, scale));
    __m128i result = _mm_slli_epi32(_mm_add_epi32(e, _mm_set1_epi32(128)), 24);
    for (int k = 0; k < 3; ++k) {
        const __m128 q = _mm_min_ps(round_even_lanes(_mm_mul_ps(c[k], scale)), _mm_set1_ps(255.0f));
        result = _mm_or_si128(result, _mm_slli_epi32(_mm_cvttps_epi32(q), 8 * k));
    }
    _mm_storeu_si128(reinterpret_cast<__m128i*>(w), result);
}

// ---- Octahedral unit vectors (Meyer et al. 2010; "precise" variant of Cigolle et al. 2014) ----
//
// Each of the two octahedral coordinates in [-1, 1] is quantised symmetrically to the integers
// -S..S (S = 2^(bits-1) - 1) stored as 0..2S, so 0 and +-1 are exact and the six axis directions
// (the normals of axis-aligned walls) encode without error. The code 2S+1 is left free; the
// photon uses it to mark "no normal". The encoder tries the four neighbouring lattice points and
// keeps the one that decodes closest to the input (measured bounds: see photon_record_test.cpp).

namespace detail {
inline Vec2 oct_wrap(Vec2 p) {
    return {(1.0f - std::fabs(p.y)) * (p.x >= 0 ? 1.0f : -1.0f),
            (1.0f - std::fabs(p.x)) * (p.y >= 0 ? 1.0f : -1.0f)};
}
template <int Bits>
inline Vec3 oct_decode_ints(int u, int v) {
    constexpr float inv = 1.0f / float((1 << (Bits - 1)) - 1);
    Vec2 f(float(u - ((1 << (Bits - 1)) - 1)) * inv, float(v - ((1 << (Bits - 1)) - 1)) * inv);
    const float z = 1.0f - std::fabs(f.x) - std::fabs(f.y);
    if (z < 0) f = oct_wrap(f);
    return normalize(Vec3(f.x, f.y, z));
}
}  // namespace detail

// Encodes unit vector `d` into 2*Bits bits (u in the low Bits, v in the next Bits). This is the
// reference form: one lattice point at a time. encode_octahedral below gives the same codes.
template <int Bits>
inline uint32_t encode_octahedral_reference(Vec3 d) {
    static_assert(Bits >= 2 && Bits <= 15);
    constexpr int S = (1 << (Bits - 1)) - 1;
    const float l1 = std::fabs(d.x) + std::fabs(d.y) + std::fabs(d.z);
    if (!(l1 > 0) || !std::isfinite(l1)) return uint32_t(S) | (uint32_t(S) << Bits);  // +z, any code will do
    const float inv = 1.0f / l1;
    Vec2 p(d.x * inv, d.y * inv);
    if (d.z < 0) p = detail::oct_wrap(p);
    const float fu = std::fmin(std::fmax(p.x, -1.0f), 1.0f) * S + S;
    const float fv = std::fmin(std::fmax(p.y, -1.0f), 1.0f) * S + S;
    const int u0 = int(std::floor(fu)), v0 = int(std::floor(fv));
    const Vec3 dn = normalize(d);
    int best_u = u0, best_v = v0;
    float best = -2.0f;
    for (int du = 0; du <= 1; ++du) {
        for (int dv = 0; dv <= 1; ++dv) {
            const int u = std::min(u0 + du, 2 * S), v = std::min(v0 + dv, 2 * S);
            const float c = dot(detail::oct_decode_ints<Bits>(u, v), dn);
            if (c > best) best = c, best_u = u, best_v = v;
        }
    }
    return uint32_t(best_u) | (uint32_t(best_v) << Bits);
}

// The same codes as encode_octahedral_reference, with the four lattice points decoded and compared
// in the four lanes of one SSE register (each lane does the reference's IEEE operations in the
// same order, so the results are identical bit for bit; photon_record_test.cpp checks it). This
// is on the photon tracer's hot path: every stored photon encodes its direction.
template <int Bits>
inline uint32_t encode_octahedral(Vec3 d) {
    static_assert(Bits >= 2 && Bits <= 15);
    constexpr int S = (1 << (Bits - 1)) - 1;
    const float l1 = std::fabs(d.x) + std::fabs(d.y) + std::fabs(d.z);
    if (!(l1 > 0) || !std::isfinite(l1)) return uint32_t(S) | (uint32_t(S) << Bits);
    const float inv = 1.0f / l1;
    Vec2 p(d.x * inv, d.y * inv);
    if (d.z < 0) p = detail::oct_wrap(p);
    // fmin/fmax of the reference: p is finite here, so plain comparisons agree with them.
    const float px = p.x < -1.0f ? -1.0f : (p.x > 1.0f ? 1.0f : p.x);
    const float py = p.y < -1.0f ? -1.0f : (p.y > 1.0f ? 1.0f : p.y);
    const float fu = px * S + S, fv = py * S + S;  // in [0, 2S]: the truncation below is floor
    const int u0 = int(fu), v0 = int(fv);
    const int u1 = std::min(u0 + 1, 2 * S), v1 = std::min(v0 + 1, 2 * S);
    const Vec3 dn = normalize(d);
    // Lanes in the reference's order (du, dv) = (0,0), (0,1), (1,0), (1,1); _mm_set_ps lists lane 3 first.
    constexpr float kInv = 1.0f / float(S);
    const __m128 sign_mask = _mm_set1_ps(-0.0f), one = _mm_set1_ps(1.0f);
    const __m128 fx =
        _mm_mul_ps(_mm_set_ps(float(u1 - S), float(u1 - S), float(u0 - S), float(u0 - S)), _mm_set1_ps(kInv));
    const __m128 fy =
        _mm_mul_ps(_mm_set_ps(float(v1 - S), float(v0 - S), float(v1 - S), float(v0 - S)), _mm_set1_ps(kInv));
    const __m128 ax = _mm_andnot_ps(sign_mask, fx), ay = _mm_andnot_ps(sign_mask, fy);
    const __m128 z = _mm_sub_ps(_mm_sub_ps(one, ax), ay);
    // oct_wrap where z < 0: x' = (1 - |y|) sign(x), y' = (1 - |x|) sign(y), sign(0) = +1.
    const __m128 wrap = _mm_cmplt_ps(z, _mm_setzero_ps());
    const __m128 neg_x = _mm_andnot_ps(_mm_cmpge_ps(fx, _mm_setzero_ps()), sign_mask);
    const __m128 neg_y = _mm_andnot_ps(_mm_cmpge_ps(fy, _mm_setzero_ps()), sign_mask);
    const __m128 wx = _mm_xor_ps(_mm_sub_ps(one, ay), neg_x), wy = _mm_xor_ps(_mm_sub_ps(one, ax), neg_y);
    const __m128 x = _mm_or_ps(_mm_and_ps(wrap, wx), _mm_andnot_ps(wrap, fx));
    const __m128 y = _mm_or_ps(_mm_and_ps(wrap, wy), _mm_andnot_ps(wrap, fy));
    const __m128 len =
        _mm_sqrt_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y)), _mm_mul_ps(z, z)));
    const __m128 c = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_div_ps(x, len), _mm_set1_ps(dn.x)),
                                           _mm_mul_ps(_mm_div_ps(y, len), _mm_set1_ps(dn.y))),
                                _mm_mul_ps(_mm_div_ps(z, len), _mm_set1_ps(dn.z)));
    alignas(16) float cs[4];
    _mm_store_ps(cs, c);
    // The first strictly largest lane wins, as in the reference (which keeps (u0, v0) if none
    // beats its start, best = -2).
    int k = 0;
    float best = -2.0f;
    for (int i = 0; i < 4; ++i)
        if (cs[i] > best) best = cs[i], k = i;
    const int u = k >= 2 ? u1 : u0, v = (k & 1) ? v1 : v0;
    return uint32_t(u) | (uint32_t(v) << Bits);
}

namespace detail {
// The lanes of SSE (every x86-64 CPU) for encode_octahedral_lanes (octahedral_lanes.h).
struct SseLanes {
    using F = __m128;
    using I = __m128i;
    static F load_strided(const float* p, int stride) {
        return _mm_setr_ps(p[0], p[stride], p[2 * stride], p[3 * stride]);
    }
    static F set1(float v) { return _mm_set1_ps(v); }
    static F add(F a, F b) { return _mm_add_ps(a, b); }
    static F sub(F a, F b) { return _mm_sub_ps(a, b); }
    static F mul(F a, F b) { return _mm_mul_ps(a, b); }
    static F div(F a, F b) { return _mm_div_ps(a, b); }
    static F sqrt(F a) { return _mm_sqrt_ps(a); }
    static F min(F a, F b) { return _mm_min_ps(a, b); }
    static F max(F a, F b) { return _mm_max_ps(a, b); }
    static F and_(F a, F b) { return _mm_and_ps(a, b); }
    static F or_(F a, F b) { return _mm_or_ps(a, b); }
    static F andnot(F a, F b) { return _mm_andnot_ps(a, b); }
    static F xor_(F a, F b) { return _mm_xor_ps(a, b); }
    static F cmplt(F a, F b) { return _mm_cmplt_ps(a, b); }
    static F cmpgt(F a, F b) { return _mm_cmpgt_ps(a, b); }
    static F cmpge(F a, F b) { return _mm_cmpge_ps(a, b); }
    static I cvtt(F a) { return _mm_cvttps_epi32(a); }
    static F cvt(I a) { return _mm_cvtepi32_ps(a); }
    static I as_i(F a) { return _mm_castps_si128(a); }
    static I set1_i(int v) { return _mm_set1_epi32(v); }
    static I add_i(I a, I b) { return _mm_add_epi32(a, b); }
    static I sub_i(I a, I b) { return _mm_sub_epi32(a, b); }
    static I cmpgt_i(I a, I b) { return _mm_cmpgt_epi32(a, b); }
    static I and_i(I a, I b) { return _mm_and_si128(a, b); }
    static I or_i(I a, I b) { return _mm_or_si128(a, b); }
    static I andnot_i(I a, I b) { return _mm_andnot_si128(a, b); }
    static I shl_i(I a, int n) { return _mm_slli_epi32(a, n); }
    static void store_u32(uint32_t* out, I a) { _mm_storeu_si128(reinterpret_cast<__m128i*>(out), a); }
};
}  // namespace detail

// The same codes as encode_octahedral_reference for four directions at once, one per SSE lane
// (encode_octahedral_lanes: each lane does the reference's IEEE operations in its order, the four
// lattice points one after another): no scalar chain from the input to the code, so consecutive
// calls overlap. The photon tracer encodes each batch's stored directions this way, or eight at a
// time with AVX2 (octahedral_avx2.h) where the CPU has it.
template <int Bits>
inline void encode_octahedral4(const Vec3 d[4], uint32_t codes[4]) {
    static_assert(sizeof(Vec3) == 3 * sizeof(float));
    detail::encode_octahedral_lanes<Bits, detail::SseLanes>(&d[0].x, codes);
}

template <int Bits>
inline Vec3 decode_octahedral(uint32_t code) {
    constexpr uint32_t mask = (1u << Bits) - 1;
    return detail::oct_decode_ints<Bits>(int(code & mask), int((code >> Bits) & mask));
}

// Worst angle between a unit vector and its decoded code, measured over 2e7 random directions
// (16 bits: 0.636 deg, 14 bits: 1.283 deg), with a small margin; asserted by the tests.
inline constexpr float kDirectionMaxErrorDegrees = 0.65f;
inline constexpr float kNormalMaxErrorDegrees = 1.3f;

// ---- The photon record ----
//
//   bytes  0..11  position (3 x float)
//   bytes 12..15  power, RGBE
//   bytes 16..17  wi: direction towards where the photon came from, octahedral 8+8 bits
//   bytes 18..19  bits 0-1: k-d split axis (0/1/2, 3 = not a split node, set by the tree);
//                 bits 2-15: surface normal, octahedral 7+7 bits (u code 127 = no normal, for
//                 photons stored off surfaces, e.g. in media)
// The normal lets a density estimate reject photons from a differently oriented surface (thin
// walls, corners) as Mitsuba's 28-byte photon does, in Jensen's 20 bytes.
struct Photon {
    Vec3 position;
    uint32_t power_rgbe = 0;
    uint16_t wi_code = 0;
    uint16_t normal_axis = kNoNormalCode << 2 | 3;

    static constexpr uint16_t kNoNormalCode = 127;  // u = 127, v = 0 (never produced by the encoder)

    Photon() = default;
    // `power` is the photon's flux (W, per channel); `wi` points away from the surface towards the
    // photon's origin; `normal` is the surface normal (a zero vector stores "no normal"). Both
    // directions need not be normalised.
    Photon(Vec3 position_, Rgb power, Vec3 wi, Vec3 normal)
        : position(position_), power_rgbe(encode_rgbe(power)), wi_code(uint16_t(encode_octahedral<8>(wi))) {
        set_normal(normal);
    }

    Rgb power() const { return decode_rgbe(power_rgbe); }
    Vec3 wi() const { return decode_octahedral<8>(wi_code); }
    bool has_normal() const { return (normal_axis >> 2) != kNoNormalCode; }
    // Decoded normal; (0,0,0) when none was stored.
    Vec3 normal() const { return has_normal() ? decode_octahedral<7>(normal_axis >> 2) : Vec3(0.0f); }
    int split_axis() const { return normal_axis & 3; }

    void set_power(Rgb p) { power_rgbe = encode_rgbe(p); }
    void set_normal(Vec3 n) {
        const uint32_t code = length_squared(n) > 0 ? encode_octahedral<7>(n) : kNoNormalCode;
        normal_axis = uint16_t((code << 2) | (normal_axis & 3u));
    }
    void set_split_axis(int axis) { normal_axis = uint16_t((normal_axis & ~3u) | (uint32_t(axis) & 3u)); }
};

static_assert(sizeof(Photon) == 20, "the photon record must stay at 20 bytes");
static_assert(alignof(Photon) == 4);

}  // namespace phos::photon
