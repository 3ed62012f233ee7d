// The photon tracer's direction codes eight at a time with AVX2, for CPUs that have it (chosen at
// run time: the shipped build targets every x86-64 CPU). The same codes as encode_octahedral4<8>.
#pragma once

#include <cstdint>

namespace phos::photon {

// The 8-bit octahedral codes (photon.h's encode_octahedral<8>) of the eight directions at xyz
// (x, y, z of each, one after another). Only where __builtin_cpu_supports("avx2"), which the
// caller asks (code compiled with -mavx2, as this function is, may not run before that).
void encode_octahedral8_avx2(const float* xyz, uint32_t codes[8]);

}  // namespace phos::photon
