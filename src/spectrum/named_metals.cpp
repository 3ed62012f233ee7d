// Lookups in the named metals' tables (see named_metals.h).
#include "spectrum/named_metals.h"

#include "spectrum/piecewise_linear.h"

namespace phos::spectrum {

namespace {

float interpolate(const std::vector<OpticalConstant>& t, float lambda, float OpticalConstant::*field) {
    return piecewise_linear(
        t.size(), [&](size_t i) { return t[i].lambda; }, [&](size_t i) { return t[i].*field; }, lambda);
}

}  // namespace

float NamedMetal::eta(float lambda) const { return interpolate(table, lambda, &OpticalConstant::eta); }
float NamedMetal::k(float lambda) const { return interpolate(table, lambda, &OpticalConstant::k); }

float NamedMetal::normal_reflectance(float lambda) const {
    const float n = eta(lambda), kk = k(lambda);
    return ((n - 1) * (n - 1) + kk * kk) / ((n + 1) * (n + 1) + kk * kk);
}

std::optional<NamedMetal> named_metal(const std::string& name) {
    std::string key = name;
    if (key.rfind("metal-", 0) == 0) {
        key = key.substr(6);
        for (const char* suffix : {"-eta", "-k"}) {
            const std::string s = suffix;
            if (key.size() > s.size() && key.compare(key.size() - s.size(), s.size(), s) == 0)
                key = key.substr(0, key.size() - s.size());
        }
    }
    for (const NamedMetal& m : named_metals())
        if (m.name == key) return m;
    return std::nullopt;
}

}  // namespace phos::spectrum
