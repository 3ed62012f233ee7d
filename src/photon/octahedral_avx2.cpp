// encode_octahedral_lanes (octahedral_lanes.h) on the eight lanes of AVX2. This file alone is
// compiled with -mavx2 (CMakeLists.txt), without FMA, so every lane rounds as the reference does;
// it includes nothing else of phos, so no inline function of the rest of phos is ever compiled here
// with AVX instructions (the linker could keep that copy for CPUs without them).
#include "photon/octahedral_avx2.h"

#include <immintrin.h>

#include "photon/octahedral_lanes.h"

namespace phos::photon {
namespace {

struct Avx2Lanes {
    using F = __m256;
    using I = __m256i;
    static F load_strided(const float* p, int stride) {
        return _mm256_setr_ps(p[0], p[stride], p[2 * stride], p[3 * stride], p[4 * stride], p[5 * stride],
                              p[6 * stride], p[7 * stride]);
    }
    static F set1(float v) { return _mm256_set1_ps(v); }
    static F add(F a, F b) { return _mm256_add_ps(a, b); }
    static F sub(F a, F b) { return _mm256_sub_ps(a, b); }
    static F mul(F a, F b) { return _mm256_mul_ps(a, b); }
    static F div(F a, F b) { return _mm256_div_ps(a, b); }
    static F sqrt(F a) { return _mm256_sqrt_ps(a); }
    static F min(F a, F b) { return _mm256_min_ps(a, b); }
    static F max(F a, F b) { return _mm256_max_ps(a, b); }
    static F and_(F a, F b) { return _mm256_and_ps(a, b); }
    static F or_(F a, F b) { return _mm256_or_ps(a, b); }
    static F andnot(F a, F b) { return _mm256_andnot_ps(a, b); }
    static F xor_(F a, F b) { return _mm256_xor_ps(a, b); }
    // The ordered, non-signalling predicates of SSE's cmplt/cmpgt/cmpge (false for NaN).
    static F cmplt(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
    static F cmpgt(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
    static F cmpge(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_GE_OQ); }
    static I cvtt(F a) { return _mm256_cvttps_epi32(a); }
    static F cvt(I a) { return _mm256_cvtepi32_ps(a); }
    static I as_i(F a) { return _mm256_castps_si256(a); }
    static I set1_i(int v) { return _mm256_set1_epi32(v); }
    static I add_i(I a, I b) { return _mm256_add_epi32(a, b); }
    static I sub_i(I a, I b) { return _mm256_sub_epi32(a, b); }
    static I cmpgt_i(I a, I b) { return _mm256_cmpgt_epi32(a, b); }
    static I and_i(I a, I b) { return _mm256_and_si256(a, b); }
    static I or_i(I a, I b) { return _mm256_or_si256(a, b); }
    static I andnot_i(I a, I b) { return _mm256_andnot_si256(a, b); }
    static I shl_i(I a, int n) { return _mm256_slli_epi32(a, n); }
    static void store_u32(uint32_t* out, I a) { _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), a); }
};

}  // namespace

void encode_octahedral8_avx2(const float* xyz, uint32_t codes[8]) {
    detail::encode_octahedral_lanes<8, Avx2Lanes>(xyz, codes);
}

}  // namespace phos::photon
