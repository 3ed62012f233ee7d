// Render statistics reported by `phos render -v`: rays traced by kind and wall time per phase.
// Counters are atomics bumped once per tile or task (never per ray), so they cost nothing.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace phos {

struct RayCounts {
    uint64_t camera = 0, shadow = 0, bounce = 0, photon = 0;
    RayCounts& operator+=(const RayCounts& o) {
        camera += o.camera, shadow += o.shadow, bounce += o.bounce, photon += o.photon;
        return *this;
    }
};

class Stats {
public:
    void add_rays(const RayCounts& c);
    RayCounts rays() const;
    // Records `seconds` spent in `phase` (phases keep their first-seen order).
    void add_time(const std::string& phase, double seconds);
    // Free-form "name: value" lines (photon counts, bytes per photon...).
    void add_value(const std::string& name, const std::string& value);
    std::string report() const;
    // Samples an integrator dropped for being NaN or infinite outside the film (which counts its
    // own): reported by -v with the film's.
    void add_dropped_samples(uint64_t n) { dropped_.fetch_add(n, std::memory_order_relaxed); }
    uint64_t dropped_samples() const { return dropped_.load(std::memory_order_relaxed); }
    // Photons emitted by the photon-map integrators (photonmap, ppm, sppm).
    void add_photons_emitted(uint64_t n) { photons_.fetch_add(n, std::memory_order_relaxed); }
    uint64_t photons_emitted() const { return photons_.load(std::memory_order_relaxed); }

private:
    std::atomic<uint64_t> camera_{0}, shadow_{0}, bounce_{0}, photon_{0};
    std::atomic<uint64_t> dropped_{0};
    std::atomic<uint64_t> photons_{0};
    mutable std::mutex mutex_;
    std::vector<std::pair<std::string, double>> times_;
    std::vector<std::pair<std::string, std::string>> values_;
};

// Seconds of wall time since `t0` (steady clock).
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Measures the lifetime of a scope into `stats` under `phase`.
class ScopedTimer {
public:
    ScopedTimer(Stats& stats, std::string phase)
        : stats_(stats), phase_(std::move(phase)), start_(std::chrono::steady_clock::now()) {}
    ~ScopedTimer() { stats_.add_time(phase_, seconds_since(start_)); }
    ScopedTimer(const ScopedTimer&) = delete;
    ScopedTimer& operator=(const ScopedTimer&) = delete;

private:
    Stats& stats_;
    std::string phase_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace phos
