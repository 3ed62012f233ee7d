// Tests of film/metrics against hand-computed values and the shared bench references.
#include "film/metrics.h"

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "io/image/image_io.h"

namespace phos::film {
namespace {

Image two_pixels(Rgb a, Rgb b) {
    Image img(2, 1);
    img.at(0, 0) = a;
    img.at(1, 0) = b;
    return img;
}

TEST(Metrics, RelMseHandComputed) {
    const Image ref = two_pixels(Rgb(1, 0, 0.1f), Rgb(0, 0, 0));
    const Image img = two_pixels(Rgb(2, 0, 0.1f), Rgb(0, 0.1f, 0));
    // Terms: (1)^2/(1 + 0.01) and 0.1^2/(0 + 0.01) = 1; the other four are 0. Mean over 6.
    const double expected = (1.0 / 1.01 + 1.0) / 6.0;
    EXPECT_NEAR(rel_mse(img, ref), expected, 1e-7);
    EXPECT_EQ(rel_mse(ref, ref), 0.0);
}

TEST(Metrics, MeanRatioHandComputed) {
    const Image ref = two_pixels(Rgb(1, 1, 1), Rgb(1, 1, 1));
    const Image img = two_pixels(Rgb(1.5f, 1.5f, 1.5f), Rgb(0.5f, 0.5f, 0.0f));  // mean 5.5/6
    EXPECT_NEAR(mean_ratio(img, ref), 5.5 / 6.0, 1e-7);
    EXPECT_DOUBLE_EQ(mean_ratio(ref, ref), 1.0);
    const Image black(2, 1);
    EXPECT_DOUBLE_EQ(mean_ratio(black, black), 1.0);
}

TEST(Metrics, WindowMeanIsHalfOpen) {
    Image img(4, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) img.at(x, y) = Rgb(float(x), float(y), float(10 * x + y));
    // Window x in [1,3), y in [0,2): pixels (1,0) (2,0) (1,1) (2,1), channel averages
    // (1+0+10)/3, (2+0+20)/3, (1+1+11)/3, (2+1+21)/3 -> mean 70/12.
    EXPECT_NEAR(window_mean(img, 1, 3, 0, 2), 70.0 / 12.0, 1e-9);
    EXPECT_NEAR(window_mean(img, 3, 4, 2, 3), (3.0 + 2.0 + 32.0) / 3.0, 1e-9);
    EXPECT_THROW(window_mean(img, 1, 1, 0, 2), InputError);  // empty
    EXPECT_THROW(window_mean(img, 0, 5, 0, 1), InputError);  // outside
    EXPECT_THROW(window_mean(img, -1, 2, 0, 1), InputError);
}

TEST(Metrics, SizeMismatchThrows) {
    const Image a(2, 1), b(1, 2);
    EXPECT_THROW(rel_mse(a, b), InputError);
    EXPECT_THROW(mean_ratio(a, b), InputError);
}

// On the shared references: zero error against itself, and the caustic window of
// cornell-glass-mirror matches the value bench/README.md quotes (0.680).
TEST(Metrics, SharedReferences) {
    const std::string dir = std::string(PHOS_SHARED_DIR) + "/bench/ref/";
    const Image ref = io::read_image(dir + "cornell-diffuse.pfm");
    EXPECT_EQ(rel_mse(ref, ref), 0.0);
    EXPECT_DOUBLE_EQ(mean_ratio(ref, ref), 1.0);
    Image brighter = ref;
    for (Rgb& p : brighter.pixels) p *= 1.1f;
    EXPECT_NEAR(mean_ratio(brighter, ref), 1.1, 1e-5);
    EXPECT_GT(rel_mse(brighter, ref), 0.0);

    const Image glass = io::read_image(dir + "cornell-glass-mirror.pfm");
    EXPECT_NEAR(window_mean(glass, 168, 200, 226, 242), 0.680, 0.0005);
    const Image point = io::read_image(dir + "caustic-point.pfm");
    EXPECT_NEAR(window_mean(point, 104, 128, 132, 156), 4.58, 0.005);
}

TEST(Metrics, SpeckleFractionCountsIsolatedBrightPixelsOnly) {
    Image img(10, 10);
    for (Rgb& p : img.pixels) p = Rgb(0.2f);
    EXPECT_EQ(speckle_fraction(img), 0.0);
    // Threshold 3 x 0.2 + 0.05 = 0.65: a dot at 0.7 counts, one at 0.6 does not.
    img.at(3, 3) = Rgb(0.7f);
    img.at(7, 7) = Rgb(0.6f);
    EXPECT_DOUBLE_EQ(speckle_fraction(img), 1.0 / 100.0);
    // A corner dot counts too (its clipped 3x3 window still has a median of 0.2).
    img.at(0, 0) = Rgb(5.0f);
    EXPECT_DOUBLE_EQ(speckle_fraction(img), 2.0 / 100.0);
    // A bright 6x6 patch is a feature: only the pixels whose 5x5 window holds at most 12 of its 36
    // pixels (its 4 corners and their 8 neighbours along the edges) stand out from a dark median.
    Image patch(12, 12);
    for (Rgb& p : patch.pixels) p = Rgb(0.1f);
    for (int y = 3; y < 9; ++y)
        for (int x = 3; x < 9; ++x) patch.at(x, y) = Rgb(4.0f);
    EXPECT_DOUBLE_EQ(speckle_fraction(patch), 12.0 / 144.0);
    // Dark noise below the offset never counts.
    Image dark(8, 8);
    for (int i = 0; i < 64; ++i) dark.pixels[size_t(i)] = Rgb(i % 7 == 0 ? 0.04f : 0.0f);
    EXPECT_EQ(speckle_fraction(dark), 0.0);
}

TEST(Metrics, BlockCorrelationOfAffineBrighteningIsOne) {
    Image a(32, 32), b(64, 64);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) a.at(x, y) = Rgb(float(x / 16) + 0.5f * float(y / 16));
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) b.at(x, y) = Rgb(3.0f * a.at(x / 2, y / 2).r + 1.0f);
    EXPECT_NEAR(block_correlation(a, b, 16), 1.0, 1e-9);
    EXPECT_NEAR(block_correlation(b, a, 16), 1.0, 1e-9);
    // The negative image correlates -1.
    Image c = a;
    for (Rgb& p : c.pixels) p = Rgb(2.0f) - p;
    EXPECT_NEAR(block_correlation(a, c, 16), -1.0, 1e-9);
    EXPECT_THROW(block_correlation(a, Image(48, 48), 16), InputError);
    EXPECT_THROW(block_correlation(a, b, 64), InputError);
}

}  // namespace
}  // namespace phos::film
