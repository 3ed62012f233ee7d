// Process memory from /proc and the cgroup files (see memory.h).
#include "core/memory.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#ifdef __linux__
#include <sys/mman.h>
#include <sys/resource.h>
#endif

#include "core/format.h"

namespace phos::memory {
namespace {

[[maybe_unused]] std::string read_text(const std::string& path) {
    std::ifstream f(path);
    if (!f) return {};
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

// A cgroup file holding one number ("max" or a missing file: none).
[[maybe_unused]] std::optional<uint64_t> read_number(const std::string& path) {
    const std::string t = read_text(path);
    if (t.empty() || !(t[0] >= '0' && t[0] <= '9')) return std::nullopt;
    return std::stoull(t);
}

[[maybe_unused]] std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string part;
    std::istringstream in(s);
    while (std::getline(in, part, sep)) out.push_back(part);
    return out;
}

#ifdef __linux__
// Limits of 2^60 and more are the kernel's ways of saying "unlimited" (cgroup v1: LONG_MAX
// rounded to a page).
constexpr uint64_t kUnlimited = uint64_t(1) << 60;

// A cgroup mount: its mount point and the cgroup path its root shows.
struct Mount {
    std::string root, point;
};

// The cgroup v2 mount and the v1 mount of the memory controller, from /proc/self/mountinfo.
void cgroup_mounts(std::optional<Mount>& v2, std::optional<Mount>& v1) {
    std::istringstream in(read_text("/proc/self/mountinfo"));
    std::string line;
    while (std::getline(in, line)) {
        const size_t dash = line.find(" - ");
        if (dash == std::string::npos) continue;
        std::istringstream left(line.substr(0, dash)), right(line.substr(dash + 3));
        std::string id, parent, dev, root, point, fstype, source, options;
        left >> id >> parent >> dev >> root >> point;
        right >> fstype >> source >> options;
        if (fstype == "cgroup2" && std::filesystem::exists(point + "/cgroup.controllers")) {
            const std::string controllers = read_text(point + "/cgroup.controllers");
            if (controllers.find("memory") != std::string::npos || !v2) v2 = Mount{root, point};
        } else if (fstype == "cgroup") {
            const auto opts = split(options, ',');
            if (std::find(opts.begin(), opts.end(), "memory") != opts.end()) v1 = Mount{root, point};
        }
    }
}

// The directory of cgroup `path` under mount `m`; the mount point itself when the path is not
// visible there (a container's cgroup namespace shows its own cgroup as the root).
std::filesystem::path cgroup_dir(const Mount& m, std::string path) {
    if (m.root != "/" && path.compare(0, m.root.size(), m.root) == 0) path = path.substr(m.root.size());
    const std::filesystem::path dir =
        std::filesystem::path(m.point) / std::filesystem::path(path).relative_path();
    std::error_code ec;
    return std::filesystem::is_directory(dir, ec) ? dir : std::filesystem::path(m.point);
}

// Limit minus usage, the reclaimable inactive file pages counted as free.
uint64_t headroom(uint64_t limit, uint64_t usage, uint64_t inactive_file) {
    const uint64_t used = usage > inactive_file ? usage - inactive_file : 0;
    return limit > used ? limit - used : 0;
}

// The smallest headroom of this process's cgroups (every level up to the mount point).
std::optional<uint64_t> cgroup_headroom(std::string& limited_by) {
    std::optional<Mount> v2, v1;
    cgroup_mounts(v2, v1);
    std::optional<uint64_t> best;
    const auto take = [&](uint64_t h, const char* what) {
        if (!best || h < *best) best = h, limited_by = what;
    };
    std::istringstream in(read_text("/proc/self/cgroup"));
    std::string line;
    while (std::getline(in, line)) {
        const size_t a = line.find(':'), b = line.find(':', a + 1);
        if (a == std::string::npos || b == std::string::npos) continue;
        const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
        if (controllers.empty() && v2) {
            const std::filesystem::path top(v2->point);
            for (std::filesystem::path d = cgroup_dir(*v2, path);; d = d.parent_path()) {
                const auto limit = read_number((d / "memory.max").string());
                const auto usage = read_number((d / "memory.current").string());
                if (limit && usage && *limit < kUnlimited) {
                    const auto inactive = kb_field(read_text((d / "memory.stat").string()), "inactive_file");
                    take(headroom(*limit, *usage, inactive.value_or(0)), "cgroup memory.max");
                }
                if (d == top || d == d.parent_path() || d.string().size() <= top.string().size()) break;
            }
        } else if (v1) {
            const auto names = split(controllers, ',');
            if (std::find(names.begin(), names.end(), "memory") == names.end()) continue;
            const std::filesystem::path d = cgroup_dir(*v1, path);
            const std::string stat = read_text((d / "memory.stat").string());
            auto limit = kb_field(stat, "hierarchical_memory_limit");
            if (!limit) limit = read_number((d / "memory.limit_in_bytes").string());
            const auto usage = read_number((d / "memory.usage_in_bytes").string());
            if (limit && usage && *limit < kUnlimited)
                take(headroom(*limit, *usage, kb_field(stat, "total_inactive_file").value_or(0)),
                     "cgroup memory limit");
        }
    }
    return best;
}
#endif

}  // namespace

std::optional<uint64_t> kb_field(const std::string& text, const std::string& key) {
    size_t at = 0;
    while (at < text.size()) {
        size_t end = text.find('\n', at);
        if (end == std::string::npos) end = text.size();
        if (text.compare(at, key.size(), key) == 0 && at + key.size() < end) {
            size_t i = at + key.size();
            const char c = text[i];
            if (c == ':' || c == ' ' || c == '\t') {
                while (i < end && (text[i] == ':' || text[i] == ' ' || text[i] == '\t')) ++i;
                uint64_t v = 0;
                bool digits = false;
                for (; i < end && text[i] >= '0' && text[i] <= '9'; ++i)
                    v = v * 10 + uint64_t(text[i] - '0'), digits = true;
                if (!digits) return std::nullopt;
                while (i < end && text[i] == ' ') ++i;
                return text.compare(i, 2, "kB") == 0 ? v * 1024 : v;
            }
        }
        at = end + 1;
    }
    return std::nullopt;
}

std::optional<uint64_t> peak_rss() {
#ifdef __linux__
    return kb_field(read_text("/proc/self/status"), "VmHWM");
#else
    return std::nullopt;
#endif
}

std::optional<uint64_t> current_rss() {
#ifdef __linux__
    return kb_field(read_text("/proc/self/status"), "VmRSS");
#else
    return std::nullopt;
#endif
}

void advise_huge_pages(void* begin, size_t bytes) {
#ifdef __linux__
    constexpr uintptr_t kHuge = uintptr_t(1) << 21;
    const uintptr_t lo = (reinterpret_cast<uintptr_t>(begin) + kHuge - 1) & ~(kHuge - 1);
    const uintptr_t hi = (reinterpret_cast<uintptr_t>(begin) + bytes) & ~(kHuge - 1);
    if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);  // advice: failure is harmless
#else
    (void)begin, (void)bytes;
#endif
}

Available available() {
    Available a;
#ifdef __linux__
    if (const auto m = kb_field(read_text("/proc/meminfo"), "MemAvailable"))
        a.bytes = *m, a.limited_by = "MemAvailable";
    std::string why;
    if (const auto c = cgroup_headroom(why); c && (!a.bytes || *c < *a.bytes))
        a.bytes = *c, a.limited_by = why;
    rlimit rl{};
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
        const uint64_t used = kb_field(read_text("/proc/self/status"), "VmSize").value_or(0);
        const uint64_t h = uint64_t(rl.rlim_cur) > used ? uint64_t(rl.rlim_cur) - used : 0;
        if (!a.bytes || h < *a.bytes) a.bytes = h, a.limited_by = "RLIMIT_AS";
    }
#endif
    return a;
}

std::string format_bytes(uint64_t bytes) {
    // Three significant digits; a value that rounds up to 1000 takes the next unit.
    const char* units[] = {"bytes", "kB", "MB", "GB", "TB"};
    double v = double(bytes);
    int u = 0;
    while (u < 4 && v >= 999.5) v /= 1000, ++u;
    const int decimals = u == 0 || v >= 99.95 ? 0 : v >= 9.995 ? 1 : 2;
    return printf_string("%.*f %s", decimals, v, units[u]);
}

}  // namespace phos::memory
