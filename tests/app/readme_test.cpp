// The README's examples run exactly as written from a fresh clone (after the build): every
// indented `build/phos ...` line is run in a directory laid out like the repository (scenes/,
// build/phos, out/) and must exit 0 and write what it names.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_util.h"

namespace phos::testing {
namespace {

TEST(Readme, ExamplesRunAsWritten) {
    std::ifstream f(std::string(PHOS_SOURCE_DIR) + "/README.md");
    ASSERT_TRUE(f) << "README.md";
    std::vector<std::string> commands;
    for (std::string line; std::getline(f, line);)
        if (line.rfind("    build/phos ", 0) == 0) commands.push_back(line.substr(4));
    ASSERT_GE(commands.size(), 5u);

    TempDir dir;
    namespace fs = std::filesystem;
    fs::create_directory_symlink(fs::path(PHOS_SOURCE_DIR) / "scenes", dir.path() / "scenes");
    fs::create_directories(dir.path() / "build");
    fs::create_symlink(fs::path(PHOS_BINARY), dir.path() / "build" / "phos");
    fs::create_directories(dir.path() / "out");
    for (const std::string& c : commands) {
        const std::string cmd = "cd '" + dir.path().string() + "' && " + c + " > cmd.log 2>&1";
        const int status = std::system(cmd.c_str());
        std::ifstream log(dir.file("cmd.log"));
        std::stringstream text;
        text << log.rdbuf();
        EXPECT_EQ(status, 0) << c << "\n" << text.str();
        const size_t o = c.find(" -o ");
        if (o != std::string::npos) {
            const std::string out = c.substr(o + 4, c.find(' ', o + 4) - o - 4);
            EXPECT_TRUE(fs::exists(dir.path() / out)) << c;
        }
    }
    EXPECT_TRUE(fs::exists(dir.path() / "out/cornell.direct.exr"));
    EXPECT_TRUE(fs::exists(dir.path() / "out/cornell.albedo.exr"));
}

}  // namespace
}  // namespace phos::testing
