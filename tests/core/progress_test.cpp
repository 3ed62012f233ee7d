// Progress reporting: the mode chosen for a render (bar on a terminal, plain lines in a log,
// nothing with -q or --no-progress), a line about every 10 % in a log, and the time-budget form
// ("sppm 12.3 s / 30 s, 41 iterations") instead of a count with a meaningless ETA.
#include "core/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace phos {
namespace {

// Runs `f` on a Progress writing to a temporary file and returns what it wrote.
template <class F>
std::string written(Progress::Mode mode, F&& f) {
    std::FILE* out = std::tmpfile();
    {
        Progress p(mode, out);
        f(p);
    }
    std::string s;
    std::rewind(out);
    for (int c; (c = std::fgetc(out)) != EOF;) s += char(c);
    std::fclose(out);
    return s;
}

std::vector<std::string> lines_of(const std::string& s) {
    std::vector<std::string> out;
    size_t start = 0;
    for (size_t i; (i = s.find('\n', start)) != std::string::npos; start = i + 1)
        out.push_back(s.substr(start, i - start));
    return out;
}

TEST(Progress, ModeForARender) {
    using M = Progress::Mode;
    EXPECT_EQ(Progress::mode_for(true, false, false), M::Bar);     // a terminal
    EXPECT_EQ(Progress::mode_for(false, false, false), M::Lines);  // a log file or a pipe
    EXPECT_EQ(Progress::mode_for(true, true, false), M::Bar);      // --progress
    EXPECT_EQ(Progress::mode_for(false, true, false), M::Off);     // --no-progress
    EXPECT_EQ(Progress::mode_for(true, false, true), M::Off);      // -q
    EXPECT_EQ(Progress::mode_for(false, false, true), M::Off);
    EXPECT_FALSE(Progress(false).enabled());
    EXPECT_TRUE(Progress(true).enabled());
}

TEST(Progress, LinesAboutEveryTenthOfACount) {
    const std::string s = written(Progress::Mode::Lines, [](Progress& p) {
        p.start("path", 200);
        for (int i = 0; i < 200; ++i) p.advance();
        p.finish();
    });
    const auto lines = lines_of(s);
    ASSERT_EQ(lines.size(), 10u) << s;  // 10 %, 20 %, ... 90 %, then the final line
    EXPECT_EQ(lines[0].rfind("path:  10 % (20 of 200), ", 0), 0u) << lines[0];
    EXPECT_EQ(lines[4].rfind("path:  50 % (100 of 200), ", 0), 0u) << lines[4];
    EXPECT_NE(lines[4].find("ETA"), std::string::npos) << lines[4];
    EXPECT_EQ(lines[9].rfind("path: 100 % (200 of 200), took ", 0), 0u) << lines[9];
    EXPECT_EQ(s.find('\r'), std::string::npos);  // no bar drawing in a log
}

TEST(Progress, LinesFromManyThreads) {
    const std::string s = written(Progress::Mode::Lines, [](Progress& p) {
        p.start("tiles", 1000);
        std::vector<std::thread> threads;
        for (int t = 0; t < 4; ++t)
            threads.emplace_back([&] {
                for (int i = 0; i < 250; ++i) p.advance();
            });
        for (auto& t : threads) t.join();
        p.finish();
    });
    const auto lines = lines_of(s);
    EXPECT_GE(lines.size(), 2u) << s;
    EXPECT_LE(lines.size(), 10u) << s;
    EXPECT_EQ(lines.back().rfind("tiles: 100 % (1000 of 1000)", 0), 0u) << s;
}

TEST(Progress, TimeBudgetShowsElapsedBudgetAndIterations) {
    const auto since = Progress::Clock::now() - std::chrono::milliseconds(12300);
    const std::string s = written(Progress::Mode::Lines, [&](Progress& p) {
        p.start_timed("sppm", 30, since);  // 41 % of the budget already spent
        for (int i = 0; i < 41; ++i) p.advance();
        p.finish();
    });
    const auto lines = lines_of(s);
    ASSERT_EQ(lines.size(), 2u) << s;  // the 40 % line at the first iteration, then the end
    // Elapsed is 12.3 s and a little more (how long the test took to get there).
    EXPECT_EQ(lines[0].rfind("sppm: 12.", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find(" s / 30 s, 1 iterations"), std::string::npos) << lines[0];
    EXPECT_NE(lines[1].find(" s / 30 s, 41 iterations, done"), std::string::npos) << lines[1];
    EXPECT_EQ(s.find("ETA"), std::string::npos) << s;
    EXPECT_EQ(s.find('%'), std::string::npos) << s;  // no "0 %" of a sentinel count

    const std::string counted = written(Progress::Mode::Lines, [&](Progress& p) {
        p.start_timed("ppm", 30, since, 100);
        for (int i = 0; i < 5; ++i) p.advance();
        p.finish();
    });
    EXPECT_NE(counted.find(" s / 30 s, 5 of 100 iterations, done"), std::string::npos) << counted;
}

TEST(Progress, BarOnATerminal) {
    const auto since = Progress::Clock::now() - std::chrono::seconds(15);
    const std::string s = written(Progress::Mode::Bar, [&](Progress& p) {
        p.start_timed("sppm", 30, since);
        p.advance();
        p.finish();
    });
    EXPECT_NE(s.find("\rsppm ["), std::string::npos) << s;
    EXPECT_NE(s.find(" / 30 s, 1 iterations, done"), std::string::npos) << s;
    EXPECT_EQ(s.back(), '\n');
}

TEST(Progress, OffWritesNothing) {
    const std::string s = written(Progress::Mode::Off, [](Progress& p) {
        p.start("path", 10);
        for (int i = 0; i < 10; ++i) p.advance();
        p.finish();
        p.start_timed("sppm", 1, Progress::Clock::now());
        p.advance();
        p.finish();
    });
    EXPECT_EQ(s, "");
}

}  // namespace
}  // namespace phos
