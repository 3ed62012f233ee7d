// Counter-based random numbers: every value is a pure function of (seed, stream keys, counter), so
// results never depend on which thread drew them or in what order. A Sampler is keyed by what is
// being sampled (pixel and sample index, photon index and pass...) and draws dimension by dimension.
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace phos {

// A strong 64-bit mixer (the finaliser of SplitMix64 / MurmurHash3, Stafford's variant 13).
constexpr uint64_t mix64(uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

constexpr uint64_t hash_combine(uint64_t a, uint64_t b) {
    return mix64(a ^ (b + 0x9e3779b97f4a7c15ULL + (a << 6) + (a >> 2)));
}

// Converts 32 random bits to a float uniformly distributed in [0, 1).
constexpr float bits_to_unit_float(uint32_t bits) { return float(bits >> 8) * 0x1p-24f; }

class Sampler {
public:
    Sampler() = default;
    explicit Sampler(uint64_t seed, uint64_t key0 = 0, uint64_t key1 = 0, uint64_t key2 = 0)
        : key_(hash_combine(hash_combine(hash_combine(mix64(seed + 0x632be59bd9b4e019ULL), key0), key1),
                            key2)) {}

    // Next value in [0, 1).
    float next() { return bits_to_unit_float(uint32_t(next_bits() >> 32)); }
    Vec2 next2() {
        const uint64_t b = next_bits();
        return {bits_to_unit_float(uint32_t(b >> 32)), bits_to_unit_float(uint32_t(b))};
    }
    uint64_t next_bits() { return mix64(key_ + 0x9e3779b97f4a7c15ULL * ++counter_); }
    // Uniform integer in [0, n).
    uint32_t next_index(uint32_t n) { return uint32_t((uint64_t(uint32_t(next_bits() >> 32)) * n) >> 32); }

    uint64_t counter() const { return counter_; }

private:
    uint64_t key_ = 0;
    uint64_t counter_ = 0;
};

}  // namespace phos
