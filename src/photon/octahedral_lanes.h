// The octahedral direction encoder of photon.h written once for any number of SIMD lanes: the
// codes of encode_octahedral_reference for a run of directions, one per lane, each lane doing the
// reference's IEEE operations in its order (so the codes are identical bit for bit). photon.h
// instantiates it for SSE (four lanes, every x86-64 CPU), octahedral_avx2.cpp for AVX2 (eight),
// which the photon tracer picks at run time. This header includes nothing that is compiled
// differently in the two: the AVX2 file is built with -mavx2, and every function it instantiates
// from here is a template over its own lane type.
#pragma once

#include <cstdint>

namespace phos::photon::detail {

// V: the lane type: as many lanes of floats (V::F) as of 32-bit ints (V::I), and the operations
// below (the SSE/AVX intrinsics of the same names). xyz holds one direction per lane, x, y, z of
// each one after another; codes receives one code per lane.
template <int Bits, class V>
inline void encode_octahedral_lanes(const float* xyz, uint32_t* codes) {
    static_assert(Bits >= 2 && Bits <= 15);
    using F = typename V::F;
    using I = typename V::I;
    constexpr int S = (1 << (Bits - 1)) - 1;
    constexpr float kInv = 1.0f / float(S);
    const F sign_mask = V::set1(-0.0f), one = V::set1(1.0f), zero = V::set1(0.0f);
    const auto abs = [&](F v) { return V::andnot(sign_mask, v); };
    const auto select = [](F m, F a, F b) { return V::or_(V::and_(m, a), V::andnot(m, b)); };
    const auto select_i = [](I m, I a, I b) { return V::or_i(V::and_i(m, a), V::andnot_i(m, b)); };
    // The minus sign where v < 0 (v >= 0, -0 included, counts as positive, as in oct_wrap).
    const auto negative = [&](F v) { return V::andnot(V::cmpge(v, zero), sign_mask); };
    const F x = V::load_strided(xyz, 3), y = V::load_strided(xyz + 1, 3), z = V::load_strided(xyz + 2, 3);
    const F l1 = V::add(V::add(abs(x), abs(y)), abs(z));
    // l1 > 0 and finite; the other lanes get the reference's fallback code below.
    const F usable = V::and_(V::cmpgt(l1, zero), V::cmplt(l1, V::set1(__builtin_huge_valf())));
    const F inv = V::div(one, l1);
    F px = V::mul(x, inv), py = V::mul(y, inv);
    const F lower = V::cmplt(z, zero);  // oct_wrap there
    const F wx = V::xor_(V::sub(one, abs(py)), negative(px));
    const F wy = V::xor_(V::sub(one, abs(px)), negative(py));
    px = select(lower, wx, px);
    py = select(lower, wy, py);
    // The reference's clamp to [-1, 1] (p is finite in usable lanes), then u0 = floor(fu).
    const F m1 = V::set1(-1.0f), s = V::set1(float(S));
    const F fu = V::add(V::mul(V::min(V::max(px, m1), one), s), s);
    const F fv = V::add(V::mul(V::min(V::max(py, m1), one), s), s);
    const I top = V::set1_i(2 * S), one_i = V::set1_i(1);
    const I u0 = V::cvtt(fu), v0 = V::cvtt(fv);
    const I u1 = select_i(V::cmpgt_i(V::add_i(u0, one_i), top), top, V::add_i(u0, one_i));
    const I v1 = select_i(V::cmpgt_i(V::add_i(v0, one_i), top), top, V::add_i(v0, one_i));
    // dn = normalize(d).
    const F dl = V::sqrt(V::add(V::add(V::mul(x, x), V::mul(y, y)), V::mul(z, z)));
    const F dnx = V::div(x, dl), dny = V::div(y, dl), dnz = V::div(z, dl);
    const I s_i = V::set1_i(S);
    F best = V::set1(-2.0f);
    I best_u = u0, best_v = v0;
    for (int k = 0; k < 4; ++k) {  // (du, dv) = (0,0), (0,1), (1,0), (1,1), as the reference
        const I u = k >= 2 ? u1 : u0, v = (k & 1) ? v1 : v0;
        const F fx = V::mul(V::cvt(V::sub_i(u, s_i)), V::set1(kInv));
        const F fy = V::mul(V::cvt(V::sub_i(v, s_i)), V::set1(kInv));
        const F ax = abs(fx), ay = abs(fy);
        const F fz = V::sub(V::sub(one, ax), ay);
        const F wrap = V::cmplt(fz, zero);
        const F qx = select(wrap, V::xor_(V::sub(one, ay), negative(fx)), fx);
        const F qy = select(wrap, V::xor_(V::sub(one, ax), negative(fy)), fy);
        const F len = V::sqrt(V::add(V::add(V::mul(qx, qx), V::mul(qy, qy)), V::mul(fz, fz)));
        const F c = V::add(V::add(V::mul(V::div(qx, len), dnx), V::mul(V::div(qy, len), dny)),
                           V::mul(V::div(fz, len), dnz));
        const F better = V::cmpgt(c, best);  // the first strictly largest wins
        best = select(better, c, best);
        best_u = select_i(V::as_i(better), u, best_u);
        best_v = select_i(V::as_i(better), v, best_v);
    }
    const I code = V::or_i(best_u, V::shl_i(best_v, Bits));
    const I fallback = V::set1_i(S | (S << Bits));
    V::store_u32(codes, select_i(V::as_i(usable), code, fallback));
}

}  // namespace phos::photon::detail
