// Scrambled low-discrepancy points for progressive estimators: the (0,2)-sequence in base 2 with
// random digit scrambling, and an Owen-style shuffle of the sample index, so several 2D (or 1D)
// dimensions of one pixel can each be a stratified sequence over the samples without the
// dimensions being correlated ("padding", Kollig & Keller 2002; pbrt-v4's PaddedSobolSampler).
// Every aligned block of 2^k consecutive indices maps to an aligned block under the shuffle, and
// any aligned block of 2^k points of the (0,2)-sequence is a (0,k,2)-net: so the first 2^k
// samples of every dimension are stratified in each elementary interval of area 2^-k, and every
// prefix is evenly spread (a render stopped after any number of samples stays well stratified).
#pragma once

#include <cstdint>

#include "core/rng.h"
#include "core/vec.h"

namespace phos {

inline uint32_t reverse_bits32(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
}

namespace detail {
// Sobol's second dimension, y = C s over GF(2) with the columns v_0 = 2^31, v_j+1 = v_j ^ (v_j >> 1)
// (Pascal's matrix), tabulated per byte of s: four lookups instead of a loop over 32 bits.
struct Sobol2Table {
    uint32_t byte[4][256];
};
constexpr Sobol2Table make_sobol2_table() {
    Sobol2Table t{};
    uint32_t v[32] = {};
    v[0] = 0x80000000u;
    for (int j = 1; j < 32; ++j) v[j] = v[j - 1] ^ (v[j - 1] >> 1);
    for (int b = 0; b < 4; ++b)
        for (uint32_t x = 0; x < 256; ++x) {
            uint32_t y = 0;
            for (int j = 0; j < 8; ++j)
                if ((x >> j) & 1u) y ^= v[8 * b + j];
            t.byte[b][x] = y;
        }
    return t;
}
inline constexpr Sobol2Table kSobol2 = make_sobol2_table();
}  // namespace detail

// Van der Corput's radical inverse of s in base 2 (s's bits reversed), as 32 bits.
inline uint32_t radical_inverse_bits(uint32_t s) { return reverse_bits32(s); }

// Sobol's second dimension of point s, as 32 bits.
inline uint32_t sobol2_bits(uint32_t s) {
    const auto& t = detail::kSobol2.byte;
    return t[0][s & 255u] ^ t[1][(s >> 8) & 255u] ^ t[2][(s >> 16) & 255u] ^ t[3][s >> 24];
}

// Point s of the (0,2)-sequence in base 2 (van der Corput's radical inverse and Sobol's second
// dimension), XOR-scrambled by `scramble` (random digit scrambling keeps the (0,2) property and
// makes each point uniform in [0, 1)^2). Kocis & Whiten 1997.
inline Vec2 sobol02_point(uint32_t s, uint64_t scramble) {
    return {bits_to_unit_float(radical_inverse_bits(s) ^ uint32_t(scramble)),
            bits_to_unit_float(sobol2_bits(s) ^ uint32_t(scramble >> 32))};
}

// Van der Corput's sequence, XOR-scrambled: a stratified 1D sequence.
inline float van_der_corput(uint32_t s, uint32_t scramble) {
    return bits_to_unit_float(radical_inverse_bits(s) ^ scramble);
}

// A permutation of the sample indices keyed by `key` in which each bit of the result depends only
// on the bits of s at and above it: aligned blocks of 2^k indices map onto aligned blocks of 2^k.
// The bits are reversed so that a hash whose multiplications carry information from low to high
// bits (Laine & Karras 2011's nested uniform scramble, in Burley's 2020 form) flips each digit
// according to the more significant ones only.
inline uint32_t shuffle_index(uint32_t s, uint32_t key) {
    uint32_t x = reverse_bits32(s);
    x ^= x * 0x3d20adeau;
    x += key;
    x *= (key >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return reverse_bits32(x);
}

// Sample s of one padded 2D dimension: the (0,2)-sequence's point shuffle_index(s), scrambled.
// `key` (one per pixel and dimension, e.g. hash_combine of both) picks the shuffle and scramble.
inline Vec2 padded_point2(uint32_t s, uint64_t key) {
    const uint64_t h = mix64(key);
    return sobol02_point(shuffle_index(s, uint32_t(h)), mix64(h));
}

// Sample s of one padded 1D dimension (van der Corput's sequence, shuffled and scrambled).
inline float padded_point1(uint32_t s, uint64_t key) {
    const uint64_t h = mix64(key);
    return van_der_corput(shuffle_index(s, uint32_t(h)), uint32_t(h >> 32));
}

}  // namespace phos
