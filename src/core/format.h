// printf-style formatting into a std::string, for the numbers in messages, reports and titles.
#pragma once

#include <string>

namespace phos {

// The text std::snprintf writes for `fmt` and the arguments, of any length:
// printf_string("%.2f s", 1.5) == "1.50 s". The compiler checks the arguments against `fmt`.
std::string printf_string(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace phos
