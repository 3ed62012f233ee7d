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
#include "test_util.h"

namespace phos::io::test {

using PbrtTempDir = phos::testing::TempDir;

// A minimal valid prefix (camera, world) so tests can focus on world content.
inline const std::string kWorld = "WorldBegin\n";

// Loads `path` and checks it fails at `line`:`col` (of `file` if given) with `message` in it.
inline void expect_pbrt_error(const std::string& path, int line, int col, const std::string& message,
                              const std::string& file = "", const PbrtOptions& options = {}) {
    phos::testing::expect_parse_error_from([&] { load_pbrt(path, options); }, file, line, col, message);
}

// Quiet logging for the duration of a test, restoring it afterwards.
struct QuietLog {
    QuietLog() { log::set_quiet(true); }
    ~QuietLog() { log::set_quiet(false); }
};

}  // namespace phos::io::test
