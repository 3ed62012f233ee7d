// A thread-safe progress bar with ETA on stderr, drawn only when stderr is a terminal (or when
// forced), and at most a few times per second so it never slows rendering down.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace phos {

class Progress {
public:
    Progress() = default;
    // Enabled by default only when stderr is a terminal.
    explicit Progress(bool enabled) : enabled_(enabled) {}
    static bool stderr_is_terminal();

    // Starts a new phase with `total` work units (0 = indeterminate).
    void start(const std::string& label, uint64_t total);
    void advance(uint64_t units = 1);
    // Ends the phase (clears the line).
    void finish();
    bool enabled() const { return enabled_; }

private:
    void draw(uint64_t done, bool final);

    bool enabled_ = false;
    std::string label_;
    uint64_t total_ = 0;
    std::atomic<uint64_t> done_{0};
    std::atomic<int64_t> last_draw_ns_{0};
    std::chrono::steady_clock::time_point start_;
    std::mutex draw_mutex_;
};

}  // namespace phos
