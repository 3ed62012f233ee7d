// pbrt `curve` shapes read as pbrt-v4 reads them: segment counts for each basis and degree, the
// conversions to cubic segments (degree elevation, B-splines to Bezier where needed), widths,
// ribbon normals, and the located errors for bad counts and names.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pbrt_test_util.h"
#include "scene/scene.h"

namespace phos::io::test {
namespace {

using scene::CurveSet;

struct Loaded {
    scene::Scene scene;
    int warnings = 0;
};

Loaded load_text(const std::string& text) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string path = dir.write("scene.pbrt", text);
    const int before = log::warning_count();
    Loaded l{load_pbrt(path), 0};
    l.warnings = log::warning_count() - before;
    return l;
}

const CurveSet& only_curves(const Loaded& l) {
    EXPECT_EQ(l.scene.shapes.size(), 1u);
    EXPECT_EQ(l.scene.shapes.at(0).kind, scene::Shape::Kind::Curves);
    return l.scene.shapes.at(0).curves;
}

// The cubic Bezier of four values at u.
template <typename T>
T bezier(const T* c, float u) {
    const float s = 1 - u;
    return c[0] * (s * s * s) + c[1] * (3 * u * s * s) + c[2] * (3 * u * u * s) + c[3] * (u * u * u);
}

void expect_vec(Vec3 a, Vec3 b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(PbrtCurves, CubicBezierSegmentsAndWidthsAsPbrt) {
    // 7 control points: two segments sharing (3, 0, 0); width 0.4 at the start to 0.2 at the end.
    const Loaded l = load_text(
        "WorldBegin\nTranslate 0 0 1\nReverseOrientation\nShape \"curve\" \"string type\" \"cylinder\" "
        "\"point3 P\" [0 0 0 1 1 0 2 1 0 3 0 0 4 -1 0 5 -1 0 6 0 0] \"float width0\" 0.4 "
        "\"float width1\" 0.2 \"integer splitdepth\" 5\n");
    EXPECT_EQ(l.warnings, 0);
    const CurveSet& c = only_curves(l);
    EXPECT_EQ(c.type, CurveSet::Type::Cylinder);
    EXPECT_EQ(c.basis, CurveSet::Basis::Bezier);
    ASSERT_EQ(c.segment_count(), 2u);
    ASSERT_EQ(c.points.size(), 8u);
    ASSERT_EQ(c.radii.size(), 8u);
    EXPECT_TRUE(c.normals.empty());
    expect_vec(c.points[c.segments[1]], {3, 0, 0}, 0);
    expect_vec(c.points[c.segments[1] + 3], {6, 0, 0}, 0);
    // Radius (half the width) linear over the whole curve: 0.2, 0.15 at the joint, 0.1.
    EXPECT_FLOAT_EQ(bezier(&c.radii[c.segments[0]], 0), 0.2f);
    EXPECT_FLOAT_EQ(bezier(&c.radii[c.segments[0]], 1), 0.15f);
    EXPECT_NEAR(bezier(&c.radii[c.segments[0]], 0.5f), 0.175f, 1e-6);
    EXPECT_FLOAT_EQ(bezier(&c.radii[c.segments[1]], 1), 0.1f);
    // The transform and orientation stay with the shape (the accelerator applies them).
    const scene::Shape& s = l.scene.shapes[0];
    EXPECT_TRUE(s.reverse_orientation);
    expect_vec(s.to_world.point({0, 0, 0}), {0, 0, 1}, 0);
}

TEST(PbrtCurves, QuadraticCurvesAreRaisedToCubicOnTheSameCurve) {
    // Degree 2 Bezier, two segments (5 points): the cubic traces the quadratic.
    const Loaded l = load_text(
        "WorldBegin\nShape \"curve\" \"integer degree\" 2 \"point3 P\" [0 0 0 1 2 0 2 0 0 3 -2 0 4 0 0]\n");
    const CurveSet& c = only_curves(l);
    EXPECT_EQ(c.type, CurveSet::Type::Flat);  // pbrt's default
    ASSERT_EQ(c.segment_count(), 2u);
    for (float u : {0.0f, 0.3f, 0.5f, 1.0f}) {
        const float s = 1 - u;
        const Vec3 q = Vec3(0, 0, 0) * (s * s) + Vec3(1, 2, 0) * (2 * u * s) + Vec3(2, 0, 0) * (u * u);
        expect_vec(bezier(&c.points[c.segments[0]], u), q, 1e-5f);
    }
    // The default width is 1: radius 0.5 everywhere.
    for (float r : c.radii) EXPECT_FLOAT_EQ(r, 0.5f);

    // Quadratic B-spline: 4 points, 2 segments, from the midpoint of p0 p1 to that of p2 p3.
    const Loaded b = load_text(
        "WorldBegin\nShape \"curve\" \"string basis\" \"bspline\" \"integer degree\" 2 \"point3 P\" "
        "[0 0 0 2 0 0 2 2 0 0 2 0]\n");
    const CurveSet& cb = only_curves(b);
    ASSERT_EQ(cb.segment_count(), 2u);
    EXPECT_EQ(cb.basis, CurveSet::Basis::Bezier);
    expect_vec(bezier(&cb.points[cb.segments[0]], 0), {1, 0, 0}, 1e-6f);
    expect_vec(bezier(&cb.points[cb.segments[0]], 1), {2, 1, 0}, 1e-6f);
    expect_vec(bezier(&cb.points[cb.segments[1]], 1), {1, 2, 0}, 1e-6f);
}

TEST(PbrtCurves, CubicBSplinesKeepTheirControlPointsAndALinearWidth) {
    const Loaded l = load_text(
        "WorldBegin\nShape \"curve\" \"string basis\" \"bspline\" \"string type\" \"cylinder\" \"point3 P\" "
        "[0 0 0 1 0 0 2 0 0 3 0 0 4 0 0 5 0 0] \"float width0\" 0.6 \"float width1\" 0.3\n");
    const CurveSet& c = only_curves(l);
    EXPECT_EQ(c.basis, CurveSet::Basis::BSpline);
    ASSERT_EQ(c.segment_count(), 3u);
    ASSERT_EQ(c.points.size(), 6u);
    EXPECT_EQ(c.segments, (std::vector<uint32_t>{0, 1, 2}));
    // The B-spline of the radii at each segment's ends: pbrt's width lerped over the segments.
    const auto radius = [&](size_t seg, float u) {
        const float s = 1 - u;
        const float w[4] = {s * s * s / 6, (3 * u * u * u - 6 * u * u + 4) / 6,
                            (-3 * u * u * u + 3 * u * u + 3 * u + 1) / 6, u * u * u / 6};
        float r = 0;
        for (int k = 0; k < 4; ++k) r += w[k] * c.radii[seg + size_t(k)];
        return r;
    };
    EXPECT_NEAR(radius(0, 0), 0.3f, 1e-6);
    EXPECT_NEAR(radius(1, 0), 0.25f, 1e-6);
    EXPECT_NEAR(radius(1, 0.5f), 0.225f, 1e-6);
    EXPECT_NEAR(radius(2, 1), 0.15f, 1e-6);
}

TEST(PbrtCurves, RibbonNormalsAreSlerpedBetweenSegmentEnds) {
    const Loaded l = load_text(
        "WorldBegin\nShape \"curve\" \"string type\" \"ribbon\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] "
        "\"normal N\" [0 0 2 0 1 0]\n");
    const CurveSet& c = only_curves(l);
    EXPECT_EQ(c.type, CurveSet::Type::Ribbon);
    ASSERT_EQ(c.normals.size(), 4u);
    expect_vec(bezier(c.normals.data(), 0), {0, 0, 1}, 1e-6f);  // normalised
    expect_vec(bezier(c.normals.data(), 1), {0, 1, 0}, 1e-6f);
    for (float u : {0.25f, 0.5f, 0.8f}) {
        const Vec3 slerp{0, std::sin(u * kPi / 2), std::cos(u * kPi / 2)};
        expect_vec(bezier(c.normals.data(), u), slerp, 0.01f);
    }
}

TEST(PbrtCurves, NormalsOnOtherCurvesWarnAndAreDropped) {
    const Loaded l = load_text(
        "WorldBegin\nShape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] \"normal N\" [0 0 1 0 0 1]\n");
    EXPECT_EQ(l.warnings, 1);
    EXPECT_TRUE(only_curves(l).normals.empty());
}

TEST(PbrtCurves, AreaLightsOnCurvesWarnAndDoNotEmit) {
    const Loaded l = load_text(
        "WorldBegin\nLightSource \"point\"\nAttributeBegin\nAreaLightSource \"diffuse\"\n"
        "Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0]\nAttributeEnd\n");
    EXPECT_EQ(l.warnings, 1);
    ASSERT_EQ(l.scene.shapes.size(), 1u);
    EXPECT_EQ(l.scene.shapes[0].area_light, -1);
    EXPECT_EQ(l.scene.lights.size(), 1u);  // the point light only
}

struct Case {
    const char* name;
    std::string shape;
    int col;
    const char* message;
};

class PbrtCurveErrors : public ::testing::TestWithParam<Case> {};

TEST_P(PbrtCurveErrors, AtTheFaultyParameter) {
    QuietLog quiet;
    PbrtTempDir dir;
    const Case& c = GetParam();
    const std::string path = dir.write("bad.pbrt", "WorldBegin\n" + c.shape + "\n");
    expect_pbrt_error(path, 2, c.col, c.message, path);
}

const std::string P4 = "\"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0]";

INSTANTIATE_TEST_SUITE_P(
    Curves, PbrtCurveErrors,
    ::testing::Values(
        Case{"NoPoints", "Shape \"curve\" \"float width\" 1", 1, "missing \"point3 P\""},
        Case{"BezierCount", "Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0 4 0 0]", 15,
             "5 control points for a degree 3 Bezier curve (4 + k * 3 are required)"},
        Case{"QuadraticCount", "Shape \"curve\" \"integer degree\" 2 " + P4, 34,
             "4 control points for a degree 2 Bezier curve"},
        Case{"BSplineCount", "Shape \"curve\" \"string basis\" \"bspline\" \"point3 P\" [0 0 0 1 0 0 2 0 0]",
             40, "3 control points for a degree 3 B-spline (at least 4 are required)"},
        Case{"Degree", "Shape \"curve\" \"integer degree\" 4 " + P4, 15, "degree 4 (2 or 3 are supported)"},
        Case{"Basis", "Shape \"curve\" \"string basis\" \"hermite\" " + P4, 15, "unknown basis \"hermite\""},
        Case{"Type", "Shape \"curve\" \"string type\" \"tube\" " + P4, 15, "unknown curve type \"tube\""},
        Case{"RibbonWithoutNormals", "Shape \"curve\" \"string type\" \"ribbon\" " + P4, 1,
             "ribbon curves need normals \"N\""},
        Case{"RibbonNormalCount",
             "Shape \"curve\" \"string type\" \"ribbon\" " + P4 + " \"normal N\" [0 0 1]", 75,
             "1 normals for 1 segments (a ribbon needs 2, one per segment end)"},
        Case{"ZeroNormal", "Shape \"curve\" \"string type\" \"ribbon\" " + P4 + " \"normal N\" [0 0 1 0 0 0]",
             75, "zero or non-finite normal"},
        Case{"NegativeWidth", "Shape \"curve\" " + P4 + " \"float width1\" -1", 52,
             "the width must be finite and >= 0"}),
    [](const ::testing::TestParamInfo<Case>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace phos::io::test
