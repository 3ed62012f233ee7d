// Tests of the RGL `.bsdf` reader and writer (io/bsdf): a written file reads back bit for bit
// (spectral, rgb-only, anisotropic); every kind of damage (truncation at any byte, bad magic,
// version, unknown or wrong dtype, wrong rank or shape, data beyond the file or over the field
// table or another field, absurd sizes, NaN, negative densities, a missing field, slices without
// mass) is a ParseError "file: what is wrong"; and a tabulated Trowbridge-Reitz conductor read
// from its file evaluates within a stated tolerance of the analytic BRDF it was made from.
#include "io/bsdf/rgl_bsdf_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "shading/measured_bxdf.h"
#include "shading/measured_tabulation.h"
#include "spectrum/named_metals.h"
#include "test_util.h"

namespace phos::io {
namespace {

using shading::TabulatedModel;
using shading::TabulationGrid;

const std::string kPath = "mat.bsdf";

// A small valid table (a rough conductor with a flat index) and its file.
scene::MeasuredBsdfTables small_tables(bool spectral = true, bool isotropic = true) {
    TabulatedModel m;
    m.alpha_x = 0.3f;
    m.alpha_y = isotropic ? 0.3f : 0.6f;
    m.eta = [](float) { return 0.2f; };
    m.k = [](float l) { return 3.0f + l / 1000; };
    TabulationGrid g;
    g.n_theta_i = 3;
    g.n_phi_i = 3;
    g.ndf_n = 4;
    g.vndf_n = 4;
    g.n = 3;
    if (spectral) g.wavelengths = {400, 600};
    g.description = "small";
    return shading::tabulate_brdf(m, g);
}

std::string error_of(const std::string& bytes) {
    try {
        parse_rgl_bsdf(bytes, kPath);
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, kPath);
        return e.what();
    }
    return "(accepted)";
}

void put_le(std::string& s, size_t at, uint64_t v, size_t width) {
    for (size_t i = 0; i < width; ++i) s[at + i] = char(uint8_t(v >> (8 * i)));
}

// Where the description of field `name` starts in the field table: the byte after its name.
size_t after_name(const std::string& s, const std::string& name) {
    std::string key(2, '\0');
    put_le(key, 0, name.size(), 2);
    key += name;
    const size_t at = s.find(key, 18);
    EXPECT_NE(at, std::string::npos) << name;
    return at + key.size();
}
// Byte positions of a field's rank, dtype, offset and shape entry `d`.
size_t dtype_at(const std::string& s, const std::string& n) { return after_name(s, n) + 2; }
size_t offset_at(const std::string& s, const std::string& n) { return after_name(s, n) + 3; }
size_t shape_at(const std::string& s, const std::string& n, size_t d) {
    return after_name(s, n) + 11 + 8 * d;
}
uint64_t get_le(const std::string& s, size_t at, size_t width) {
    uint64_t v = 0;
    for (size_t i = 0; i < width; ++i) v |= uint64_t(uint8_t(s[at + i])) << (8 * i);
    return v;
}
void put_float(std::string& s, size_t at, float f) {
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    put_le(s, at, bits, 4);
}

void expect_equal(const scene::MeasuredBsdfTables& a, const scene::MeasuredBsdfTables& b) {
    EXPECT_EQ(a.description, b.description);
    EXPECT_EQ(a.jacobian, b.jacobian);
    EXPECT_EQ(a.theta_i, b.theta_i);
    EXPECT_EQ(a.phi_i, b.phi_i);
    EXPECT_EQ(a.wavelengths, b.wavelengths);
    EXPECT_EQ(a.ndf_nx, b.ndf_nx);
    EXPECT_EQ(a.ndf_ny, b.ndf_ny);
    EXPECT_EQ(a.ndf, b.ndf);
    EXPECT_EQ(a.sigma_nx, b.sigma_nx);
    EXPECT_EQ(a.sigma, b.sigma);
    EXPECT_EQ(a.vndf_nx, b.vndf_nx);
    EXPECT_EQ(a.vndf_ny, b.vndf_ny);
    EXPECT_EQ(a.vndf, b.vndf);
    EXPECT_EQ(a.n, b.n);
    EXPECT_EQ(a.luminance, b.luminance);
    EXPECT_EQ(a.spectra, b.spectra);
    EXPECT_EQ(a.rgb, b.rgb);
}

TEST(RglBsdfFile, WrittenFilesReadBackExactly) {
    for (const bool spectral : {true, false})
        for (const bool isotropic : {true, false}) {
            const scene::MeasuredBsdfTables t = small_tables(spectral, isotropic);
            ASSERT_EQ(t.check(), "");
            EXPECT_EQ(t.isotropic(), isotropic);
            const std::string bytes = rgl_bsdf_bytes(t);
            EXPECT_EQ(bytes.substr(0, 12), std::string("tensor_file\0", 12));
            expect_equal(parse_rgl_bsdf(bytes, kPath), t);
        }
    testing::TempDir dir;
    const std::string path = dir.file("m.bsdf");
    write_rgl_bsdf(path, small_tables());
    const auto m = read_rgl_bsdf(path);
    ASSERT_TRUE(m);
    expect_equal(m->tables(), small_tables());
    try {
        read_rgl_bsdf(dir.file("missing.bsdf"));
        ADD_FAILURE() << "a missing file was read";
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.bsdf: cannot open"), std::string::npos) << e.what();
    }
}

// Every field's data is 8-byte aligned and follows the field table, as the RGL tools write them.
TEST(RglBsdfFile, LayoutIsTheRglOne) {
    const std::string s = rgl_bsdf_bytes(small_tables());
    EXPECT_EQ(get_le(s, 12, 1), 1u);
    EXPECT_EQ(get_le(s, 13, 1), 0u);
    EXPECT_EQ(get_le(s, 14, 4), 10u);  // description, jacobian, theta_i, phi_i, ndf, sigma, vndf,
                                       // luminance, wavelengths, spectra
    for (const char* name : {"description", "jacobian", "theta_i", "phi_i", "ndf", "sigma", "vndf",
                             "luminance", "wavelengths", "spectra"})
        EXPECT_EQ(get_le(s, offset_at(s, name), 8) % 8, 0u) << name;
    EXPECT_EQ(get_le(s, dtype_at(s, "vndf"), 1), 10u);        // float32
    EXPECT_EQ(get_le(s, dtype_at(s, "description"), 1), 1u);  // uint8
    EXPECT_EQ(get_le(s, shape_at(s, "spectra", 2), 8), 2u);   // the wavelengths
}

TEST(RglBsdfFile, EveryTruncationIsALocatedError) {
    const std::string s = rgl_bsdf_bytes(small_tables());
    for (size_t len = 0; len < s.size(); ++len) {
        const std::string e = error_of(s.substr(0, len));
        ASSERT_EQ(e.rfind(kPath + ": ", 0), 0u) << "length " << len << ": " << e;
    }
    EXPECT_NE(error_of(s.substr(0, 10)).find("truncated"), std::string::npos);
    EXPECT_NE(error_of(s.substr(0, 40)).find("truncated"), std::string::npos);
    EXPECT_NE(error_of(s.substr(0, s.size() - 1)).find("lies beyond the end of the file"), std::string::npos);
}

TEST(RglBsdfFile, DamagedHeadersAndTablesAreLocatedErrors) {
    const std::string good = rgl_bsdf_bytes(small_tables());
    const auto expect = [&](std::string s, const std::string& message) {
        const std::string e = error_of(s);
        EXPECT_EQ(e.rfind(kPath + ": ", 0), 0u) << e;
        EXPECT_NE(e.find(message), std::string::npos) << "expected '" << message << "' in: " << e;
    };
    std::string s = good;
    s[0] = 'T';
    expect(s, "not an RGL tensor file");
    s = good;
    s[12] = 2;
    expect(s, "version 2.0");
    s = good;
    put_le(s, 14, 0xffffffffu, 4);
    expect(s, "announces 4294967295 fields");
    s = good;
    s[dtype_at(s, "vndf")] = 12;
    expect(s, "field \"vndf\" has an unknown dtype (12)");
    s = good;
    s[dtype_at(s, "description")] = 2;  // int8: same size, wrong kind
    expect(s, "field \"description\" is int8, not uint8");
    s = good;
    s[dtype_at(s, "ndf")] = 5;  // uint32
    expect(s, "field \"ndf\" is uint32, not float32");
    s = good;
    put_le(s, shape_at(s, "vndf", 1), 2, 8);  // theta_i has 3
    expect(
        s,
        "field \"vndf\" has shape [1, 2, 4, 4]: its first two dimensions must be phi_i's 1 and theta_i's 3");
    s = good;
    put_le(s, shape_at(s, "spectra", 2), 1, 8);
    expect(s, "its third dimension must be the number of wavelengths (2)");
    s = good;
    put_le(s, shape_at(s, "luminance", 3), 2, 8);
    expect(s, "its grid must be square");
    s = good;
    put_le(s, shape_at(s, "vndf", 2), uint64_t(1) << 62, 8);
    expect(s, "holds more bytes than the file");
    s = good;
    put_le(s, shape_at(s, "ndf", 0), 0, 8);
    expect(s, "field \"ndf\" has shape [0, 4]: a dimension is empty");
    s = good;
    put_le(s, offset_at(s, "spectra"), s.size(), 8);
    expect(s, "field \"spectra\" (");
    expect(s, "lies beyond the end of the file");
    s = good;
    put_le(s, offset_at(s, "spectra"), std::numeric_limits<uint64_t>::max() - 3, 8);
    expect(s, "lies beyond the end of the file");
    s = good;
    put_le(s, offset_at(s, "theta_i"), 20, 8);
    expect(s, "overlaps the field table");
    s = good;
    put_le(s, offset_at(s, "ndf"), get_le(s, offset_at(s, "sigma"), 8), 8);
    expect(s, "overlap in the file");
    s = good;
    s[after_name(s, "sigma") - 1] = 'X';  // "sigmX"
    expect(s, "no field \"sigma\"");
    s = good;
    s[after_name(s, "phi_i") - 1] = 'X';  // "phi_X", then "phi_i" is missing
    expect(s, "no field \"phi_i\"");
}

TEST(RglBsdfFile, BadValuesAreLocatedErrors) {
    const std::string good = rgl_bsdf_bytes(small_tables());
    const auto expect = [&](const std::string& field, size_t index, float value, const std::string& message) {
        std::string s = good;
        put_float(s, size_t(get_le(s, offset_at(s, field), 8)) + 4 * index, value);
        const std::string e = error_of(s);
        EXPECT_EQ(e.rfind(kPath + ": ", 0), 0u) << e;
        EXPECT_NE(e.find(message), std::string::npos) << "expected '" << message << "' in: " << e;
    };
    expect("ndf", 3, std::nanf(""), "ndf[3] is not a finite number");
    expect("spectra", 5, std::numeric_limits<float>::infinity(), "spectra[5] is not a finite number");
    expect("sigma", 2, -1.0f, "sigma[2] is negative");
    expect("vndf", 7, -0.5f, "vndf[7] is negative");
    expect("luminance", 0, -2.0f, "luminance[0] is negative");
    expect("theta_i", 1, 0.0f, "theta_i is not strictly increasing (at index 1)");
    expect("wavelengths", 0, std::nanf(""), "wavelengths[0] is not a finite number");
    // Negative spectra are measurement noise: allowed (evaluation clamps them).
    std::string s = good;
    put_float(s, size_t(get_le(s, offset_at(s, "spectra"), 8)), -0.01f);
    EXPECT_EQ(error_of(s), "(accepted)");
    // A sampling slice without mass.
    s = good;
    const size_t lum = size_t(get_le(s, offset_at(s, "luminance"), 8));
    for (size_t i = 0; i < 9; ++i) put_float(s, lum + 4 * (9 + i), 0.0f);  // slice 1 of 3 x 3
    EXPECT_NE(error_of(s).find("luminance slice 1 is zero everywhere"), std::string::npos) << error_of(s);
}

TEST(RglBsdfFile, AnisotropicFilesMustCoverTheCircle) {
    scene::MeasuredBsdfTables t = small_tables(true, false);
    ASSERT_EQ(t.phi_i.size(), 3u);
    t.phi_i = {0.0f, 1.0f, 3.1f};  // half the circle: a symmetry reduction pbrt-v4 refuses too
    const std::string e = error_of(rgl_bsdf_bytes(t));
    EXPECT_NE(e.find("phi_i spans 3.1"), std::string::npos) << e;
}

TEST(RglBsdfFile, RandomDamageNeverEscapesAsAnythingButParseError) {
    const std::string good = rgl_bsdf_bytes(small_tables());
    Sampler rng(42);
    int accepted = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        std::string s = good;
        const int edits = 1 + int(rng.next_index(4));
        for (int k = 0; k < edits; ++k) s[rng.next_index(uint32_t(s.size()))] = char(rng.next_index(256));
        try {
            const auto m = scene::MeasuredBsdf(parse_rgl_bsdf(s, kPath));
            ++accepted;
        } catch (const ParseError& e) {
            ASSERT_EQ(std::string(e.what()).rfind(kPath + ": ", 0), 0u) << e.what();
        }
    }
    EXPECT_GT(accepted, 0);
}

// A Trowbridge-Reitz gold conductor (alpha 0.2) written to a file and read back: f of the tables
// against the analytic f at the file's wavelengths. Tolerance: the reduced BRDF F G2 / G1 is
// smooth and is interpolated bilinearly on a 32 x 32 grid of the warped square and linearly
// between 10 incident elevations; D is bilinear on a 64 x 64 grid of (u(theta), u(phi)). Relative
// errors of such interpolation are a few per cent where f matters; this checks the median below
// 1 % and the 95th percentile below 6 % over directions drawn from the measured sampler (where
// f cos is large), and that the directional albedo (quadrature) agrees within 1.5 %.
TEST(RglBsdfFile, TabulatedConductorFromFileMatchesTheAnalyticBrdf) {
    const auto au = spectrum::named_metal("Au");
    ASSERT_TRUE(au);
    TabulatedModel m;
    m.alpha_x = m.alpha_y = 0.2f;
    m.eta = [&](float l) { return au->eta(l); };
    m.k = [&](float l) { return au->k(l); };
    TabulationGrid g;
    g.wavelengths = {450, 550, 650};
    testing::TempDir dir;
    const std::string path = dir.file("gold.bsdf");
    write_rgl_bsdf(path, shading::tabulate_brdf(m, g));
    const auto data = read_rgl_bsdf(path);
    const shading::MeasuredBxdf bxdf(*data);
    const Wavelengths lambda = Wavelengths::at_values({450, 550, 650, 550});
    Sampler rng(7);
    std::vector<double> rel;
    for (float theta : {0.1f, 0.5f, 0.9f, 1.2f}) {
        const Vec3 wo(std::sin(theta), 0.0f, std::cos(theta));
        for (int i = 0; i < 400; ++i) {
            const auto s = bxdf.sample(wo, rng.next2(), lambda);
            if (!s) continue;
            const Spectrum f = bxdf.f(wo, s->wi, lambda);
            for (int c = 0; c < 3; ++c) {
                const double a = shading::analytic_brdf(m, wo, s->wi, lambda[c]);
                rel.push_back(std::fabs(f[c] - a) / a);
            }
        }
        // Albedo at 550 nm by quadrature of both.
        const auto albedo = [&](auto&& f_of) {
            double acc = 0;
            const int nt = 256, np = 256;
            for (int a = 0; a < nt; ++a)
                for (int b = 0; b < np; ++b) {
                    const double t = (a + 0.5) / nt * M_PI / 2, p = (b + 0.5) / np * 2 * M_PI;
                    const Vec3 wi(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)),
                                  float(std::cos(t)));
                    acc += f_of(wi) * std::cos(t) * std::sin(t);
                }
            return acc * (M_PI / 2 / nt) * (2 * M_PI / np);
        };
        const double tab = albedo([&](Vec3 wi) { return double(bxdf.f(wo, wi, lambda)[1]); });
        const double ana = albedo([&](Vec3 wi) { return double(shading::analytic_brdf(m, wo, wi, 550)); });
        EXPECT_NEAR(tab, ana, 0.015 * ana) << "theta " << theta;
    }
    ASSERT_GT(rel.size(), 3000u);
    std::sort(rel.begin(), rel.end());
    EXPECT_LT(rel[rel.size() / 2], 0.01);
    EXPECT_LT(rel[rel.size() * 95 / 100], 0.06);
}

}  // namespace
}  // namespace phos::io
