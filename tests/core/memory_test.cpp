// Tests of the process-memory queries: /proc field parsing, byte formatting, and that the live
// values are plausible on Linux.
#include "core/memory.h"

#include <gtest/gtest.h>

#include <vector>

namespace phos::memory {
namespace {

TEST(Memory, ParsesProcFields) {
    const std::string status = "Name:\tphos\nVmPeak:\t  200 kB\nVmHWM:\t    1234 kB\nVmRSS:\t 1000 kB\n";
    EXPECT_EQ(kb_field(status, "VmHWM"), 1234u * 1024);
    EXPECT_EQ(kb_field(status, "VmRSS"), 1000u * 1024);
    EXPECT_FALSE(kb_field(status, "VmSwap"));
    EXPECT_FALSE(kb_field(status, "Vm"));  // a prefix of a key is not the key
    // cgroup memory.stat: "key bytes".
    const std::string stat = "cache 9150464\ninactive_file 8192\ntotal_inactive_file 146845696\n";
    EXPECT_EQ(kb_field(stat, "inactive_file"), 8192u);
    EXPECT_EQ(kb_field(stat, "total_inactive_file"), 146845696u);
}

TEST(Memory, FormatsThreeSignificantDigits) {
    EXPECT_EQ(format_bytes(0), "0 bytes");
    EXPECT_EQ(format_bytes(999), "999 bytes");
    EXPECT_EQ(format_bytes(1000), "1.00 kB");
    EXPECT_EQ(format_bytes(61'240'000), "61.2 MB");
    EXPECT_EQ(format_bytes(612'400'000), "612 MB");
    EXPECT_EQ(format_bytes(9'999'999), "10.0 MB");
    EXPECT_EQ(format_bytes(999'999'999), "1.00 GB");
    EXPECT_EQ(format_bytes(31'200'000'000), "31.2 GB");
}

#ifdef __linux__
TEST(Memory, LiveValuesArePlausible) {
    const auto rss = current_rss();
    ASSERT_TRUE(rss);
    std::vector<char> block(64 << 20, 1);  // touched: resident
    const auto peak = peak_rss();
    ASSERT_TRUE(peak);
    EXPECT_GE(*peak, *rss + (48u << 20));
    const Available a = available();
    ASSERT_TRUE(a.bytes);
    EXPECT_GT(*a.bytes, 0u);
    EXPECT_FALSE(a.limited_by.empty());
    EXPECT_EQ(block[12345], 1);
}
#endif

}  // namespace
}  // namespace phos::memory
