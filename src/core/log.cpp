// Implementation of the stderr logger; a mutex keeps lines from interleaving across threads.
#include "core/log.h"

#include <cstdio>
#include <mutex>
#include <set>

namespace phos::log {
namespace {
std::mutex g_mutex;
std::set<std::string> g_seen;
bool g_quiet = false;
bool g_silenced = false;
int g_warnings = 0;
}  // namespace

void warn(const std::string& message) {
    std::lock_guard lock(g_mutex);
    ++g_warnings;
    if (!g_quiet) std::fprintf(stderr, "warning: %s\n", message.c_str());
}

void warn_once(const std::string& key, const std::string& message) {
    {
        std::lock_guard lock(g_mutex);
        if (!g_seen.insert(key).second) return;
    }
    warn(message);
}

void info(const std::string& message) {
    std::lock_guard lock(g_mutex);
    if (!g_quiet) std::fprintf(stderr, "%s\n", message.c_str());
}

void set_quiet(bool quiet) {
    std::lock_guard lock(g_mutex);
    g_quiet = quiet || g_silenced;
}

void silence() {
    std::lock_guard lock(g_mutex);
    g_silenced = g_quiet = true;
}

int warning_count() {
    std::lock_guard lock(g_mutex);
    return g_warnings;
}

}  // namespace phos::log
