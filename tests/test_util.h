// Helpers shared by end-to-end tests: run the phos binary, temporary directories, file bytes.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/vec.h"

namespace phos::testing {

struct CommandResult {
    int exit_code = -1;
    std::string output;  // stdout and stderr together
};

// Runs `phos ARGS` through the shell, capturing its output; `env` ("NAME=value ...") is set for
// it alone.
inline CommandResult run_phos_env(const std::string& env, const std::string& args) {
    const std::string cmd = "env " + env + " " + std::string(PHOS_BINARY) + " " + args + " 2>&1";
    CommandResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// Runs `phos ARGS` through the shell, capturing its output.
inline CommandResult run_phos(const std::string& args) { return run_phos_env("", args); }

// A fresh directory (mkdtemp) under the system temp dir, removed with its contents at the end
// of the test. Shared by every test folder.
class TempDir {
public:
    TempDir() {
        std::string pattern = (std::filesystem::temp_directory_path() / "phos-test-XXXXXX").string();
        if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        path_ = pattern;
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    bool ok() const { return !path_.empty(); }
    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    // Writes `text` (bytes as given) to `name`, which may contain sub-directories; returns its path.
    std::string write(const std::string& name, const std::string& text) const {
        const std::filesystem::path p = path_ / name;
        std::filesystem::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << text;
        return p.string();
    }

private:
    std::filesystem::path path_;
};

// Runs `load` and checks it throws a ParseError at `file` (any file if empty), `line`, `col`, with
// `message` in its text.
template <class Load>
void expect_parse_error_from(Load&& load, const std::string& file, int line, int col,
                             const std::string& message) {
    try {
        load();
        ADD_FAILURE() << "expected a ParseError (" << message << ")";
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

// A PFM image (linear RGB floats) of w x h pixels listed top row first (PFM stores the bottom row
// first): the small images the image-light and texture tests write.
inline std::string pfm_bytes(int w, int h, const std::vector<Rgb>& top_first) {
    std::string s = "PF\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1\n";
    for (int y = h - 1; y >= 0; --y)
        for (int x = 0; x < w; ++x) {
            const Rgb c = top_first[size_t(y * w + x)];
            const float v[3] = {c.r, c.g, c.b};
            s.append(reinterpret_cast<const char*>(v), sizeof v);
        }
    return s;
}

inline std::string read_bytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

inline std::string shared_path(const std::string& rel) { return std::string(PHOS_SHARED_DIR) + "/" + rel; }
inline std::string source_path(const std::string& rel) { return std::string(PHOS_SOURCE_DIR) + "/" + rel; }

}  // namespace phos::testing
