// Progress reporting: the bar ("label [=====>    ]  42%  ETA 12s", redrawn with a carriage
// return), the plain lines for logs, and the count- or time-bounded description both share.
#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "core/format.h"

namespace phos {
namespace {

constexpr double kLineEverySeconds = 10;  // Lines, indeterminate phase: one line per 10 s

}  // namespace

bool Progress::stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

Progress::Mode Progress::mode_for(bool bar, bool given, bool quiet) {
    if (quiet) return Mode::Off;
    if (bar) return Mode::Bar;
    return given ? Mode::Off : Mode::Lines;
}

void Progress::begin(const std::string& label, uint64_t total, double budget, Clock::time_point since,
                     const std::string& unit) {
    {
        std::lock_guard lock(draw_mutex_);
        label_ = label;
        unit_ = unit;
        total_ = total;
        budget_ = std::max(budget, 0.0);
        done_ = 0;
        last_draw_ns_ = 0;
        last_step_ = 0;
        start_ = std::min(since, Clock::now());
    }
    if (mode_ == Mode::Bar) draw(0, false);
}

Progress::Snapshot Progress::snapshot() const {
    std::lock_guard lock(draw_mutex_);
    Snapshot s;
    s.label = label_;
    if (!label_.empty())
        s.fraction = std::min(1.0, fraction(done_.load(std::memory_order_relaxed), elapsed()));
    return s;
}

void Progress::start(const std::string& label, uint64_t total) { begin(label, total, 0, Clock::now(), ""); }

void Progress::start_timed(const std::string& label, double budget, Clock::time_point since, uint64_t total,
                           const std::string& unit) {
    begin(label, total, budget, since, unit);
}

double Progress::elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

double Progress::fraction(uint64_t done, double elapsed) const {
    double f = -1;
    if (total_ > 0) f = double(done) / double(total_);
    if (budget_ > 0) f = std::max(f, elapsed / budget_);
    return f < 0 ? f : std::min(f, 1.0);
}

void Progress::advance(uint64_t units) {
    const uint64_t done = done_.fetch_add(units, std::memory_order_relaxed) + units;
    if (mode_ == Mode::Off) return;
    const double t = elapsed();
    if (mode_ == Mode::Lines) {
        // A line each time the phase crosses another tenth (or, indeterminate, another 10 s).
        const double f = fraction(done, t);
        const int step = f >= 0 ? int(std::floor(f * 10)) : int(t / kLineEverySeconds);
        int last = last_step_.load(std::memory_order_relaxed);
        if (step <= last || (f >= 0 && step >= 10)) return;  // 100 %: finish() says so
        if (!last_step_.compare_exchange_strong(last, step)) return;
        draw(done, false);
        return;
    }
    const auto now = int64_t(t * 1e9);
    int64_t last = last_draw_ns_.load(std::memory_order_relaxed);
    if (now - last < 200'000'000) return;  // 5 redraws per second at most
    if (!last_draw_ns_.compare_exchange_strong(last, now)) return;
    draw(done, false);
}

void Progress::finish() {
    if (mode_ == Mode::Off) return;
    draw(done_.load(), true);
}

std::string Progress::describe(uint64_t done, double t, bool final) const {
    const std::string count = std::to_string(done);
    if (budget_ > 0) {
        // "12.3 s / 30 s, 41 iterations" or "..., 41 of 100 iterations".
        std::string s = printf_string("%.1f s / %g s, ", t, budget_) + count;
        if (total_ > 0) s += " of " + std::to_string(total_);
        return s + (unit_.empty() ? "" : " " + unit_) + (final ? ", done" : "");
    }
    if (total_ == 0)
        return count + (unit_.empty() ? "" : " " + unit_) + printf_string(", %.1f s", t) +
               (final ? ", done" : "");
    const double f = fraction(done, t);
    std::string s = printf_string("%3.0f %%", std::floor(f * 100)) + " (" + count + " of " +
                    std::to_string(total_) + (unit_.empty() ? "" : " " + unit_) + ")";
    if (final) return s + printf_string(", took %.1f s", t);
    s += printf_string(", %.1f s", t);
    if (f > 0) s += printf_string(", ETA %.0f s", t * (1 - f) / f);
    return s;
}

void Progress::draw(uint64_t done, bool final) {
    std::lock_guard lock(draw_mutex_);
    const double t = elapsed();
    const std::string text = describe(done, t, final);
    if (mode_ == Mode::Lines) {
        std::fprintf(out_, "%s: %s\n", label_.c_str(), text.c_str());
    } else {
        const double f = fraction(final && budget_ == 0 && total_ > 0 ? total_ : done, t);
        if (f < 0) {
            std::fprintf(out_, "\r%s %s   ", label_.c_str(), text.c_str());
        } else {
            constexpr int kWidth = 30;
            const int filled = int((final ? 1.0 : f) * kWidth);
            char bar[kWidth + 1];
            for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '=' : (i == filled ? '>' : ' ');
            bar[kWidth] = 0;
            std::fprintf(out_, "\r%s [%s] %s   ", label_.c_str(), bar, text.c_str());
        }
        if (final) std::fprintf(out_, "\n");
    }
    std::fflush(out_);
}

}  // namespace phos
