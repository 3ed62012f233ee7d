// The shared per-test temporary directory, under the name the image tests use.
#pragma once

#include "test_util.h"

namespace phos::test {

using TempDir = phos::testing::TempDir;

}  // namespace phos::test
