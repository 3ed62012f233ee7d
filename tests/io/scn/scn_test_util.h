// Helpers for the .scn loader tests: a scratch directory that files are written into, and a check
// that loading throws a ParseError at an exact file, line and column.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/scn/scn_loader.h"

namespace phos::io::test {

// A fresh directory under the system temp dir, removed (with its contents) on destruction.
class TempDir {
public:
    TempDir() {
        std::string pattern = (std::filesystem::temp_directory_path() / "phos_scn_XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        path_ = pattern;
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    // Writes `content` (bytes as given) to `name` (may contain sub-directories); returns its path.
    std::string write(const std::string& name, const std::string& content) const {
        const std::filesystem::path p = path_ / name;
        std::filesystem::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << content;
        return p.string();
    }
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

// Loads `path` and checks it fails at `file`:`line`:`col` with a message containing `message`.
inline void expect_parse_error(const std::string& path, const std::string& file, int line, int col,
                               const std::string& message, const ScnOptions& options = {}) {
    try {
        load_scn(path, options);
        ADD_FAILURE() << "expected a ParseError (" << message << ")";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, file) << e.what();
        EXPECT_EQ(e.line, line) << e.what();
        EXPECT_EQ(e.column, col) << e.what();
        EXPECT_NE(e.message.find(message), std::string::npos) << "message: " << e.message;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected a ParseError, got: " << e.what();
    }
}

}  // namespace phos::io::test
