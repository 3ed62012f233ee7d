// Parallel, deterministic, in-place construction of the implicit photon k-d tree, the unfiltered kNN
// query and the brute-force reference query.
#include "photon/kdtree.h"

#include <immintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <atomic>
#include <bit>
#include <chrono>
#include <cstddef>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/rng.h"  // mix64: deterministic pseudo-random sample positions

namespace phos::photon {

namespace {

struct Box {
    float lo[3] = {kInf, kInf, kInf};
    float hi[3] = {-kInf, -kInf, -kInf};
    void grow(const Vec3& p) {
        lo[0] = std::min(lo[0], p.x), hi[0] = std::max(hi[0], p.x);
        lo[1] = std::min(lo[1], p.y), hi[1] = std::max(hi[1], p.y);
        lo[2] = std::min(lo[2], p.z), hi[2] = std::max(hi[2], p.z);
    }
    void merge(const Box& o) {
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], o.lo[a]), hi[a] = std::max(hi[a], o.hi[a]);
    }
    // Split on the axis where the points (not the cell) spread most: photons lie on planes, and a
    // tight box never picks an axis along which all points agree, so no level is wasted.
    int widest_axis() const {
        int axis = 0;
        float extent = hi[0] - lo[0];
        for (int a = 1; a < 3; ++a) {
            if (hi[a] - lo[a] > extent) axis = a, extent = hi[a] - lo[a];
        }
        return axis;
    }
};

// Coordinate `axis` of a photon's position, read at a computed offset (no branch on the axis in
// the partition loops).
static_assert(offsetof(Photon, position) == 0 && offsetof(Vec3, y) == 4 && offsetof(Vec3, z) == 8);
inline float key(const Photon& p, int axis) {
    float x;
    std::memcpy(&x, reinterpret_cast<const char*>(&p) + sizeof(float) * size_t(axis), sizeof x);
    return x;
}

// Work decomposition. Everything parallel is cut into pieces whose bounds depend only on the range
// being processed (never on the thread count), and every piece's result is a pure function of its
// input, so the tree is identical at any thread count.
constexpr uint32_t kChunk = 1u << 14;             // partition chunk: 320 KiB of photons, fits L2
constexpr uint32_t kLarge = 1u << 18;             // ranges this big use the chunked selection
constexpr uint32_t kBoxedSelect = 1u << 16;       // serial selections this big take boxes as they go
constexpr uint32_t kParallelSubtrees = 1u << 14;  // ranges this big build their subtrees in parallel
constexpr uint32_t kScan = 1u << 16;              // bounding boxes, checks: photons per piece
constexpr uint32_t kPiece = 1u << 14;             // exchanges: element pairs per piece
constexpr uint32_t kSampled = 1u << 13;           // serial selection: Floyd-Rivest steps above this
constexpr uint32_t kSampleMax = 1u << 12;         // serial selection: largest sample
constexpr uint32_t kTiny = 32;                    // serial selection: select_tiny at most
constexpr int kMaxLargeSteps = 16;                // parallel selection: steps before going serial

// The number of pieces of `size` elements that cover n, and the end of the one starting at
// `start` in a range ending at e (no overflow near 2^32).
inline uint32_t pieces_of(uint32_t n, uint32_t size) { return n / size + (n % size != 0); }
inline uint32_t piece_end(uint32_t start, uint32_t e, uint32_t size) {
    return start + std::min(e - start, size);
}

// Puts the element of rank k of the distinct keys a[0, n) at a[k], smaller ones before it and
// larger ones after: quickselect with a median-of-3 pivot and a branchless Lomuto partition (for
// the few dozen keys of select_tiny; O(n^2) at worst, no equal keys to worry about).
inline void select_keys(uint64_t* a, uint32_t n, uint32_t k) {
    const auto sort2 = [](uint64_t& x, uint64_t& y) {
        const uint64_t u = std::min(x, y), v = std::max(x, y);
        x = u, y = v;
    };
    uint32_t lo = 0, hi = n;
    while (hi - lo > 2) {
        const uint32_t mid = lo + (hi - lo) / 2;
        sort2(a[lo], a[mid]), sort2(a[mid], a[hi - 1]), sort2(a[lo], a[mid]);
        const uint64_t pivot = a[mid];
        a[mid] = a[hi - 1];
        uint32_t s = lo;
        for (uint32_t i = lo; i < hi - 1; ++i) {
            const uint64_t t = a[i];
            a[i] = a[s];
            a[s] = t;
            s += t < pivot;
        }
        a[hi - 1] = a[s];
        a[s] = pivot;
        if (k == s) return;
        if (k < s) {
            hi = s;
        } else {
            lo = s + 1;
        }
    }
    if (hi - lo == 2) sort2(a[lo], a[lo + 1]);
}

// Maps a float to an unsigned integer with the same order (-0 just below +0).
inline uint32_t ordered_bits(float x) {
    const uint32_t u = std::bit_cast<uint32_t>(x);
    return u ^ (uint32_t(int32_t(u) >> 31) | 0x80000000u);
}

// A list of disjoint position intervals, addressed by ordinal: element o of the list is the o-th
// position when the intervals are concatenated in order.
struct SegmentList {
    std::vector<uint32_t> start;
    std::vector<uint32_t> before{0};  // before[j]: positions in the intervals preceding interval j
    void add(uint32_t b, uint32_t e) {
        if (b >= e) return;
        start.push_back(b);
        before.push_back(before.back() + (e - b));
    }
    uint32_t size() const { return before.back(); }
};

// Walks a SegmentList from ordinal o: `pos` is the current position, `left` how many positions
// remain in its interval.
struct Cursor {
    const SegmentList* list;
    size_t j;
    uint32_t pos, left;
    Cursor(const SegmentList& l, uint32_t o) : list(&l) {
        j = size_t(std::upper_bound(l.before.begin(), l.before.end(), o) - l.before.begin()) - 1;
        pos = l.start[j] + (o - l.before[j]);
        left = l.before[j + 1] - o;
    }
    void advance(uint32_t m) {
        pos += m, left -= m;
        if (left == 0 && j + 2 < list->before.size()) {
            ++j;
            pos = list->start[j];
            left = list->before[j + 1] - list->before[j];
        }
    }
};

// The build's thread time, summed over threads, in nanoseconds (for -v): the top levels' passes
// (ranges of kLarge photons and more, and the bands they leave) and everything below them. On
// many cores, the top levels' share growing faster than the work says they wait for memory.
struct BuildTimes {
    std::atomic<uint64_t> top{0}, below{0};
};
// Adds the time its scope takes to one of them.
class TimeInto {
public:
    explicit TimeInto(std::atomic<uint64_t>& to) : to_(to) {}
    TimeInto(const TimeInto&) = delete;
    TimeInto& operator=(const TimeInto&) = delete;
    ~TimeInto() {
        const auto ns =
            std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0_);
        to_.fetch_add(uint64_t(ns.count()), std::memory_order_relaxed);
    }

private:
    std::atomic<uint64_t>& to_;
    const std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

// The photons, and with kIndex their input indices, permuted together.
template <bool kIndex>
struct Builder {
    Photon* p;
    uint32_t* idx;
    uint32_t leaf;
    BuildTimes* times;

    void swap(uint32_t i, uint32_t j) const {
        std::swap(p[i], p[j]);
        if constexpr (kIndex) std::swap(idx[i], idx[j]);
    }

    // Grows the SSE bounds lo, hi by the positions of p[b, e). The position and the power word
    // share one 16-byte load (lane 3 is ignored).
    static void grow_lanes(const Photon* p, uint32_t b, uint32_t e, __m128& lo, __m128& hi) {
        __m128 lo1 = lo, hi1 = hi;
        uint32_t i = b;
        for (; i + 1 < e; i += 2) {
            const __m128 v0 = _mm_loadu_ps(&p[i].position.x), v1 = _mm_loadu_ps(&p[i + 1].position.x);
            lo = _mm_min_ps(lo, v0), hi = _mm_max_ps(hi, v0);
            lo1 = _mm_min_ps(lo1, v1), hi1 = _mm_max_ps(hi1, v1);
        }
        if (i < e) {
            const __m128 v = _mm_loadu_ps(&p[i].position.x);
            lo = _mm_min_ps(lo, v), hi = _mm_max_ps(hi, v);
        }
        lo = _mm_min_ps(lo, lo1), hi = _mm_max_ps(hi, hi1);
    }
    static Box to_box(__m128 lo, __m128 hi) {
        alignas(16) float l[4], h[4];
        _mm_store_ps(l, lo);
        _mm_store_ps(h, hi);
        Box box;
        for (int a = 0; a < 3; ++a) box.lo[a] = l[a], box.hi[a] = h[a];
        return box;
    }
    Box bounds_serial(uint32_t b, uint32_t e) const {
        __m128 lo = _mm_set1_ps(kInf), hi = _mm_set1_ps(-kInf);
        grow_lanes(p, b, e, lo, hi);
        return to_box(lo, hi);
    }

    // Per-piece boxes merged in piece order: the same at any thread count.
    Box bounds(uint32_t b, uint32_t e) const {
        if (e - b <= kScan) {
            const TimeInto t(times->top);
            return bounds_serial(b, e);
        }
        const uint32_t pieces = pieces_of(e - b, kScan);
        std::vector<Box> part(pieces);
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, pieces),
                          [&](const tbb::blocked_range<uint32_t>& r) {
                              const TimeInto t(times->top);
                              for (uint32_t c = r.begin(); c < r.end(); ++c)
                                  part[c] = bounds_serial(b + c * kScan, piece_end(b + c * kScan, e, kScan));
                          });
        Box box;
        for (const Box& x : part) box.merge(x);
        return box;
    }

    // With kBoxes, the partitions below also take the bounding boxes of the elements they put
    // below (`in`) and not below (`out`): of each block as it is finished, while it is still in
    // the L1 cache, so a range too large for the caches needs no second pass for its children's
    // boxes.
    struct SideBoxes {
        __m128 in_lo = _mm_set1_ps(kInf), in_hi = _mm_set1_ps(-kInf);
        __m128 out_lo = _mm_set1_ps(kInf), out_hi = _mm_set1_ps(-kInf);
        Box in() const { return to_box(in_lo, in_hi); }
        Box out() const { return to_box(out_lo, out_hi); }
    };

    // Moves the elements of [b, e) for which below(coordinate) holds to the front, keeping nothing
    // else in order, and returns where they end. A branchless Lomuto partition: a swap per element
    // and no mispredicted branches.
    template <class Below>
    uint32_t partition_lomuto(uint32_t b, uint32_t e, int axis, Below below) const {
        uint32_t s = b;
        for (uint32_t i = b; i < e; ++i) {
            const Photon t = p[i];
            const bool is_below = below(key(t, axis));
            p[i] = p[s];
            p[s] = t;
            if constexpr (kIndex) {
                const uint32_t u = idx[i];
                idx[i] = idx[s];
                idx[s] = u;
            }
            s += is_below;
        }
        return s;
    }

    // The same result contract, with far fewer moves: a block partition (Edelkamp & Weiss,
    // "BlockQuicksort: avoiding branch mispredictions in quicksort", ESA 2016). A block of kBlock
    // elements at each end is scanned without branches, recording the offsets of the elements on
    // the wrong side; then only those are swapped in pairs. [b, l) is done (below), [r, e) too (not
    // below); a block is dropped from the unprocessed middle once its wrong elements are all
    // swapped; the last <= 2 kBlock elements take the Lomuto partition.
    template <bool kBoxes = false, class Below>
    uint32_t partition(uint32_t b, uint32_t e, int axis, Below below, SideBoxes* boxes = nullptr) const {
        constexpr uint32_t kBlock = 64;
        uint8_t wrong_l[kBlock], wrong_r[kBlock];
        uint32_t l = b, r = e, nl = 0, nr = 0, sl = 0, sr = 0;
        while (r - l > 2 * kBlock) {
            if (nl == 0) {
                sl = 0;
                for (uint32_t i = 0; i < kBlock; ++i) {
                    wrong_l[nl] = uint8_t(i);
                    nl += !below(key(p[l + i], axis));
                }
            }
            if (nr == 0) {
                sr = 0;
                for (uint32_t i = 0; i < kBlock; ++i) {
                    wrong_r[nr] = uint8_t(i);
                    nr += below(key(p[r - 1 - i], axis));
                }
            }
            const uint32_t m = std::min(nl, nr);
            for (uint32_t j = 0; j < m; ++j) swap(l + wrong_l[sl + j], r - 1 - wrong_r[sr + j]);
            nl -= m, nr -= m, sl += m, sr += m;
            if (nl == 0) {  // the block holds only elements below: final
                if constexpr (kBoxes) grow_lanes(p, l, l + kBlock, boxes->in_lo, boxes->in_hi);
                l += kBlock;
            }
            if (nr == 0) {
                if constexpr (kBoxes) grow_lanes(p, r - kBlock, r, boxes->out_lo, boxes->out_hi);
                r -= kBlock;
            }
        }
        const uint32_t s = partition_lomuto(l, r, axis, below);
        if constexpr (kBoxes) {
            grow_lanes(p, l, s, boxes->in_lo, boxes->in_hi);
            grow_lanes(p, s, r, boxes->out_lo, boxes->out_hi);
        }
        return s;
    }

    // Selection in a range of at most kTiny photons: selects among (coordinate, position) pairs
    // packed into 64-bit integers and moves the photons once, instead of swapping 20-byte records.
    void select_tiny(uint32_t b, uint32_t e, uint32_t k, int axis) const {
        const uint32_t n = e - b;
        uint64_t order[kTiny];
        for (uint32_t i = 0; i < n; ++i) order[i] = uint64_t(ordered_bits(key(p[b + i], axis))) << 32 | i;
        select_keys(order, n, k - b);
        alignas(Photon) unsigned char tmp[kTiny * sizeof(Photon)];  // raw: no default construction
        std::memcpy(tmp, p + b, n * sizeof(Photon));
        for (uint32_t i = 0; i < n; ++i)
            std::memcpy(static_cast<void*>(p + b + i), tmp + sizeof(Photon) * uint32_t(order[i]),
                        sizeof(Photon));
        if constexpr (kIndex) {
            uint32_t itmp[kTiny];
            std::memcpy(itmp, idx + b, n * sizeof(uint32_t));
            for (uint32_t i = 0; i < n; ++i) idx[b + i] = itmp[uint32_t(order[i])];
        }
    }

    // Guaranteed O(n log n) fallback for select_small (heapsort).
    void heap_sort(uint32_t b, uint32_t e, int axis) const {
        const auto sift = [&](uint32_t root, uint32_t n) {
            for (;;) {
                uint32_t c = 2 * root + 1;
                if (c >= n) return;
                if (c + 1 < n && key(p[b + c + 1], axis) > key(p[b + c], axis)) ++c;
                if (!(key(p[b + c], axis) > key(p[b + root], axis))) return;
                swap(b + root, b + c);
                root = c;
            }
        };
        const uint32_t n = e - b;
        for (uint32_t i = n / 2; i-- > 0;) sift(i, n);
        for (uint32_t m = n; m > 1; --m) {
            swap(b, b + m - 1);
            sift(0, m - 1);
        }
    }

    static float median3(float a, float b, float c) {
        return std::max(std::min(a, b), std::min(std::max(a, b), c));
    }

    // The values just below and above the sample rank that corresponds to rank k - b of [b, e),
    // from a pseudo-random sample of s coordinates (Floyd & Rivest, "Expected time bounds for
    // selection", CACM 1975): rank k lies between them with high probability (the margin is 3
    // standard deviations of the sample rank), while only ~3/sqrt(s) of the range does. With
    // `narrow` both are the sample value at that rank. `sample` holds s floats.
    void pick_pivots(uint32_t b, uint32_t e, uint32_t k, bool narrow, float* sample, uint32_t s, float& lo,
                     float& hi) const {
        const uint32_t n = e - b;
        const uint32_t r = uint32_t(uint64_t(k - b) * s / n);
        const uint32_t d = narrow ? 0 : uint32_t(1.5f * std::sqrt(float(s))) + 1;
        const uint32_t ilo = r > d ? r - d : 0, ihi = std::min(s - 1, r + d);
        std::nth_element(sample, sample + ilo, sample + s);
        lo = hi = sample[ilo];
        if (ihi > ilo) {
            std::nth_element(sample + ilo + 1, sample + ihi, sample + s);
            hi = sample[ihi];
        }
    }
    // Sample position i of a range of n elements.
    static uint32_t sample_at(uint32_t i, uint32_t n) { return uint32_t(((mix64(i) >> 32) * n) >> 32); }

    // Puts the element of rank k - b (by coordinate `axis`) of [b, e) at k, smaller-or-equal ones
    // before it and greater-or-equal ones after, like std::nth_element but several times faster
    // here. Ranges above kSampled first take Floyd-Rivest steps: two sample values bracket rank
    // k, two branchless partition passes cut out the band between them (1.5 passes over the
    // range instead of the ~2.5 of quickselect), and the search continues in the band. Then a
    // quickselect with a ninther pivot; runs of equal coordinates (photons on an axis-aligned
    // wall, duplicates) are peeled off by a second `<=` pass so they cannot make it quadratic, and
    // an unlucky pivot sequence falls back to heapsort. The last kTiny photons take select_tiny.
    // Deterministic: a pure function of the input order.
    // With kBoxes, also the bounding boxes of [b, k) and (k, e), taken by the Floyd-Rivest steps'
    // partitions as they classify (so a range beyond the cache is not read a second time for
    // them) and by one pass over the final band; the permutation is the same either way.
    template <bool kBoxes = false>
    void select_small(uint32_t b, uint32_t e, uint32_t k, int axis, Box* left = nullptr,
                      Box* right = nullptr) const {
        uint32_t lo = b, hi = e;
        Box below, above;  // with kBoxes: the boxes of [b, lo) and [hi, e)
        bool done = false;
        for (int steps = 0; hi - lo > kSampled && steps < 8; ++steps) {
            const uint32_t n = hi - lo;
            float sample[kSampleMax];
            const uint32_t s = std::min(kSampleMax, n / 64);
            for (uint32_t i = 0; i < s; ++i) sample[i] = key(p[lo + sample_at(i, n)], axis);
            float plo, phi;
            pick_pivots(lo, hi, k, false, sample, s, plo, phi);
            SideBoxes first, second;
            const uint32_t s1 = partition<kBoxes>(
                lo, hi, axis, [plo](float x) { return x < plo; }, &first);
            if (k < s1) {  // rare: rank k is below the band
                hi = s1;
                if constexpr (kBoxes) above.merge(first.out());
                continue;
            }
            const uint32_t s2 = partition<kBoxes>(
                s1, hi, axis, [phi](float x) { return x <= phi; }, &second);
            if (k >= s2) {  // rare: above it
                lo = s2;
                if constexpr (kBoxes) below.merge(first.in()), below.merge(second.in());
                continue;
            }
            if constexpr (kBoxes) below.merge(first.in()), above.merge(second.out());
            lo = s1, hi = s2;
            if (plo == phi) {  // the band holds equal coordinates only
                done = true;
                break;
            }
            if (2 * (hi - lo) > n) break;  // few distinct values: leave it to quickselect
        }
        if (!done) select_band(lo, hi, k, axis);
        if constexpr (kBoxes) {
            below.merge(bounds_serial(lo, k)), above.merge(bounds_serial(k + 1, hi));
            *left = below, *right = above;
        }
    }
    // The quickselect part of select_small, on what its Floyd-Rivest steps left.
    void select_band(uint32_t lo, uint32_t hi, uint32_t k, int axis) const {
        for (int budget = 2 * std::bit_width(hi - lo) + 8; hi - lo > kTiny; --budget) {
            if (budget == 0) {
                heap_sort(lo, hi, axis);
                return;
            }
            const uint32_t len = hi - lo, st = len / 8;
            const auto v = [&](uint32_t i) { return key(p[lo + i], axis); };
            const float pivot =
                median3(median3(v(0), v(st), v(2 * st)), median3(v(3 * st), v(4 * st), v(5 * st)),
                        median3(v(6 * st), v(7 * st), v(len - 1)));
            uint32_t s = partition(lo, hi, axis, [pivot](float x) { return x < pivot; });
            if (s == lo) {  // the pivot is the minimum: split off everything equal to it
                s = partition(lo, hi, axis, [pivot](float x) { return x <= pivot; });
                if (k < s) return;
                lo = s;
            } else if (k < s) {
                hi = s;
            } else {
                lo = s;
            }
        }
        select_tiny(lo, hi, k, axis);
    }

    // Exchanges the elements at ordinals [oa, oa + count) of list a with those at [ob, ob + count)
    // of list b, pairwise.
    void exchange(const SegmentList& a, uint32_t oa, const SegmentList& b, uint32_t ob,
                  uint32_t count) const {
        if (count == 0) return;
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, count, kPiece),
                          [&](const tbb::blocked_range<uint32_t>& r) {
                              const TimeInto t(times->top);
                              Cursor ca(a, oa + r.begin()), cb(b, ob + r.begin());
                              for (uint32_t i = r.begin(); i < r.end();) {
                                  const uint32_t m = std::min({ca.left, cb.left, r.end() - i});
                                  for (uint32_t t = 0; t < m; ++t) swap(ca.pos + t, cb.pos + t);
                                  ca.advance(m), cb.advance(m), i += m;
                              }
                          });
    }

    // Rotates triples: with pa, pb, pc the positions at ordinal oa + i of a, ob + i of b and oc + i
    // of c, the element at pb moves to pa, the one at pc to pb and the one at pa to pc.
    void rotate(const SegmentList& a, uint32_t oa, const SegmentList& b, uint32_t ob, const SegmentList& c,
                uint32_t oc, uint32_t count) const {
        if (count == 0) return;
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, count, kPiece),
                          [&](const tbb::blocked_range<uint32_t>& r) {
                              const TimeInto t(times->top);
                              Cursor ca(a, oa + r.begin()), cb(b, ob + r.begin()), cc(c, oc + r.begin());
                              for (uint32_t i = r.begin(); i < r.end();) {
                                  const uint32_t m = std::min({ca.left, cb.left, cc.left, r.end() - i});
                                  for (uint32_t t = 0; t < m; ++t) {
                                      const uint32_t pa = ca.pos + t, pb = cb.pos + t, pc = cc.pos + t;
                                      const Photon x = p[pa];
                                      p[pa] = p[pb], p[pb] = p[pc], p[pc] = x;
                                      if constexpr (kIndex) {
                                          const uint32_t u = idx[pa];
                                          idx[pa] = idx[pb], idx[pb] = idx[pc], idx[pc] = u;
                                      }
                                  }
                                  ca.advance(m), cb.advance(m), cc.advance(m), i += m;
                              }
                          });
    }

    // Three-way partition of [b, e) into class 0 (coordinate < lo), 1 (lo <= coordinate <= hi)
    // and 2 (> hi), returning the class boundaries za <= zb and the bounding boxes of classes 0 and
    // 2. First every fixed-size chunk is partitioned locally (in cache, in parallel) and the boxes
    // are taken there; then each element still outside its class's zone is exchanged with one of
    // the zone's foreign elements: pairs where two classes hold each other's places, 3-cycles for
    // what remains. Misplaced elements are enumerated in chunk order through SegmentLists, so each
    // exchange is fixed in advance and the exchanges run in parallel without synchronisation.
    void partition3(uint32_t b, uint32_t e, int axis, float lo, float hi, uint32_t& za, uint32_t& zb,
                    Box& box0, Box& box2) const {
        struct Chunk {
            uint32_t n0, n1;
            Box box0, box2;
        };
        const uint32_t chunks = pieces_of(e - b, kChunk);
        std::vector<Chunk> info(chunks);
        tbb::parallel_for(
            tbb::blocked_range<uint32_t>(0, chunks), [&](const tbb::blocked_range<uint32_t>& r) {
                const TimeInto t(times->top);
                for (uint32_t c = r.begin(); c < r.end(); ++c) {
                    const uint32_t cb = b + c * kChunk, ce = piece_end(cb, e, kChunk);
                    const uint32_t s1 = partition(cb, ce, axis, [lo](float x) { return x < lo; });
                    const uint32_t s2 = partition(s1, ce, axis, [hi](float x) { return x <= hi; });
                    info[c] = {s1 - cb, s2 - s1, bounds_serial(cb, s1), bounds_serial(s2, ce)};
                }
            });
        // misplaced[x][y]: positions of class-x elements inside zone y (x != y), in chunk order.
        SegmentList misplaced[3][3];
        {
            const TimeInto t(times->top);
            uint32_t n0 = 0, n1 = 0;
            box0 = box2 = Box();
            for (const Chunk& c : info) {
                n0 += c.n0, n1 += c.n1;
                box0.merge(c.box0), box2.merge(c.box2);
            }
            za = b + n0, zb = za + n1;
            const uint32_t zone[4] = {b, za, zb, e};
            for (uint32_t c = 0; c < chunks; ++c) {
                const uint32_t cb = b + c * kChunk, ce = piece_end(cb, e, kChunk);
                const uint32_t seg[4] = {cb, cb + info[c].n0, cb + info[c].n0 + info[c].n1, ce};
                for (int x = 0; x < 3; ++x) {
                    for (int y = 0; y < 3; ++y) {
                        if (x != y)
                            misplaced[x][y].add(std::max(seg[x], zone[y]), std::min(seg[x + 1], zone[y + 1]));
                    }
                }
            }
        }
        uint32_t done[3][3] = {};
        for (int x = 0; x < 3; ++x) {
            for (int y = x + 1; y < 3; ++y) {
                const uint32_t m = std::min(misplaced[x][y].size(), misplaced[y][x].size());
                exchange(misplaced[x][y], 0, misplaced[y][x], 0, m);
                done[x][y] = done[y][x] = m;
            }
        }
        // What is left is a number of 3-cycles, all in the same direction: class x in zone y, y in
        // zone z and z in zone x. The element of class x goes to where the z one is, and so on.
        const auto left = [&](int x, int y) { return misplaced[x][y].size() - done[x][y]; };
        const int x = 0, y = left(0, 1) > 0 ? 1 : 2, z = 3 - y;
        rotate(misplaced[z][x], done[z][x], misplaced[x][y], done[x][y], misplaced[y][z], done[y][z],
               left(x, y));
    }

    // Puts the element of rank k - b of [b, e) along `axis` at k, smaller-or-equal ones before it
    // and greater-or-equal ones after, and returns the bounding boxes of [b, k) and (k, e) (an
    // empty box for a part of at most `skip` photons of a small range: a leaf needs none). Large
    // ranges are split three ways around sample-chosen values (pick_pivots, partition3) and the
    // search continues in the part that holds rank k: almost always the small middle one, so one
    // partition pass over the range does most of the work. Every step removes at least one
    // element or finishes, so runs of equal coordinates cannot loop: a middle part that did not
    // shrink below half the range is split next around a single value, and a middle part of one
    // value is done. Should sampling keep failing (2 or 3 steps are usual), the serial selection
    // finishes the job after kMaxLargeSteps: slower, but O(n log n) at worst.
    void select(uint32_t b, uint32_t e, uint32_t k, int axis, bool narrow, uint32_t skip, int depth,
                Box& left, Box& right) const {
        const uint32_t n = e - b;
        if (n < kLarge || depth == kMaxLargeSteps) {
            if (depth == 0) return select_serial(b, e, k, axis, skip, left, right);  // timed by the caller
            const TimeInto t(times->top);  // the band a top level left
            return select_serial(b, e, k, axis, skip, left, right);
        }
        const uint32_t s = std::clamp<uint32_t>(n >> 8, 1u << 10, 1u << 16);
        std::vector<float> sample(s);
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, s, 4096),
                          [&](const tbb::blocked_range<uint32_t>& r) {
                              const TimeInto t(times->top);
                              for (uint32_t i = r.begin(); i < r.end(); ++i)
                                  sample[i] = key(p[b + sample_at(i, n)], axis);
                          });
        float lo, hi;
        {
            const TimeInto t(times->top);
            pick_pivots(b, e, k, narrow, sample.data(), s, lo, hi);
        }
        uint32_t za, zb;
        Box box0, box2;
        partition3(b, e, axis, lo, hi, za, zb, box0, box2);
        if (k < za) {
            select(b, za, k, axis, false, 0, depth + 1, left, right);
            right.merge(bounds(za, zb)), right.merge(box2);
        } else if (k >= zb) {
            select(zb, e, k, axis, false, 0, depth + 1, left, right);
            left.merge(box0), left.merge(bounds(za, zb));
        } else if (lo == hi) {  // the middle part holds equal coordinates only
            left = box0, left.merge(bounds(za, k));
            right = bounds(k + 1, zb), right.merge(box2);
        } else {
            select(za, zb, k, axis, 2 * uint64_t(zb - za) > e - b, 0, depth + 1, left, right);
            left.merge(box0), right.merge(box2);
        }
    }

    // select for a range below kLarge (or one the sampling kept failing on): serial.
    void select_serial(uint32_t b, uint32_t e, uint32_t k, int axis, uint32_t skip, Box& left,
                       Box& right) const {
        if (e - b >= kBoxedSelect) {
            select_small<true>(b, e, k, axis, &left, &right);
            if (k - b <= skip) left = Box();
            if (e - k - 1 <= skip) right = Box();
            return;
        }
        select_small(b, e, k, axis);
        left = k - b > skip ? bounds_serial(b, k) : Box();
        right = e - k - 1 > skip ? bounds_serial(k + 1, e) : Box();
    }

    // Subtrees above kParallelSubtrees photons build their two halves in parallel.
    void build(uint32_t b, uint32_t e, Box box) const {
        if (e - b <= kParallelSubtrees) {
            const TimeInto t(times->below);
            return build_serial(b, e, box);
        }
        const int axis = box.widest_axis();
        const uint32_t m = b + (e - b) / 2;
        Box left, right;
        if (e - b < kLarge) {
            const TimeInto t(times->below);
            select(b, e, m, axis, false, leaf, 0, left, right);
        } else {
            select(b, e, m, axis, false, leaf, 0, left, right);  // timed inside, piece by piece
        }
        p[m].set_split_axis(axis);
        tbb::parallel_invoke([&] { build(b, m, left); }, [&] { build(m + 1, e, right); });
    }
    void build_serial(uint32_t b, uint32_t e, Box box) const {
        while (e - b > leaf) {
            const int axis = box.widest_axis();
            const uint32_t m = b + (e - b) / 2;
            Box left, right;
            select(b, e, m, axis, false, leaf, 0, left, right);
            p[m].set_split_axis(axis);
            build_serial(b, m, left);
            b = m + 1, box = right;  // loop on the right subtree instead of recursing
        }
        for (uint32_t i = b; i < e; ++i) p[i].set_split_axis(3);
    }
};

}  // namespace

void PhotonKdTree::save(ByteWriter& out) const {
    out.put(leaf_size_);
    out.put_vector(photons_);
    out.put_vector(input_index_);
}

void PhotonKdTree::load(ByteReader& in) {
    build_stats_ = {};
    leaf_size_ = in.get<uint32_t>();
    photons_ = in.get_vector<Photon>();
    input_index_ = in.get_vector<uint32_t>();
    if (leaf_size_ == 0 || photons_.size() > size_t(0xfffffffeu) ||
        (!input_index_.empty() && input_index_.size() != photons_.size()))
        in.fail("inconsistent photon map");
    // The layout build() gives: split photons name an axis (traverse() indexes by it), leaf
    // photons say 3, and every position is finite.
    for (const Photon& ph : photons_)
        if (!is_finite(ph.position)) in.fail("photon map: a photon has a non-finite position");
    const uint32_t n = uint32_t(photons_.size());
    std::vector<std::pair<uint32_t, uint32_t>> todo{{0, n}};
    while (!todo.empty()) {
        const auto [b, e] = todo.back();
        todo.pop_back();
        if (e - b <= leaf_size_) {
            for (uint32_t i = b; i < e; ++i)
                if (photons_[i].split_axis() != 3) in.fail("inconsistent photon map");
            continue;
        }
        const uint32_t m = b + (e - b) / 2;
        if (photons_[m].split_axis() > 2) in.fail("inconsistent photon map");
        todo.push_back({b, m});
        todo.push_back({m + 1, e});
    }
}

void PhotonKdTree::build(std::span<const Photon> photons, const KdTreeOptions& options) {
    if (photons.size() >= std::numeric_limits<uint32_t>::max() - 1)
        throw InputError("photon map: too many photons for 32-bit indices");
    // Copied first, so `photons` may even be this tree's own array.
    build(std::vector<Photon>(photons.begin(), photons.end()), options);
}

void PhotonKdTree::build(std::vector<Photon>&& photons, const KdTreeOptions& options) {
    if (photons.size() >= std::numeric_limits<uint32_t>::max() - 1)
        throw InputError("photon map: too many photons for 32-bit indices");
    const uint32_t n = uint32_t(photons.size());
    const uint32_t leaf = std::max<uint32_t>(options.leaf_size, 2);

    // One pass checks the positions (the first bad one is reported, at any thread count) and
    // takes the root's bounding box; nothing is modified before it.
    const uint32_t pieces = pieces_of(n, kScan);
    std::vector<Box> boxes(pieces);
    std::vector<uint32_t> bad(pieces, n);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, pieces), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t c = r.begin(); c < r.end(); ++c) {
            Box box;
            for (uint32_t i = c * kScan, end = piece_end(i, n, kScan); i < end; ++i) {
                const Vec3 p = photons[i].position;
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                    bad[c] = i;
                    break;
                }
                box.grow(p);
            }
            boxes[c] = box;
        }
    });
    Box root;
    for (uint32_t c = 0; c < pieces; ++c) {
        if (bad[c] < n)
            throw InputError("photon map: photon " + std::to_string(bad[c]) + " has a non-finite position");
        root.merge(boxes[c]);
    }

    // Taken over before it is permuted, so `photons` may even be this tree's own array.
    std::vector<Photon> tree = std::move(photons);
    std::vector<uint32_t> index(options.keep_input_index ? n : 0);
    BuildTimes times;
    if (options.keep_input_index) {
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, kScan),
                          [&](const tbb::blocked_range<uint32_t>& r) {
                              for (uint32_t i = r.begin(); i < r.end(); ++i) index[i] = i;
                          });
        if (n > 0) Builder<true>{tree.data(), index.data(), leaf, &times}.build(0, n, root);
    } else if (n > 0) {
        Builder<false>{tree.data(), nullptr, leaf, &times}.build(0, n, root);
    }
    build_stats_ = {double(times.top.load()) * 1e-9, double(times.below.load()) * 1e-9};
    photons_ = std::move(tree);
    input_index_ = std::move(index);
    leaf_size_ = leaf;
}

KnnResult PhotonKdTree::knn(Vec3 q, uint32_t k, float max_dist2, Neighbour* out) const {
    return knn_if(q, k, max_dist2, out, [](const Photon&) { return true; });
}

}  // namespace phos::photon
