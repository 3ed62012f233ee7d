// Helpers for the pbrt loader tests: a scratch directory for scene files and a check that loading
// throws a ParseError at an exact file, line and column.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/log.h"
#include "io/pbrt/pbrt_loader.h"

namespace phos::io::test {

class PbrtTempDir {
public:
    PbrtTempDir() {
        std::string pattern = (std::filesystem::temp_directory_path() / "phos_pbrt_XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        path_ = pattern;
    }
    ~PbrtTempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    PbrtTempDir(const PbrtTempDir&) = delete;
    PbrtTempDir& operator=(const PbrtTempDir&) = delete;

    std::string write(const std::string& name, const std::string& content) const {
        const std::filesystem::path p = path_ / name;
        std::filesystem::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << content;
        return p.string();
    }

private:
    std::filesystem::path path_;
};

// A minimal valid prefix (camera, world) so tests can focus on world content.
inline const std::string kWorld = "WorldBegin\n";

// Loads `path` and checks it fails at `line`:`col` (of `file` if given) with `message` in it.
inline void expect_pbrt_error(const std::string& path, int line, int col, const std::string& message,
                              const std::string& file = "", const PbrtOptions& options = {}) {
    try {
        load_pbrt(path, options);
        ADD_FAILURE() << "expected a ParseError (" << message << ") for " << path;
    } catch (const ParseError& e) {
        if (!file.empty()) {
            EXPECT_EQ(e.file, file) << e.what();
        }
        EXPECT_EQ(e.line, line) << e.what();
        EXPECT_EQ(e.column, col) << e.what();
        EXPECT_NE(e.message.find(message), std::string::npos) << "message: " << e.message;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected a ParseError, got: " << e.what();
    }
}

// Quiet logging for the duration of a test, restoring it afterwards.
struct QuietLog {
    QuietLog() { log::set_quiet(true); }
    ~QuietLog() { log::set_quiet(false); }
};

}  // namespace phos::io::test
