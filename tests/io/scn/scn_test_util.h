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
#include "test_util.h"

namespace phos::io::test {

using TempDir = phos::testing::TempDir;

// Loads `path` and checks it fails at `file`:`line`:`col` with a message containing `message`.
inline void expect_parse_error(const std::string& path, const std::string& file, int line, int col,
                               const std::string& message, const ScnOptions& options = {}) {
    phos::testing::expect_parse_error_from([&] { load_scn(path, options); }, file, line, col, message);
}

}  // namespace phos::io::test
