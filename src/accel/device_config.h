// Embree device configurations (rtcNewDevice's "key=value,key=value" string, --embree-config),
// checked before use: Embree ignores keys and values it does not know, so a typo would silently
// leave its defaults in place. Kernels of different widths (`isa`, `max_isa`) can differ in a
// hit's last bits, and so in the image: a fixed isa takes that difference between machines away.
#pragma once

#include <string>

namespace phos::accel {

// Why `config` cannot be used (empty: it can). Accepted, comma-separated: isa=I and max_isa=I (I:
// sse2, sse4.2, avx, avx2, avx512; at most what this CPU runs), frequency_level=simd128|simd256|
// simd512, hugepages=0|1, verbose=0..3. Thread counts belong to --threads, not here.
std::string embree_config_error(const std::string& config);

}  // namespace phos::accel
