// Tests of printf_string: the text snprintf writes, short or longer than its stack buffer.
#include "core/format.h"

#include <gtest/gtest.h>

#include <string>

namespace phos {
namespace {

TEST(Format, WritesWhatSnprintfWrites) {
    EXPECT_EQ(printf_string("%.2f", 1.5), "1.50");
    EXPECT_EQ(printf_string("%g %g %g", 0.5, 1.0, 1e-7), "0.5 1 1e-07");
    EXPECT_EQ(printf_string("0x%02X", 7u), "0x07");
    EXPECT_EQ(printf_string("%.*g", 3, 3.14159), "3.14");
    EXPECT_EQ(printf_string("%3.0f %%", 42.0), " 42 %");
    EXPECT_EQ(printf_string("%s", ""), "");
}

TEST(Format, KeepsTextLongerThanItsBuffer) {
    const std::string long_name(200, 'x');
    EXPECT_EQ(printf_string("%s %d", long_name.c_str(), 5), long_name + " 5");
}

}  // namespace
}  // namespace phos
