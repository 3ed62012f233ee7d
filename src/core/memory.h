// The process's memory: its peak and current resident size, and how much more it can get (the
// system's available memory, a cgroup limit, RLIMIT_AS). Linux reads /proc and /sys/fs/cgroup;
// elsewhere every answer is "unknown" (an empty optional).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace phos::memory {

// Peak resident set size of this process (VmHWM), in bytes.
std::optional<uint64_t> peak_rss();
// Current resident set size (VmRSS), in bytes.
std::optional<uint64_t> current_rss();

// Memory this process can still take, in bytes, and what sets it: the smallest of the system's
// MemAvailable, each enclosing cgroup's limit minus its usage (v2 memory.max - memory.current, v1
// the hierarchical limit - usage_in_bytes; reclaimable inactive file pages count as free), and
// RLIMIT_AS minus the address space in use.
struct Available {
    std::optional<uint64_t> bytes;
    std::string limited_by;  // "MemAvailable", "cgroup memory.max", "cgroup memory limit", "RLIMIT_AS"
};
Available available();

// The value of a "/proc"-style line "key:  1234 kB" (or a bare number: bytes) in `text`, in bytes.
std::optional<uint64_t> kb_field(const std::string& text, const std::string& key);

// Asks the kernel to back the 2 MiB-aligned pages inside [begin, begin + bytes) with transparent
// huge pages (Linux madvise(MADV_HUGEPAGE); elsewhere, or when refused, nothing happens). For
// large arrays about to be written whole: one fault per 2 MiB instead of one per 4 kB.
void advise_huge_pages(void* begin, size_t bytes);

// Bytes for messages, decimal units with three significant digits: "812 kB", "61.2 MB", "1.23 GB".
std::string format_bytes(uint64_t bytes);

}  // namespace phos::memory
