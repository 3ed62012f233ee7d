// printf_string: vsnprintf into a stack buffer, or into the string itself when the text is longer.
#include "core/format.h"

#include <cstdarg>
#include <cstdio>

namespace phos {

std::string printf_string(const char* fmt, ...) {
    va_list args, again;
    va_start(args, fmt);
    va_copy(again, args);
    char buf[64];
    const int n = std::vsnprintf(buf, sizeof buf, fmt, args);
    va_end(args);
    std::string s;
    if (n >= 0 && size_t(n) < sizeof buf) {
        s.assign(buf, size_t(n));
    } else if (n > 0) {
        s.resize(size_t(n));
        std::vsnprintf(s.data(), s.size() + 1, fmt, again);
    }
    va_end(again);
    return s;
}

}  // namespace phos
