// Tests of the 20-byte photon record: RGBE power error bounds, octahedral direction/normal angular
// error bounds, and that the packed fields do not disturb one another.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/rng.h"
#include "photon/octahedral_avx2.h"
#include "photon/photon.h"

namespace phos::photon {
namespace {

Vec3 uniform_sphere(Vec2 u) {
    const float z = 1.0f - 2.0f * u.x;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

float angle_degrees(Vec3 a, Vec3 b) {
    // atan2 form: accurate for tiny angles, unlike acos of the dot product.
    return std::atan2(length(cross(a, b)), dot(a, b)) * 180.0f / kPi;
}

TEST(PhotonRecord, IsTwentyBytes) { EXPECT_EQ(sizeof(Photon), 20u); }

TEST(Rgbe, ErrorBoundOverWideRange) {
    Sampler rng(7);
    double sum_signed = 0;
    float worst_max_channel = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        // Max channel anywhere in 2^-100..2^100, the others up to 2^12 times smaller (or zero).
        const float base = std::ldexp(1.0f + rng.next(), int(rng.next_index(200)) - 100);
        Rgb c(base, base * std::ldexp(rng.next(), -int(rng.next_index(12))),
              rng.next() < 0.1f ? 0.0f : base * rng.next());
        if (i % 3 == 1) std::swap(c.r, c.g);
        if (i % 3 == 2) std::swap(c.r, c.b);
        const float m = c.max();
        const Rgb d = decode_rgbe(encode_rgbe(c));
        for (int ch = 0; ch < 3; ++ch) {
            ASSERT_LE(std::fabs(d[ch] - c[ch]), kRgbeMaxRelativeError * m) << i << " ch " << ch;
        }
        const float rel = std::fabs(d.max() - m) / m;
        worst_max_channel = std::max(worst_max_channel, rel);
        sum_signed += (d.max() - m) / m;
    }
    EXPECT_LE(worst_max_channel, kRgbeMaxRelativeError);
    // Rounding, not truncation: no systematic darkening (truncation would average about -2^-9).
    EXPECT_LT(std::fabs(sum_signed / n), 2e-4);
}

TEST(Rgbe, ExactValuesAndCarry) {
    for (float v : {1.0f, 0.5f, 0.75f, 3.0f, 0.125f, 0x1.8p-100f, 0x1.fep+100f}) {
        EXPECT_EQ(decode_rgbe(encode_rgbe(Rgb(v))), Rgb(v));
    }
    EXPECT_EQ(decode_rgbe(encode_rgbe(Rgb(1.0f, 0.5f, 0.25f))), Rgb(1.0f, 0.5f, 0.25f));
    // 255.75/256 rounds up to 256/256: the exponent must carry, decoding to exactly 1.
    const Rgb d = decode_rgbe(encode_rgbe(Rgb(255.75f / 256.0f, 0.1f, 0.0f)));
    EXPECT_EQ(d.r, 1.0f);
    EXPECT_NEAR(d.g, 0.1f, 1.0f / 512.0f);
    EXPECT_EQ(d.b, 0.0f);
}

TEST(Rgbe, DegenerateInputs) {
    EXPECT_EQ(encode_rgbe(Rgb(0.0f)), 0u);
    EXPECT_EQ(decode_rgbe(0u), Rgb(0.0f));
    EXPECT_EQ(decode_rgbe(encode_rgbe(Rgb(-1.0f, 2.0f, NAN))), Rgb(0.0f, 2.0f, 0.0f));
    EXPECT_EQ(decode_rgbe(encode_rgbe(Rgb(-1.0f))), Rgb(0.0f));
    EXPECT_EQ(decode_rgbe(encode_rgbe(Rgb(1e-40f))), Rgb(0.0f));  // below the exponent range
    const Rgb big = decode_rgbe(encode_rgbe(Rgb(INFINITY, 1e38f, 1.0f)));
    EXPECT_TRUE(big.is_finite());
    EXPECT_GT(big.r, 1e38f);
    // Tiny but representable powers (deep bounces of a weak light) keep their precision.
    const Rgb tiny(3e-36f, 1e-36f, 2e-36f);
    const Rgb dt = decode_rgbe(encode_rgbe(tiny));
    EXPECT_NEAR(dt.r, tiny.r, tiny.r * kRgbeMaxRelativeError);
}

// The fast encoder must give the reference's word for every input: random powers over the whole
// exponent range (where it defers to the reference at the ends), mantissas that round up to the
// next exponent, ties, zeros, negatives, NaN and infinities.
TEST(Rgbe, FastEncoderGivesTheReferenceWords) {
    Sampler rng(31);
    int mismatches = 0;
    const auto check = [&](Rgb c) {
        if (encode_rgbe(c) != encode_rgbe_reference(c)) ++mismatches;
    };
    for (int i = 0; i < 1000000; ++i) {
        const float scale = std::ldexp(1.0f, int(rng.next_index(300)) - 150);
        check(Rgb(rng.next(), rng.next(), rng.next()) * scale);
        check(Rgb(rng.next(), 1e-3f * rng.next(), 0.0f) * scale);
        // Exactly representable mantissas and halfway points: k/2 * 2^j.
        const float half = float(rng.next_index(512)) * 0.5f * std::ldexp(1.0f, int(rng.next_index(40)) - 20);
        check(Rgb(half, half * 0.5f, 255.5f * std::ldexp(1.0f, int(rng.next_index(40)) - 20)));
    }
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    for (Rgb c : {Rgb(0.0f), Rgb(-1.0f, 2.0f, -0.0f), Rgb(nan, 1.0f, 0.5f), Rgb(inf, 1.0f, 0.0f), Rgb(3e38f),
                  Rgb(1e-40f), Rgb(0x1p-110f, 0x1p-120f, 0.0f), Rgb(0x1p114f, 1.0f, 0.0f),
                  Rgb(255.5f, 0.0f, 1.0f), Rgb(0.99999994f, 0.5f, 0.25f)})
        check(c);
    EXPECT_EQ(mismatches, 0);
}

// The four-lane rescale (scale_rgbe4, the photon tracer's division of every power by N) gives the
// scalar encode_rgbe(decode_rgbe(w) * s) in every lane: random words over the whole exponent range
// (black and tiny exponents among them, which send their group to the scalar path), words near a
// carry to the next exponent, and scales from 1e-9 to 1e3 (1 / N for any N, and more).
TEST(Rgbe, FourLaneRescaleGivesTheScalarWords) {
    Sampler rng(32);
    int mismatches = 0, vector_groups = 0;
    for (int i = 0; i < 400000; ++i) {
        const float s = std::ldexp(0.5f + rng.next(), int(rng.next_index(40)) - 30);
        uint32_t w[4], want[4];
        bool fast = true;
        for (int k = 0; k < 4; ++k) {
            const uint32_t bits = uint32_t(rng.next_bits());
            // Mostly exponents of everyday powers; sometimes any byte, or a mantissa of 255.
            const uint32_t eb = rng.next() < 0.9f ? 100 + (bits >> 24) % 60 : bits >> 24;
            w[k] = (bits & 0xffffffu) | (eb << 24);
            if (rng.next() < 0.2f) w[k] |= 0xffu;
            want[k] = encode_rgbe(decode_rgbe(w[k]) * s);
            fast = fast && eb >= 10;
        }
        vector_groups += fast;
        scale_rgbe4(w, s);
        for (int k = 0; k < 4; ++k) mismatches += w[k] != want[k];
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(vector_groups, 200000);  // most groups took the four-lane path
}

template <int Bits>
float worst_octahedral_error(int n, uint64_t seed) {
    Sampler rng(seed);
    float worst = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3 d = uniform_sphere(rng.next2());
        const Vec3 r = decode_octahedral<Bits>(encode_octahedral<Bits>(d));
        EXPECT_NEAR(length(r), 1.0f, 1e-5f);
        worst = std::max(worst, angle_degrees(d, r));
    }
    return worst;
}

TEST(Octahedral, DirectionErrorBound16Bit) {
    const float worst = worst_octahedral_error<8>(300000, 11);
    EXPECT_LE(worst, kDirectionMaxErrorDegrees);
    EXPECT_GT(worst, 0.2f);  // sanity: the bound is not vacuous (we really quantise to 8+8 bits)
    RecordProperty("worst_degrees", std::to_string(worst));
}

TEST(Octahedral, NormalErrorBound14Bit) {
    const float worst = worst_octahedral_error<7>(300000, 12);
    EXPECT_LE(worst, kNormalMaxErrorDegrees);
    RecordProperty("worst_degrees", std::to_string(worst));
}

TEST(Octahedral, AxesAndSeamsAreExact) {
    const Vec3 axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (Vec3 a : axes) {
        EXPECT_EQ(decode_octahedral<8>(encode_octahedral<8>(a)), a);
        EXPECT_EQ(decode_octahedral<7>(encode_octahedral<7>(a)), a);
        EXPECT_EQ(decode_octahedral<8>(encode_octahedral<8>(a * 3.0f)), a);  // not normalised
    }
    // Lower hemisphere next to the fold lines.
    for (Vec3 d : {Vec3(0.7f, 0.0f, -0.7f), Vec3(0.0f, -0.6f, -0.8f), Vec3(-0.5f, 0.5f, -0.7071f)}) {
        d = normalize(d);
        EXPECT_LE(angle_degrees(d, decode_octahedral<8>(encode_octahedral<8>(d))), kDirectionMaxErrorDegrees);
    }
    // Degenerate input still yields a valid unit vector.
    EXPECT_NEAR(length(decode_octahedral<8>(encode_octahedral<8>(Vec3(0.0f)))), 1.0f, 1e-6f);
}

// The four-lane encoders (four lattice points of one direction, or four directions) and the
// eight-lane AVX2 one (eight directions) must give
// the reference's code for every input: random unit and
// non-unit vectors, the axes, the fold lines and the lattice's own directions (ties between
// neighbouring lattice points), for the direction (8) and normal (7) widths and a wide one.
template <int Bits>
void expect_same_codes_as_reference(uint64_t seed) {
    Sampler rng(seed);
    int mismatches = 0, compared8 = 0;
    // The batch encoders see each direction in a different lane, beside earlier directions; the
    // eight-lane AVX2 one (directions only) where this CPU has AVX2.
    const bool avx2 = Bits == 8 && __builtin_cpu_supports("avx2");
    Vec3 lanes[4] = {Vec3(0, 0, 1), Vec3(0.0f), Vec3(1, -2, 3), Vec3(-0.5f, 0.25f, -1)};
    Vec3 lanes8[8] = {Vec3(0, 0, 1),          Vec3(0.0f),     Vec3(1, -2, 3),         Vec3(-0.5f, 0.25f, -1),
                      Vec3(0.1f, 0.9f, 0.2f), Vec3(-1, 0, 0), Vec3(3e38f, 1, -3e38f), Vec3(0, -1e-30f, 0)};
    int lane = 0, lane8 = 0;
    const auto check = [&](Vec3 d) {
        const uint32_t want = encode_octahedral_reference<Bits>(d);
        if (encode_octahedral<Bits>(d) != want) ++mismatches;
        lanes[lane] = d;
        uint32_t codes[4];
        encode_octahedral4<Bits>(lanes, codes);
        if (codes[lane] != want) ++mismatches;
        lane = (lane + 1) & 3;
        if (avx2) {
            lanes8[lane8] = d;
            uint32_t codes8[8];
            encode_octahedral8_avx2(&lanes8[0].x, codes8);
            if (codes8[lane8] != want) ++mismatches;
            lane8 = (lane8 + 1) & 7;
            ++compared8;
        }
    };
    for (int i = 0; i < 400000; ++i) {
        const Vec3 d = uniform_sphere(rng.next2());
        check(d);
        check(d * (0.01f + 10.0f * rng.next()));
        // Directions on the lattice, and halfway between two lattice points.
        constexpr uint32_t mask = (1u << Bits) - 1;
        const uint32_t code = uint32_t(rng.next_bits()) & ((mask << Bits) | mask);
        const Vec3 a = decode_octahedral<Bits>(code), b = decode_octahedral<Bits>(code ^ 1u);
        check(a);
        check(a + b);
    }
    for (Vec3 a :
         {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1),
          Vec3(0.7f, 0.0f, -0.7f), Vec3(0.0f, -0.6f, -0.8f), Vec3(-0.0f, 0.0f, -1.0f), Vec3(0.0f),
          Vec3(1e-30f, -1e-30f, 1e-30f), Vec3(3e38f, 3e38f, -3e38f)})
        check(a);
    EXPECT_EQ(mismatches, 0) << Bits << "-bit codes";
    if (avx2) {
        EXPECT_GT(compared8, 1000000);
    }
}

TEST(Octahedral, LaneEncodersGiveTheReferenceCodes) {
    expect_same_codes_as_reference<8>(21);
    expect_same_codes_as_reference<7>(22);
    expect_same_codes_as_reference<12>(23);
}

TEST(PhotonRecord, ConstructAndDecodeFields) {
    const Vec3 p(0.25f, -3.5f, 1e3f);
    const Rgb power(2e-5f, 1e-5f, 5e-6f);
    const Vec3 wi = normalize(Vec3(0.3f, 0.9f, -0.2f));
    const Vec3 n = normalize(Vec3(-0.1f, 0.2f, 0.97f));
    Photon ph(p, power, wi * 2.0f, n);
    EXPECT_EQ(ph.position, p);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(ph.power()[c], power[c], power.max() * kRgbeMaxRelativeError);
    EXPECT_LE(angle_degrees(ph.wi(), wi), kDirectionMaxErrorDegrees);
    ASSERT_TRUE(ph.has_normal());
    EXPECT_LE(angle_degrees(ph.normal(), n), kNormalMaxErrorDegrees);

    // The split-axis bits share a 16-bit word with the normal: setting one keeps the other.
    const Vec3 before = ph.normal();
    for (int axis : {0, 1, 2, 3}) {
        ph.set_split_axis(axis);
        EXPECT_EQ(ph.split_axis(), axis);
        EXPECT_EQ(ph.normal(), before);
    }
    ph.set_normal(Vec3(0, -1, 0));
    EXPECT_EQ(ph.split_axis(), 3);
    EXPECT_EQ(ph.normal(), Vec3(0, -1, 0));
}

TEST(PhotonRecord, NoNormal) {
    Photon ph(Vec3(1, 2, 3), Rgb(1.0f), Vec3(0, 0, 1), Vec3(0.0f));
    EXPECT_FALSE(ph.has_normal());
    EXPECT_EQ(ph.normal(), Vec3(0.0f));
    ph.set_split_axis(2);
    EXPECT_FALSE(ph.has_normal());
    EXPECT_FALSE(Photon().has_normal());
    // No real normal ever encodes to the reserved code.
    Sampler rng(5);
    for (int i = 0; i < 100000; ++i) {
        EXPECT_NE(encode_octahedral<7>(uniform_sphere(rng.next2())), uint32_t(Photon::kNoNormalCode));
    }
}

}  // namespace
}  // namespace phos::photon
