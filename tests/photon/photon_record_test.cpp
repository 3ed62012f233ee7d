// Tests of the 24-byte photon record: the shared-exponent power's error bounds, exact codes and
// degenerate inputs (and the fast encoder against the reference), the wavelengths' 16-bit code and
// terminated flag, octahedral direction/normal angular error bounds, and that the packed fields do
// not disturb one another.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/rng.h"
#include "photon/octahedral_avx2.h"
#include "photon/photon.h"
#include "spectrum/color.h"

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

Spectrum spectrum_of(float a, float b, float c, float d) {
    Spectrum s;
    s[0] = a, s[1] = b, s[2] = c, s[3] = d;
    return s;
}

Spectrum round_trip(const Spectrum& s) { return decode_power(encode_power(s)); }

TEST(PhotonRecord, IsTwentyFourBytes) { EXPECT_EQ(sizeof(Photon), 24u); }

TEST(SharedExponentPower, ErrorBoundOverWideRange) {
    Sampler rng(7);
    double sum_signed = 0;
    float worst_max_channel = 0;
    int exact_zeros = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        // Max channel anywhere in 2^-100..2^100, the others up to 2^12 times smaller (or zero), the
        // largest in each of the four channels in turn.
        const float base = std::ldexp(1.0f + rng.next(), int(rng.next_index(200)) - 100);
        Spectrum c = spectrum_of(base, base * std::ldexp(rng.next(), -int(rng.next_index(12))),
                                 rng.next() < 0.1f ? 0.0f : base * rng.next(), base * rng.next() * 1e-3f);
        std::swap(c[0], c[i % 4]);
        const float m = c.max();
        const Spectrum d = round_trip(c);
        for (int ch = 0; ch < 4; ++ch) {
            ASSERT_LE(std::fabs(d[ch] - c[ch]), kPowerMaxRelativeError * m) << i << " ch " << ch;
            if (c[ch] == 0) {
                ASSERT_EQ(d[ch], 0.0f) << i << " ch " << ch;
                ++exact_zeros;
            }
        }
        const float rel = std::fabs(d.max() - m) / m;
        worst_max_channel = std::max(worst_max_channel, rel);
        sum_signed += (d.max() - m) / m;
    }
    EXPECT_LE(worst_max_channel, kPowerMaxRelativeError);
    EXPECT_GT(worst_max_channel, 0.5f * kPowerMaxRelativeError);  // the bound is not vacuous
    EXPECT_GT(exact_zeros, n / 20);
    // Rounding, not truncation: no systematic darkening (truncation would average about -2^-9).
    EXPECT_LT(std::fabs(sum_signed / n), 2e-4);
}

TEST(SharedExponentPower, ExactValuesAndCarry) {
    for (float v : {1.0f, 0.5f, 0.75f, 3.0f, 0.125f, 0x1.8p-100f, 0x1.fep+100f}) {
        EXPECT_EQ(round_trip(Spectrum(v)), Spectrum(v)) << v;
    }
    EXPECT_EQ(round_trip(spectrum_of(1.0f, 0.5f, 0.25f, 0.125f)), spectrum_of(1.0f, 0.5f, 0.25f, 0.125f));
    // The code's layout: channel i's mantissa in byte i, the exponent biased by 128 (1 = 128 * 2^(1-8)).
    EXPECT_EQ(encode_power(Spectrum(1.0f)), (PowerCode{0x80808080u, 129}));
    EXPECT_EQ(encode_power(spectrum_of(1.0f, 0.5f, 0.25f, 0.0f)), (PowerCode{0x00204080u, 129}));
    EXPECT_EQ(encode_power(spectrum_of(0.0f, 0.0f, 0.0f, 3.0f)), (PowerCode{0xc0000000u, 130}));
    // 255.75/256 rounds up to 256/256: the exponent must carry, decoding to exactly 1, whichever
    // channel holds the largest value (the fast encoder's lanes).
    for (int ch = 0; ch < 4; ++ch) {
        Spectrum c = spectrum_of(0.1f, 0.0f, 0.3f, 0.7f);
        c[ch] = 255.75f / 256.0f;
        const PowerCode code = encode_power(c);
        EXPECT_EQ(code.exponent, 129) << ch;
        EXPECT_EQ(code, encode_power_reference(c)) << ch;
        const Spectrum d = decode_power(code);
        EXPECT_EQ(d[ch], 1.0f) << ch;
        for (int k = 0; k < 4; ++k) EXPECT_NEAR(d[k], c[k], kPowerMaxRelativeError * 1.0f) << ch << " " << k;
    }
}

TEST(SharedExponentPower, DegenerateInputs) {
    EXPECT_EQ(encode_power(Spectrum(0.0f)), PowerCode{});
    EXPECT_EQ(encode_power(Spectrum(0.0f)).exponent, 0);
    EXPECT_EQ(decode_power(PowerCode{}), Spectrum(0.0f));
    // Exponent byte 0 is black whatever the mantissas say.
    EXPECT_EQ(decode_power(PowerCode{0xffffffffu, 0}), Spectrum(0.0f));
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(round_trip(spectrum_of(-1.0f, 2.0f, nan, 0.5f)), spectrum_of(0.0f, 2.0f, 0.0f, 0.5f));
    EXPECT_EQ(round_trip(Spectrum(-1.0f)), Spectrum(0.0f));
    EXPECT_EQ(round_trip(Spectrum(nan)), Spectrum(0.0f));
    EXPECT_EQ(round_trip(Spectrum(1e-40f)), Spectrum(0.0f));  // below the exponent range
    const Spectrum big = round_trip(spectrum_of(inf, 1e38f, 1.0f, -inf));
    EXPECT_TRUE(big.is_finite());
    EXPECT_GT(big[0], 1e38f);
    EXPECT_EQ(big[3], 0.0f);
    // Tiny but representable powers (deep bounces of a weak light) keep their precision.
    const Spectrum tiny = spectrum_of(3e-36f, 1e-36f, 2e-36f, 0.0f);
    const Spectrum dt = round_trip(tiny);
    for (int ch = 0; ch < 4; ++ch) EXPECT_NEAR(dt[ch], tiny[ch], tiny.max() * kPowerMaxRelativeError) << ch;
}

// Disabled: fails against the library as it stands (reported, not changed here). For maxima in
// [2^-128, 2^-120) encode_power_reference's scale ldexp(1, 8 - e) overflows to +inf, so every
// channel's mantissa becomes 255 (a zero channel too: nearbyint(0 * inf) is NaN and fmin(NaN,
// 255) is 255): 1e-37 at channel 0 decodes as 3.7e-37 in all four channels. The header promises
// the bound above down to 2^-127 and black below it. (encode_power defers to the reference there,
// so the fast-vs-reference test cannot see it.)
TEST(SharedExponentPower, TinyMaximaKeepTheBoundOrEncodeBlack) {
    for (int k = -132; k <= -115; ++k) {
        for (float f : {1.0f, 1.5f, 1.99f}) {
            const float m = std::ldexp(f, k);
            const Spectrum c = spectrum_of(m, 0.5f * m, 0.0f, 0.25f * m);
            const Spectrum d = round_trip(c);
            if (d.is_black() && m < 0x1p-127f) continue;  // below the exponent range
            for (int ch = 0; ch < 4; ++ch)
                EXPECT_LE(std::fabs(d[ch] - c[ch]), kPowerMaxRelativeError * m) << m << " ch " << ch;
        }
    }
}

// The fast encoder must give the reference's code for every input: random powers over the whole
// exponent range (where it defers to the reference at the ends), mantissas that round up to the
// next exponent, ties, zeros, negatives, NaN and infinities, in every channel.
TEST(SharedExponentPower, FastEncoderGivesTheReferenceCodes) {
    Sampler rng(31);
    int mismatches = 0, compared = 0;
    const auto check = [&](const Spectrum& c) {
        ++compared;
        if (!(encode_power(c) == encode_power_reference(c))) ++mismatches;
    };
    for (int i = 0; i < 1000000; ++i) {
        const float scale = std::ldexp(1.0f, int(rng.next_index(300)) - 150);
        check(spectrum_of(rng.next(), rng.next(), rng.next(), rng.next()) * scale);
        Spectrum skewed = spectrum_of(rng.next(), 1e-3f * rng.next(), 0.0f, 1e-6f * rng.next()) * scale;
        std::swap(skewed[0], skewed[i % 4]);
        check(skewed);
        // Exactly representable mantissas and halfway points: k/2 * 2^j, and a carry candidate.
        const float half = float(rng.next_index(512)) * 0.5f * std::ldexp(1.0f, int(rng.next_index(40)) - 20);
        Spectrum ties = spectrum_of(half, half * 0.5f,
                                    255.5f * std::ldexp(1.0f, int(rng.next_index(40)) - 20), half * 0.25f);
        std::swap(ties[2], ties[i % 4]);
        check(ties);
    }
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    for (const Spectrum& c :
         {Spectrum(0.0f), spectrum_of(-1.0f, 2.0f, -0.0f, 0.0f), spectrum_of(nan, 1.0f, 0.5f, nan),
          spectrum_of(inf, 1.0f, 0.0f, 2.0f), spectrum_of(0.0f, 0.0f, 0.0f, inf), Spectrum(3e38f),
          Spectrum(1e-40f), spectrum_of(0x1p-110f, 0x1p-120f, 0.0f, 0x1p-112f),
          spectrum_of(0x1p114f, 1.0f, 0.0f, 0.0f), spectrum_of(255.5f, 0.0f, 1.0f, 255.0f),
          spectrum_of(0.99999994f, 0.5f, 0.25f, 0.125f), spectrum_of(0.0f, 0.0f, 0.0f, 255.75f / 256.0f)})
        check(c);
    EXPECT_GT(compared, 3000000);
    EXPECT_EQ(mismatches, 0);
}

// (The tracer's final rescale of every photon's power by 1 / N goes through encode_power, which
// the tests above cover.)

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

void expect_same_wavelengths(const Wavelengths& a, const Wavelengths& b) {
    EXPECT_EQ(a.code(), b.code());
    EXPECT_EQ(a.secondary_terminated(), b.secondary_terminated());
    for (int i = 0; i < spectrum::kSpectrumSamples; ++i) {
        EXPECT_EQ(a[i], b[i]) << i;
        EXPECT_EQ(a.pdf(i), b.pdf(i)) << i;
    }
}

TEST(PhotonRecord, ConstructAndDecodeFields) {
    const Vec3 p(0.25f, -3.5f, 1e3f);
    const Spectrum power = spectrum_of(2e-5f, 1e-5f, 5e-6f, 1.5e-5f);
    const Wavelengths lambda = Wavelengths::visible(0.3f);
    const Vec3 wi = normalize(Vec3(0.3f, 0.9f, -0.2f));
    const Vec3 n = normalize(Vec3(-0.1f, 0.2f, 0.97f));
    Photon ph(p, power, lambda, wi * 2.0f, n);
    EXPECT_EQ(ph.position, p);
    for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(ph.power()[c], power[c], power.max() * kPowerMaxRelativeError) << c;
    EXPECT_EQ(ph.power(), decode_power(encode_power_reference(power)));
    expect_same_wavelengths(ph.wavelengths(), lambda);
    EXPECT_EQ(ph.flags, 0);
    // The colour is the decoded power's at the stored wavelengths.
    EXPECT_EQ(ph.colour(), spectrum::to_srgb(ph.power(), lambda));
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

    // Power, wavelengths and the terminated flag can each change without touching the rest.
    const Vec3 wi_before = ph.wi();
    const Spectrum other = spectrum_of(0.0f, 4.0f, 1.0f, 2.0f);
    ph.set_power(other);
    EXPECT_EQ(ph.power(), other);  // exactly representable
    expect_same_wavelengths(ph.wavelengths(), lambda);
    Wavelengths hero_only = Wavelengths::visible(0.8f);
    hero_only.terminate_secondary();
    ph.set_wavelengths(hero_only);
    expect_same_wavelengths(ph.wavelengths(), hero_only);
    EXPECT_EQ(ph.flags, Photon::kSecondaryTerminated);
    EXPECT_EQ(ph.power(), other);
    ph.set_wavelengths(lambda);  // clears the flag again
    EXPECT_EQ(ph.flags, 0);
    expect_same_wavelengths(ph.wavelengths(), lambda);
    EXPECT_EQ(ph.position, p);
    EXPECT_EQ(ph.wi(), wi_before);
    EXPECT_EQ(ph.normal(), Vec3(0, -1, 0));
    EXPECT_EQ(ph.split_axis(), 3);
}

// Every 16-bit code comes back from the record as the wavelengths it was made from, with and
// without the secondary wavelengths terminated (a terminated photon's colour is its hero's alone).
TEST(PhotonRecord, WavelengthsRoundTrip) {
    int mismatches = 0;
    for (uint32_t code = 0; code < uint32_t(spectrum::kWavelengthCodes); ++code) {
        for (bool terminated : {false, true}) {
            const Wavelengths lambda = Wavelengths::from_code(uint16_t(code), terminated);
            const Photon ph(Vec3(0.0f), Spectrum(1.0f), lambda, Vec3(0, 0, 1), Vec3(0, 1, 0));
            const Wavelengths back = ph.wavelengths();
            bool same = back.code() == code && back.secondary_terminated() == terminated &&
                        ph.lambda_code == code &&
                        ((ph.flags & Photon::kSecondaryTerminated) != 0) == terminated;
            for (int i = 0; i < spectrum::kSpectrumSamples; ++i)
                same = same && back[i] == lambda[i] && back.pdf(i) == lambda.pdf(i);
            mismatches += !same;
        }
    }
    EXPECT_EQ(mismatches, 0);
    // visible(u) is the code of u: the record keeps the photon's sampled wavelengths.
    for (float u : {0.0f, 0.3f, 0.5f, 0.99999994f}) {
        const Wavelengths lambda = Wavelengths::visible(u);
        expect_same_wavelengths(
            Photon(Vec3(0.0f), Spectrum(1.0f), lambda, Vec3(0, 0, 1), Vec3(0.0f)).wavelengths(), lambda);
    }
    // Terminated: only the hero carries the colour, at n times its density's weight.
    Wavelengths hero = Wavelengths::visible(0.4f);
    const Wavelengths all = hero;
    hero.terminate_secondary();
    const Photon ph(Vec3(0.0f), spectrum_of(1.0f, 0.0f, 0.0f, 0.0f), hero, Vec3(0, 0, 1), Vec3(0.0f));
    const Rgb c = ph.colour(), c_all = spectrum::to_srgb(spectrum_of(1.0f, 0.0f, 0.0f, 0.0f), all);
    for (int ch = 0; ch < 3; ++ch) EXPECT_FLOAT_EQ(c[ch], spectrum::kSpectrumSamples * c_all[ch]) << ch;
}

// The irradiance cache keeps a colour in a record's first three power channels.
// A colour stored in a record (the irradiance cache's points) comes back, negative channels too.
TEST(PhotonRecord, StoredColourRoundTrip) {
    for (const Rgb colour : {Rgb(0.3f, 1.2f, 0.05f), Rgb(-0.2f, 0.13f, 0.6f), Rgb(0.5f, -0.01f, -0.3f)}) {
        Photon ph(Vec3(0.0f), Spectrum(0.0f), Wavelengths(), Vec3(0, 0, 1), Vec3(0, 0, 1));
        set_stored_colour(ph, colour);
        EXPECT_EQ(ph.power()[3], 0.0f);
        const Rgb back = stored_colour(ph);
        float m = 0;
        for (int ch = 0; ch < 3; ++ch) m = std::max(m, std::fabs(colour[ch]));
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(back[ch], colour[ch], m * kPowerMaxRelativeError) << ch;
    }
}

TEST(PhotonRecord, NoNormal) {
    Photon ph(Vec3(1, 2, 3), Spectrum(1.0f), Wavelengths::visible(0.5f), Vec3(0, 0, 1), Vec3(0.0f));
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
