// Checks Embree device configurations (see device_config.h).
#include "accel/device_config.h"

#include <algorithm>
#include <array>
#include <set>
#include <sstream>
#include <utility>

namespace phos::accel {
namespace {

constexpr std::array<const char*, 5> kIsas = {"sse2", "sse4.2", "avx", "avx2", "avx512"};

// Whether this CPU runs Embree's kernels for `isa` (what Embree itself asks of it).
bool cpu_runs(const std::string& isa) {
    if (isa == "sse2") return __builtin_cpu_supports("sse2");
    if (isa == "sse4.2") return __builtin_cpu_supports("sse4.2");
    if (isa == "avx") return __builtin_cpu_supports("avx");
    if (isa == "avx2")
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
               __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512vl");
}

std::string one_of(const std::string& key, const std::string& value, const std::string& values) {
    return key + "=" + value + ": " + key + " is one of " + values;
}

std::string entry_error(const std::string& key, const std::string& value) {
    if (key == "isa" || key == "max_isa") {
        if (std::find(kIsas.begin(), kIsas.end(), value) == kIsas.end())
            return one_of(key, value, "sse2, sse4.2, avx, avx2, avx512");
        if (!cpu_runs(value))
            return key + "=" + value + ": this CPU does not run Embree's " + value + " kernels";
        return "";
    }
    if (key == "frequency_level")
        return value == "simd128" || value == "simd256" || value == "simd512"
                   ? ""
                   : one_of(key, value, "simd128, simd256, simd512");
    if (key == "hugepages") return value == "0" || value == "1" ? "" : one_of(key, value, "0, 1");
    if (key == "verbose")
        return value.size() == 1 && value[0] >= '0' && value[0] <= '3' ? ""
                                                                       : one_of(key, value, "0, 1, 2, 3");
    if (key == "threads" || key == "user_threads" || key == "start_threads" || key == "set_affinity")
        return key + ": phos runs Embree on its own threads (--threads sets how many)";
    return "unknown key '" + key + "' (isa, max_isa, frequency_level, hugepages, verbose)";
}

}  // namespace

std::string embree_config_error(const std::string& config) {
    std::set<std::string> seen;
    std::istringstream in(config);
    std::string entry;
    while (std::getline(in, entry, ',')) {
        const size_t eq = entry.find('=');
        if (entry.empty() || eq == std::string::npos || eq == 0 || eq + 1 == entry.size())
            return "'" + entry + "' is not key=value";
        const std::string key = entry.substr(0, eq), value = entry.substr(eq + 1);
        if (!seen.insert(key).second) return key + " is given twice";
        if (std::string e = entry_error(key, value); !e.empty()) return e;
    }
    if (!config.empty() && config.back() == ',') return "'" + config + "' ends with a comma";
    return "";
}

}  // namespace phos::accel
