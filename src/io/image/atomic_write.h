// Crash-safe file output: write to a temporary file in the target's directory, fsync it and rename
// it over the target, so readers only ever see the old file or the complete new one.
#pragma once

#include <functional>
#include <string>

namespace phos::io {

// Calls `write(temp_path)`, which must create and fill the file at `temp_path` (any way it likes,
// by name). Then flushes it to disk and renames it to `path`. If `write` throws or any step fails,
// the temporary file is removed, the file at `path` (if any) is left untouched, and
// InputError("cannot write 'path': reason") is thrown.
void atomic_write(const std::string& path, const std::function<void(const std::string& temp_path)>& write);

}  // namespace phos::io
