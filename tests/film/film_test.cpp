// Tests of film/film: weighted averaging with the box filter, set_pixel, named layers, and rejection
// (with a count) of NaN/inf samples.
#include "film/film.h"

#include <gtest/gtest.h>

#include <limits>

namespace phos::film {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInfF = std::numeric_limits<float>::infinity();

TEST(Film, AveragesWeightedSamplesPerPixel) {
    Film film(4, 3);
    EXPECT_EQ(film.width(), 4);
    EXPECT_EQ(film.height(), 3);
    film.add_sample(1, 2, Rgb(1, 2, 3));
    film.add_sample(1, 2, Rgb(3, 2, 1));
    film.add_sample(3, 0, Rgb(2, 0, 0), 3.0f);
    film.add_sample(3, 0, Rgb(6, 4, 0), 1.0f);  // weighted mean: (3*2 + 6)/4 = 3, 4/4 = 1
    const Image img = film.image();
    ASSERT_EQ(img.width, 4);
    ASSERT_EQ(img.height, 3);
    EXPECT_EQ(img.at(1, 2), Rgb(2, 2, 2));
    EXPECT_EQ(img.at(3, 0), Rgb(3, 1, 0));
    // Box filter: no other pixel received anything.
    int touched = 0;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) touched += img.at(x, y).is_black() ? 0 : 1;
    EXPECT_EQ(touched, 2);
    EXPECT_DOUBLE_EQ(film.main().weight(3, 0), 4.0);
    EXPECT_DOUBLE_EQ(film.main().weight(0, 0), 0.0);
}

TEST(Film, SetPixelOverwrites) {
    Film film(2, 2);
    film.add_sample(0, 1, Rgb(9, 9, 9), 5.0f);
    film.set_pixel(0, 1, Rgb(0.5f, 0.25f, 1));
    EXPECT_EQ(film.image().at(0, 1), Rgb(0.5f, 0.25f, 1));
    film.add_sample(0, 1, Rgb(1.5f, 0.75f, 1));  // now averages with the set value at weight 1
    EXPECT_EQ(film.image().at(0, 1), Rgb(1, 0.5f, 1));
}

TEST(Film, RejectsNonFiniteSamplesAndCountsThem) {
    Film film(2, 1);
    film.add_sample(0, 0, Rgb(1, 1, 1));
    EXPECT_FALSE(film.add_sample(0, 0, Rgb(kNan, 0, 0)));
    EXPECT_FALSE(film.add_sample(0, 0, Rgb(0, kInfF, 0)));
    EXPECT_FALSE(film.add_sample(0, 0, Rgb(0, 0, -kInfF)));
    EXPECT_FALSE(film.add_sample(0, 0, Rgb(1, 1, 1), kNan));
    EXPECT_TRUE(film.add_sample(0, 0, Rgb(3, 3, 3)));
    EXPECT_EQ(film.rejected_samples(), 4u);
    EXPECT_EQ(film.image().at(0, 0), Rgb(2, 2, 2));  // the good samples only, weight 2
    // Outside the film: ignored, not counted as NaN.
    EXPECT_FALSE(film.add_sample(2, 0, Rgb(1, 1, 1)));
    EXPECT_FALSE(film.add_sample(0, -1, Rgb(1, 1, 1)));
    EXPECT_EQ(film.rejected_samples(), 4u);
    film.clear();
    EXPECT_EQ(film.rejected_samples(), 0u);
    EXPECT_TRUE(film.image().at(0, 0).is_black());
}

TEST(Film, NamedLayersAccumulateSeparately) {
    Film film(3, 2);
    EXPECT_EQ(film.find_layer("direct"), nullptr);
    Layer& direct = film.layer("direct");
    Layer& caustic = film.layer("caustic");
    EXPECT_EQ(&film.layer("direct"), &direct);  // same layer on repeated lookup
    EXPECT_EQ(direct.width(), 3);
    EXPECT_EQ(direct.height(), 2);
    direct.add(2, 1, Rgb(1, 0, 0));
    direct.add(2, 1, Rgb(0, 0, 1));
    caustic.add(2, 1, Rgb(0, 4, 0));
    caustic.add(0, 0, Rgb(kNan, 0, 0));
    film.add_sample(2, 1, Rgb(1, 4, 1));
    EXPECT_EQ(direct.image().at(2, 1), Rgb(0.5f, 0, 0.5f));
    EXPECT_EQ(film.find_layer("caustic")->image().at(2, 1), Rgb(0, 4, 0));
    EXPECT_EQ(film.image().at(2, 1), Rgb(1, 4, 1));
    EXPECT_EQ(caustic.rejected(), 1u);
    EXPECT_EQ(film.rejected_samples(), 0u);  // the main image saw no bad sample
    EXPECT_EQ(film.layer_names(), (std::vector<std::string>{"caustic", "direct"}));
}

TEST(Film, CopiesAreIndependent) {
    Film a(2, 2);
    a.add_sample(0, 0, Rgb(1, 1, 1));
    a.add_sample(0, 0, Rgb(kNan, 1, 1));
    Film b = a;
    b.add_sample(0, 0, Rgb(3, 3, 3));
    EXPECT_EQ(a.image().at(0, 0), Rgb(1, 1, 1));
    EXPECT_EQ(b.image().at(0, 0), Rgb(2, 2, 2));
    EXPECT_EQ(b.rejected_samples(), 1u);
}

}  // namespace
}  // namespace phos::film
