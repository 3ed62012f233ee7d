// Warnings and informational messages on stderr. Warnings can be de-duplicated by key so a
// per-light or per-pixel problem is reported once, and tests can count them.
#pragma once

#include <string>

namespace phos::log {

void warn(const std::string& message);
// Prints `message` only the first time `key` is seen in this process.
void warn_once(const std::string& key, const std::string& message);
void info(const std::string& message);
void set_quiet(bool quiet);
// Silences this process for good (set_quiet(false) no longer speaks): the MPI ranks other than 0,
// whose messages rank 0 prints.
void silence();
// Number of warnings printed so far (for tests).
int warning_count();

}  // namespace phos::log
