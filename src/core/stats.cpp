// Statistics accumulation and the `-v` report text.
#include "core/stats.h"

#include "core/format.h"

namespace phos {

void Stats::add_rays(const RayCounts& c) {
    camera_.fetch_add(c.camera, std::memory_order_relaxed);
    shadow_.fetch_add(c.shadow, std::memory_order_relaxed);
    bounce_.fetch_add(c.bounce, std::memory_order_relaxed);
    photon_.fetch_add(c.photon, std::memory_order_relaxed);
}

RayCounts Stats::rays() const { return {camera_.load(), shadow_.load(), bounce_.load(), photon_.load()}; }

void Stats::add_time(const std::string& phase, double seconds) {
    std::lock_guard lock(mutex_);
    for (auto& [name, t] : times_)
        if (name == phase) {
            t += seconds;
            return;
        }
    times_.emplace_back(phase, seconds);
}

void Stats::add_value(const std::string& name, const std::string& value) {
    std::lock_guard lock(mutex_);
    values_.emplace_back(name, value);
}

std::string Stats::report() const {
    std::lock_guard lock(mutex_);
    std::string s;
    const RayCounts r = rays();
    const uint64_t total = r.camera + r.shadow + r.bounce + r.photon;
    double render_time = 0;
    s += "statistics:\n";
    s += printf_string("  rays: %llu camera, %llu shadow, %llu bounce, %llu photon (%llu total)\n",
                       (unsigned long long)r.camera, (unsigned long long)r.shadow,
                       (unsigned long long)r.bounce, (unsigned long long)r.photon, (unsigned long long)total);
    for (const auto& [name, t] : times_) {
        s += printf_string("  time %-18s %9.3f s\n", (name + ":").c_str(), t);
        if (name == "render") render_time = t;
    }
    if (render_time > 0) {
        s += printf_string("  rays per second (render): %.3g M\n",
                           double(r.camera + r.shadow + r.bounce) / render_time * 1e-6);
    }
    for (const auto& [name, v] : values_) s += "  " + name + ": " + v + "\n";
    return s;
}

}  // namespace phos
