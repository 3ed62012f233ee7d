// Progress bar drawing: "label [=====>    ] 42%  ETA 12s" redrawn in place with a carriage return.
#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace phos {

bool Progress::stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

void Progress::start(const std::string& label, uint64_t total) {
    label_ = label;
    total_ = total;
    done_ = 0;
    last_draw_ns_ = 0;
    start_ = std::chrono::steady_clock::now();
    if (enabled_) draw(0, false);
}

void Progress::advance(uint64_t units) {
    const uint64_t done = done_.fetch_add(units, std::memory_order_relaxed) + units;
    if (!enabled_) return;
    const int64_t now =
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_)
            .count();
    int64_t last = last_draw_ns_.load(std::memory_order_relaxed);
    if (now - last < 200'000'000) return;  // 5 redraws per second at most
    if (!last_draw_ns_.compare_exchange_strong(last, now)) return;
    draw(done, false);
}

void Progress::finish() {
    if (!enabled_) return;
    draw(total_ ? total_ : done_.load(), true);
}

void Progress::draw(uint64_t done, bool final) {
    std::lock_guard lock(draw_mutex_);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    constexpr int kWidth = 30;
    if (total_ == 0) {
        std::fprintf(stderr, "\r%s %llu  %.1fs   ", label_.c_str(), (unsigned long long)done, elapsed);
    } else {
        const double f = std::min(1.0, double(done) / double(total_));
        const int filled = int(f * kWidth);
        char bar[kWidth + 1];
        for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '=' : (i == filled ? '>' : ' ');
        bar[kWidth] = 0;
        const double eta = f > 0 ? elapsed * (1 - f) / f : 0;
        std::fprintf(stderr, "\r%s [%s] %3d%%  %s %.0fs   ", label_.c_str(), bar, int(f * 100),
                     final ? "took" : "ETA", final ? elapsed : eta);
    }
    if (final) std::fprintf(stderr, "\n");
    std::fflush(stderr);
}

}  // namespace phos
