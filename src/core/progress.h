// Render progress on stderr: a bar redrawn in place when stderr is a terminal (at most five times
// a second, so it never slows rendering down), a plain line about every 10 % when it is not (CI
// logs, `2> log`), nothing with -q. A phase is bounded by a count of work units (tiles,
// iterations: "42 %, ETA 12 s") or by a time budget ("sppm 12.3 s / 30 s, 41 iterations").
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

namespace phos {

class Progress {
public:
    enum class Mode {
        Off,    // nothing
        Bar,    // a bar redrawn in place (a terminal)
        Lines,  // a plain line about every 10 % of the phase (a log file)
    };
    using Clock = std::chrono::steady_clock;

    Progress() = default;
    // Bar when enabled, else Off.
    explicit Progress(bool enabled) : mode_(enabled ? Mode::Bar : Mode::Off) {}
    // `out` is where it writes (stderr; tests pass a temporary file).
    explicit Progress(Mode mode, std::FILE* out = stderr) : mode_(mode), out_(out) {}
    static bool stderr_is_terminal();
    // The mode for a render: Off with -q (`quiet`) or when the bar was turned off on the command
    // line (`given` and not `bar`); Bar when `bar` (forced, or stderr is a terminal); Lines
    // otherwise (stderr is a file or a pipe).
    static Mode mode_for(bool bar, bool given, bool quiet);

    // Starts a phase with `total` work units (0 = indeterminate; Lines: a line every 10 s).
    void start(const std::string& label, uint64_t total);
    // Starts a phase bounded by time: `budget` seconds counted from `since` (which may lie before
    // now: a budget for the whole command). advance() counts `unit`s done; `total` > 0 is a count
    // bound as well ("41 of 100 iterations"). Lines: one about every 10 % of the budget.
    void start_timed(const std::string& label, double budget, Clock::time_point since, uint64_t total = 0,
                     const std::string& unit = "iterations");
    // Thread-safe.
    void advance(uint64_t units = 1);
    // Ends the phase (Bar: completes the line; Lines: a final line).
    void finish();
    bool enabled() const { return mode_ != Mode::Off; }

    // Where the current phase stands, readable from any thread while the render runs (the Python
    // module's progress callback polls it): its label and the fraction done (< 0: unknown).
    struct Snapshot {
        std::string label;
        double fraction = -1;
    };
    Snapshot snapshot() const;
    Mode mode() const { return mode_; }

private:
    void begin(const std::string& label, uint64_t total, double budget, Clock::time_point since,
               const std::string& unit);
    double elapsed() const;
    // The fraction of the phase done: by count, by time, or the larger of the two; < 0: unknown.
    double fraction(uint64_t done, double elapsed) const;
    std::string describe(uint64_t done, double elapsed, bool final) const;
    void draw(uint64_t done, bool final);

    Mode mode_ = Mode::Off;
    std::FILE* out_ = stderr;
    std::string label_;
    std::string unit_;
    uint64_t total_ = 0;
    double budget_ = 0;  // seconds; 0: a count-bounded phase
    std::atomic<uint64_t> done_{0};
    std::atomic<int64_t> last_draw_ns_{0};
    std::atomic<int> last_step_{0};  // Lines: the last tenth (or 10 s step) reported
    Clock::time_point start_;
    mutable std::mutex draw_mutex_;  // guards the output and label_, unit_, total_, budget_, start_
};

}  // namespace phos
