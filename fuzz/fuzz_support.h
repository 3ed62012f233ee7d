// Shared by the libFuzzer harnesses in fuzz/: a per-process scratch directory on tmpfs where each
// input is written as one or more files (the readers take paths), small valid fixture files the
// inputs can name (meshes, images, an include), and the one rule for which exceptions are expected.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/log.h"
#include "scene/shape.h"

namespace phos::fuzz {

namespace fs = std::filesystem;

// The input split into files: the bytes before the first separator line are the main file; each
// line "#@file NAME" starts another file called NAME (letters, digits, '.', '_', '-'; at most 32
// characters; no leading '.'), so one input can hold a scene and the files it includes or names.
struct InputFiles {
    std::string main;
    std::vector<std::pair<std::string, std::string>> extra;
};

inline bool valid_name(const std::string& n) {
    if (n.empty() || n.size() > 32 || n[0] == '.') return false;
    for (char c : n)
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
              c == '_' || c == '-'))
            return false;
    return true;
}

inline InputFiles split_input(const uint8_t* data, size_t size) {
    static const std::string kSep = "#@file ";
    const std::string all(reinterpret_cast<const char*>(data), size);
    InputFiles out;
    std::string* current = &out.main;
    size_t pos = 0;
    while (pos < all.size()) {
        size_t eol = all.find('\n', pos);
        const size_t next = eol == std::string::npos ? all.size() : eol + 1;
        if (eol == std::string::npos) eol = all.size();
        if (all.compare(pos, kSep.size(), kSep) == 0) {
            const std::string name = all.substr(pos + kSep.size(), eol - pos - kSep.size());
            if (valid_name(name)) {
                out.extra.emplace_back(name, std::string());
                current = &out.extra.back().second;
                pos = next;
                continue;
            }
        }
        current->append(all, pos, next - pos);
        pos = next;
    }
    return out;
}

// A directory of its own for this process (several fuzzers may run at once), emptied and refilled
// with the fixtures before every input so that each run sees exactly its own files.
class Scratch {
public:
    Scratch() {
        const char* shm = "/dev/shm";
        const fs::path base = fs::is_directory(shm) ? fs::path(shm) : fs::temp_directory_path();
        dir_ = base / ("phos-fuzz-" + std::to_string(::getpid()));
        // A run that crashed or timed out leaves its directory behind: remove those of processes
        // that no longer exist.
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(base, ec)) {
            const std::string name = entry.path().filename().string();
            if (name.rfind("phos-fuzz-", 0) == 0 && !fs::exists("/proc/" + name.substr(10), ec))
                fs::remove_all(entry.path(), ec);
        }
        fs::create_directories(dir_);
        // Readers may warn on every input; the fuzzer's output should show only its own lines.
        log::set_quiet(true);
        std::atexit([] { instance_dir_cleanup(); });
        cleanup_dir() = dir_;
    }
    const fs::path& dir() const { return dir_; }

    // Leaves the directory holding exactly `fixtures`, then `files` (a later name replaces an
    // earlier one); returns the path of the file named `main_name`, holding `main`. Only what the
    // previous input wrote is removed and only the fixtures it replaced are rewritten (readers
    // never write), which keeps the per-input cost low.
    std::string prepare(const std::vector<std::pair<std::string, std::string>>& fixtures,
                        const InputFiles& files, const std::string& main_name) {
        std::error_code ec;
        for (const std::string& name : written_) fs::remove(dir_ / name, ec);
        for (const auto& [name, bytes] : fixtures)
            if (!fixtures_written_ || std::find(written_.begin(), written_.end(), name) != written_.end())
                write(name, bytes);
        fixtures_written_ = true;
        written_.clear();
        for (const auto& [name, bytes] : files.extra) {
            write(name, bytes);
            written_.push_back(name);
        }
        written_.push_back(main_name);
        return write(main_name, files.main);
    }

    std::string write(const std::string& name, const std::string& bytes) const {
        const fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
        return p.string();
    }

private:
    static fs::path& cleanup_dir() {
        static fs::path d;
        return d;
    }
    static void instance_dir_cleanup() {
        std::error_code ec;
        if (!cleanup_dir().empty()) fs::remove_all(cleanup_dir(), ec);
    }
    fs::path dir_;
    std::vector<std::string> written_;  // by the previous input
    bool fixtures_written_ = false;
};

// Runs `read`: a reader may reject the input only with phos's own ParseError or InputError. Any
// other exception escapes to libFuzzer, which reports it (with the input) as a crash. With
// PHOS_FUZZ_VERBOSE set, prints how each input ended (for checking seeds and triaging).
template <class F>
void expect_reader_errors(F&& read) {
    static const bool verbose = std::getenv("PHOS_FUZZ_VERBOSE") != nullptr;
    try {
        read();
        if (verbose) std::fprintf(stderr, "phos fuzz: accepted\n");
    } catch (const ParseError& e) {
        if (verbose) std::fprintf(stderr, "phos fuzz: ParseError: %s\n", e.what());
    } catch (const InputError& e) {
        if (verbose) std::fprintf(stderr, "phos fuzz: InputError: %s\n", e.what());
    }
}

// Aborts with a message (libFuzzer then saves the input): a broken invariant of a successful read.
[[noreturn]] inline void invariant_failed(const char* what) {
    std::fprintf(stderr, "phos fuzz: invariant violated: %s\n", what);
    std::abort();
}

// What every caller of a mesh reader relies on: indices in range, whole triangles, normals and uvs
// absent or one per vertex.
inline void check_mesh(const scene::TriangleMesh& m) {
    for (uint32_t i : m.indices)
        if (i >= m.positions.size()) invariant_failed("index out of range");
    if (m.indices.size() % 3 != 0) invariant_failed("partial triangle");
    if (!m.normals.empty() && m.normals.size() != m.positions.size()) invariant_failed("normal count");
    if (!m.uvs.empty() && m.uvs.size() != m.positions.size()) invariant_failed("uv count");
}

// ---- fixtures: small valid files an input may name ----

inline std::string fixture_off() { return "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"; }

inline std::string fixture_ply() {
    return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
           "property float z\nproperty float u\nproperty float v\nelement face 1\n"
           "property list uchar int vertex_indices\nend_header\n"
           "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n4 0 1 2 3\n";
}

inline std::string fixture_obj() {
    return "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n"
           "usemtl red\nf 1/1/1 2/2/1 3/3/1\n";
}

inline std::string fixture_mtl() { return "newmtl red\nKd 1 0 0\n"; }

// A 2x2 little-endian RGB PFM.
inline std::string fixture_pfm() {
    std::string s = "PF\n2 2\n-1.0\n";
    const float v[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    s.append(reinterpret_cast<const char*>(v), sizeof v);
    return s;
}

// A 2x2 24-bit uncompressed BMP (rows padded to 4 bytes).
inline std::string fixture_bmp() {
    const unsigned char header[54] = {'B', 'M', 70, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0, 40, 0, 0,  0,
                                      2,   0,   0,  0, 2, 0, 0, 0, 1, 0, 24, 0, 0, 0, 0,  0, 16, 0,
                                      0,   0,   0,  0, 0, 0, 0, 0, 0, 0, 0,  0, 0, 0, 0,  0, 0,  0};
    std::string s(reinterpret_cast<const char*>(header), sizeof header);
    const unsigned char px[16] = {0, 0, 255, 0, 255, 0, 0, 0, 255, 0, 0, 255, 255, 255, 0, 0};
    s.append(reinterpret_cast<const char*>(px), sizeof px);
    return s;
}

}  // namespace phos::fuzz
