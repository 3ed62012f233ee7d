// The compact 24-byte photon record stored in photon maps, and the encodings it is built from:
// shared-exponent power at the photon's four wavelengths (RGBE with rounding, over four channels),
// the wavelengths' 16-bit code, octahedral unit vectors (16-bit incident direction, 14-bit surface
// normal), plus the 2-bit k-d tree split axis.
#pragma once

#include <immintrin.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/vec.h"
#include "photon/octahedral_lanes.h"
#include "spectrum/color.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::photon {

// ---- Shared-exponent spectral power (Ward's RGBE generalised to the photon's four wavelengths:
// four mantissa bytes, then a biased exponent byte) ----
//
// We round instead of truncating, so for power c with largest channel m every channel has
//   |decoded_i - c_i| <= half a mantissa step <= m / 255.5
// (2^-9 * 2^e with m >= 2^(e-1); m / 255.5 when rounding carried m into the next exponent): the
// largest channel has relative error <= 0.39 % and the smaller ones an absolute error of at most
// 0.39 % of the largest, without bias (Ward's truncating encoder: 0.78 %, always darker).
// Negative and NaN channels encode as 0; +inf and values beyond ~2^127 saturate; maxima below
// 2^-127 encode as black. Exponent byte 0 is black.
inline constexpr float kPowerMaxRelativeError = 1.0f / 255.0f;

struct PowerCode {
    uint32_t mantissas = 0;  // channel i in byte i
    uint8_t exponent = 0;    // e + 128; 0 = black
    bool operator==(const PowerCode&) const = default;
};

inline PowerCode encode_power_reference(const Spectrum& c) {
    float v[4];
    float m = 0;
    for (int i = 0; i < 4; ++i) {
        // NaN fails every comparison, so `!(x > 0)` maps NaN and negatives to 0.
        v[i] = c[i] > 0 ? std::fmin(c[i], 3e38f) : 0.0f;
        m = std::fmax(m, v[i]);
    }
    if (!(m > 0)) return {};
    int e;
    std::frexp(m, &e);  // m = f * 2^e, f in [0.5, 1)
    if (e < -127) return {};
    // Mantissas are c * 2^(8-e); the largest lands in [128, 256). Rounding may carry it to 256, in
    // which case the exponent grows by one (the rounded value 128 * 2^(e+1-8) is then exact). The
    // scale is a double: 2^(8-e) overflows a float for the smallest exponents.
    double scale = std::ldexp(1.0, 8 - e);
    if (std::nearbyint(double(m) * scale) >= 256.0) {
        ++e;
        scale *= 0.5;
    }
    if (e > 127) {  // saturate rather than wrap around
        e = 127;
        scale = std::ldexp(1.0, 8 - e);
    }
    PowerCode code;
    for (int i = 0; i < 4; ++i)
        code.mantissas |= uint32_t(std::fmin(std::nearbyint(double(v[i]) * scale), 255.0)) << (8 * i);
    code.exponent = uint8_t(e + 128);
    return code;
}

// Rounds each lane to the nearest whole number, ties to even, by adding and subtracting 2^23 (exact
// for 0 <= x < 2^23 in the default rounding mode; the scalar round_even below, lane by lane).
inline __m128 round_even_lanes(__m128 x) {
    const __m128 two23 = _mm_set1_ps(0x1p23f);
    return _mm_sub_ps(_mm_add_ps(x, two23), two23);
}

// The same codes as encode_power_reference (photon_record_test.cpp compares them), without its
// libm calls where the largest channel is a normal float well inside the exponent range (every
// photon in practice): the exponent from the bits, powers of two built from bits, and round to
// nearest even by adding and subtracting 2^23 (exact for 0 <= x < 2^23 in the default rounding
// mode, which nearbyint also uses). The four channels travel in the lanes of one SSE register:
// each lane's clamp, product and rounding are the scalar operations, and the maximum of four
// non-negative, non-NaN values is the same whichever way it is taken.
inline PowerCode encode_power(const Spectrum& c) {
    static_assert(spectrum::kSpectrumSamples == 4);
    const __m128 raw = _mm_loadu_ps(c.v.data());
    // c > 0 ? min(c, 3e38) : 0 per channel (NaN fails the comparison).
    const __m128 v = _mm_and_ps(_mm_cmpgt_ps(raw, _mm_setzero_ps()), _mm_min_ps(raw, _mm_set1_ps(3e38f)));
    const __m128 m2 = _mm_max_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
    const float m = _mm_cvtss_f32(_mm_max_ps(m2, _mm_shuffle_ps(m2, m2, _MM_SHUFFLE(1, 0, 3, 2))));
    const int biased = int(std::bit_cast<uint32_t>(m) >> 23);  // m >= 0: no sign bit
    if (!(m > 0) || biased < 16 || biased > 240) return encode_power_reference(c);
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
    // min(x, 255) as whole numbers, then the low bytes of the four lanes.
    const __m128i q = _mm_cvttps_epi32(_mm_min_ps(x, _mm_set1_ps(255.0f)));
    const __m128i bytes = _mm_packus_epi16(_mm_packs_epi32(q, q), _mm_setzero_si128());
    return {uint32_t(_mm_cvtsi128_si32(bytes)), uint8_t(e + 128)};
}

inline Spectrum decode_power(PowerCode code) {
    Spectrum s;
    if (code.exponent == 0) return s;
    // 2^(e-8) with e = exponent - 128, built from its bit pattern (normal floats need e-8 >= -126);
    // the few tinier exponents take ldexp.
    const int e2 = int(code.exponent) - 128 - 8;
    const float scale = e2 >= -126 ? std::bit_cast<float>(uint32_t(e2 + 127) << 23) : std::ldexp(1.0f, e2);
    for (int i = 0; i < 4; ++i) s[i] = float((code.mantissas >> (8 * i)) & 0xff) * scale;
    return s;
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
//   bytes 12..15  power: the four wavelengths' mantissas (PowerCode)
//   byte  16      power: the shared exponent
//   byte  17      bit 0: the photon's secondary wavelengths were terminated (it crossed a
//                 dispersive interface; only the hero carries power)
//   bytes 18..19  the photon's wavelengths: the 16-bit code of its hero (SampledWavelengths::from_code)
//   bytes 20..21  wi: direction towards where the photon came from, octahedral 8+8 bits
//   bytes 22..23  bits 0-1: k-d split axis (0/1/2, 3 = not a split node, set by the tree);
//                 bits 2-15: surface normal, octahedral 7+7 bits (u code 127 = no normal, for
//                 photons stored off surfaces, e.g. in media)
// The normal lets a density estimate reject photons from a differently oriented surface (thin
// walls, corners) as Mitsuba's 28-byte photon does; the wavelengths let an estimate evaluate the
// BSDF where the photon's power is, at the cost of 4 bytes over Jensen's 20.
struct Photon {
    Vec3 position;
    uint32_t power_mantissas = 0;
    uint8_t power_exponent = 0;
    uint8_t flags = 0;
    uint16_t lambda_code = 0;
    uint16_t wi_code = 0;
    uint16_t normal_axis = kNoNormalCode << 2 | 3;

    static constexpr uint16_t kNoNormalCode = 127;  // u = 127, v = 0 (never produced by the encoder)
    static constexpr uint8_t kSecondaryTerminated = 1;

    Photon() = default;
    // `power` is the photon's flux (W) at its wavelengths `lambda`; `wi` points away from the
    // surface towards the photon's origin; `normal` is the surface normal (a zero vector stores "no
    // normal"). Both directions need not be normalised.
    Photon(Vec3 position_, const Spectrum& power, const Wavelengths& lambda, Vec3 wi, Vec3 normal)
        : position(position_), wi_code(uint16_t(encode_octahedral<8>(wi))) {
        set_power(power);
        set_wavelengths(lambda);
        set_normal(normal);
    }

    Spectrum power() const { return decode_power({power_mantissas, power_exponent}); }
    Wavelengths wavelengths() const {
        return Wavelengths::from_code(lambda_code, (flags & kSecondaryTerminated) != 0);
    }
    // The power's linear sRGB (what estimates add when nothing at the photon depends on wavelength).
    Rgb colour() const { return spectrum::to_srgb(power(), wavelengths()); }
    Vec3 wi() const { return decode_octahedral<8>(wi_code); }
    bool has_normal() const { return (normal_axis >> 2) != kNoNormalCode; }
    // Decoded normal; (0,0,0) when none was stored.
    Vec3 normal() const { return has_normal() ? decode_octahedral<7>(normal_axis >> 2) : Vec3(0.0f); }
    int split_axis() const { return normal_axis & 3; }

    void set_power(const Spectrum& p) {
        const PowerCode c = encode_power(p);
        power_mantissas = c.mantissas;
        power_exponent = c.exponent;
    }
    void set_wavelengths(const Wavelengths& lambda) {
        lambda_code = lambda.code();
        flags = uint8_t((flags & ~kSecondaryTerminated) |
                        (lambda.secondary_terminated() ? kSecondaryTerminated : 0));
    }
    void set_normal(Vec3 n) {
        const uint32_t code = length_squared(n) > 0 ? encode_octahedral<7>(n) : kNoNormalCode;
        normal_axis = uint16_t((code << 2) | (normal_axis & 3u));
    }
    void set_split_axis(int axis) { normal_axis = uint16_t((normal_axis & ~3u) | (uint32_t(axis) & 3u)); }
};

static_assert(sizeof(Photon) == 24, "the photon record must stay at 24 bytes");

// Caches that keep a colour per point in photon records (the irradiance cache) hold its linear
// sRGB in the first three power channels, and the channels' signs in flags bits 1-3 (a colour
// estimated from few wavelengths may have a negative channel).
inline void set_stored_colour(Photon& ph, Rgb c) {
    Spectrum s;
    uint8_t signs = 0;
    for (int k = 0; k < 3; ++k) {
        s[k] = std::fabs(c[k]);
        if (c[k] < 0) signs = uint8_t(signs | (2u << k));
    }
    ph.set_power(s);
    ph.flags = uint8_t((ph.flags & ~0x0eu) | signs);
}
inline Rgb stored_colour(const Photon& ph) {
    const Spectrum s = ph.power();
    Rgb c;
    for (int k = 0; k < 3; ++k) c[k] = (ph.flags & (2u << k)) ? -s[k] : s[k];
    return c;
}
static_assert(alignof(Photon) == 4);

}  // namespace phos::photon
