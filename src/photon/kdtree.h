// The photon map's spatial index: a balanced k-d tree stored implicitly in the photon array itself
// (no nodes, no pointers), with k-nearest-within-radius and fixed-radius queries that allocate
// nothing. Used by the global / caustic / volume photon maps and by (S)PPM.
//
// Layout. Photons are permuted so that every subtree owns a contiguous range [b, e). A range with
// more than `leaf_size` photons is split at its middle element m = b + (e - b) / 2, which is the
// median along the axis of largest extent of the range's points; the photon at m is the split node
// (its record's 2 axis bits say which axis), [b, m) is the left subtree (coordinates <= split),
// [m + 1, e) the right one (>= split). Ranges of at most `leaf_size` photons are leaf buckets,
// scanned linearly. So a node is just a range, the children are computed, and the only memory is
// the 20-byte photons (plus 4 bytes per photon if the input order is kept). A leaf's photons and
// the split photons above it are adjacent in memory, so a query reads few cache lines.
// Compared with Jensen's left-balanced heap-ordered array, this keeps whole subtrees contiguous
// (cache-friendly buckets), needs no "left-balancing" arithmetic, and parallelises trivially
// because subtrees are disjoint ranges.
//
// Build: in place and O(n log n). build(std::vector<Photon>&&) permutes the caller's array itself
// (the span overload copies it first), so beyond the photons it needs only O(threads x small)
// buffers, plus the 4-byte input index (permuted alongside) when it is kept: no key copies. Each
// range puts its median along its axis at m, and the children's bounding boxes come out of that
// selection. Ranges of 2^18 photons and more (the top levels, where one or two ranges cannot
// occupy the threads) select in parallel: Floyd-Rivest sampling (Floyd & Rivest, "Expected time
// bounds for selection", CACM 1975) gives two coordinates that bracket the median; a three-way
// partition around them (each 16 K-photon chunk partitioned in cache, then the elements outside
// their class's zone exchanged in pairs and 3-cycles fixed by chunk order) leaves a small middle
// band holding the median, selected recursively, so one partition pass over a level does most of
// the work. Smaller ranges select serially: Floyd-Rivest steps, then quickselect with ninther
// pivots, both on branchless block partitions (Edelkamp & Weiss, "BlockQuicksort", ESA 2016),
// and a packed-key selection for the last 32 photons. From 2^16 photons (beyond the caches on
// many cores) the partitions also take the children's boxes, block by block as each is
// finished, so the range is not read again for them. Runs of equal coordinates (walls,
// duplicates) cannot make either quadratic: a band of one value is finished at once, equal pivots
// are peeled off, and heapsort backs up unlucky pivot sequences. Subtrees of large ranges build in
// parallel (oneTBB). Parallel work is cut into fixed-size pieces of each range, never by thread
// count, and every piece's result is a pure function of its input, so the tree is identical at any
// thread count. In place (no keys, no copy of the photons) it builds ~23 M photons/s at 100 M
// photons on 2 threads; see bench/kdtree_bench.cpp and docs/performance.md.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/byte_buffer.h"
#include "core/vec.h"
#include "photon/photon.h"

namespace phos::photon {

// One neighbour found by a query: `index` is the photon's position in the tree (tree.photon(index));
// `dist2` its squared distance to the query point.
struct Neighbour {
    uint32_t index;
    float dist2;
};

struct KnnResult {
    uint32_t count = 0;   // neighbours written (<= k)
    float max_dist2 = 0;  // largest dist2 among them (0 if none): r^2 of the density estimate
};

struct KdTreeOptions {
    uint32_t leaf_size = 8;         // photons per leaf bucket (>= 2)
    bool keep_input_index = false;  // remember each photon's index in the build input (+4 B each)
};

// Where the last build's time went, summed over its threads: the top levels' passes over memory
// (ranges of 2^18 photons and more: sampling, partitions, exchanges, and the bands they leave) and
// the levels below them. Not saved with the tree.
struct KdBuildStats {
    double top_seconds = 0, below_seconds = 0;
};

class PhotonKdTree {
public:
    PhotonKdTree() = default;
    explicit PhotonKdTree(std::span<const Photon> photons, const KdTreeOptions& options = {}) {
        build(photons, options);
    }
    explicit PhotonKdTree(std::vector<Photon>&& photons, const KdTreeOptions& options = {}) {
        build(std::move(photons), options);
    }

    // Replaces the contents with `photons` in tree order: the array is taken over and permuted in
    // place (it becomes photons()), so the build needs no second copy. Runs in the calling
    // thread's oneTBB arena (so a tbb::task_arena limits the threads). Throws InputError for
    // non-finite positions or more than 2^32 - 2 photons; `photons` is then left as it was.
    void build(std::vector<Photon>&& photons, const KdTreeOptions& options = {});
    // The same on a copy of `photons` (the caller may then free its array).
    void build(std::span<const Photon> photons, const KdTreeOptions& options = {});

    // Saves the tree (photons in tree order, input indices, leaf size) and restores it exactly:
    // a checkpoint holds the maps so a resumed render need not trace them again.
    void save(ByteWriter& out) const;
    void load(ByteReader& in);

    size_t size() const { return photons_.size(); }
    bool empty() const { return photons_.empty(); }
    // Photons in tree order; Neighbour::index points into this.
    std::span<const Photon> photons() const { return photons_; }
    const Photon& photon(uint32_t i) const { return photons_[i]; }
    // Index in the build input of tree photon i (only if built with keep_input_index).
    bool has_input_index() const { return !input_index_.empty() || photons_.empty(); }
    uint32_t input_index(uint32_t i) const { return input_index_[i]; }
    uint32_t leaf_size() const { return leaf_size_; }
    const KdBuildStats& build_stats() const { return build_stats_; }
    size_t memory_bytes() const {
        return photons_.capacity() * sizeof(Photon) + input_index_.capacity() * sizeof(uint32_t);
    }

    // The (up to) k photons nearest to q with squared distance <= max_dist2 (pass kInf for no
    // limit). `out` must hold k entries; they come back in max-heap order (not sorted; out[0] is
    // the farthest when count == k). Among photons at exactly equal distance the choice is
    // unspecified (but deterministic).
    KnnResult knn(Vec3 q, uint32_t k, float max_dist2, Neighbour* out) const;

    // Same, counting only photons for which accept(const Photon&) is true (e.g. a normal test, so
    // the k neighbours all come from the query's surface).
    template <class Accept>
    KnnResult knn_if(Vec3 q, uint32_t k, float max_dist2, Neighbour* out, Accept&& accept) const;

    // Calls f(uint32_t index, float dist2) for every photon with squared distance <= radius2, in
    // an unspecified but deterministic order.
    template <class F>
    void for_each_in_radius(Vec3 q, float radius2, F&& f) const;

private:
    // Visits every photon i with dist2 < thr, calling visit(i, dist2); visit may lower `thr`,
    // which prunes the rest of the traversal.
    template <class Visit>
    void traverse(Vec3 q, const float& thr, Visit&& visit) const;

    std::vector<Photon> photons_;
    std::vector<uint32_t> input_index_;
    uint32_t leaf_size_ = 16;
    KdBuildStats build_stats_;
};

// ---- implementation of the templates ----

namespace detail {
inline float coord(const Vec3& v, int axis) { return axis == 0 ? v.x : (axis == 1 ? v.y : v.z); }
inline float dist2(Vec3 a, Vec3 b) {
    const float dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    return dx * dx + dy * dy + dz * dz;
}
// Restores the max-heap property after out[0] was replaced.
inline void sift_down(Neighbour* h, uint32_t n) {
    const Neighbour top = h[0];
    uint32_t i = 0;
    for (;;) {
        uint32_t c = 2 * i + 1;
        if (c >= n) break;
        if (c + 1 < n && h[c + 1].dist2 > h[c].dist2) ++c;
        if (h[c].dist2 <= top.dist2) break;
        h[i] = h[c];
        i = c;
    }
    h[i] = top;
}
// The smallest float greater than x: turns "dist2 <= r2" into the "dist2 < thr" used inside.
inline float above(float x) { return std::nextafter(x, kInf * kInf); }
}  // namespace detail

template <class Visit>
void PhotonKdTree::traverse(Vec3 q, const float& thr, Visit&& visit) const {
    const uint32_t n = uint32_t(photons_.size());
    if (n == 0) return;
    const Photon* P = photons_.data();
    const uint32_t leaf = leaf_size_;
    // Lower bounds are accumulated incrementally (Arya & Mount): `off` holds the query's offset
    // from the current cell on each axis, lb the squared length of that offset. The far child of
    // a split differs from its parent only on the split axis. A relative slack of ~2^-20 keeps
    // rounding in lb from pruning a cell that holds a point at the exact bound.
    constexpr float kSlack = 1.0f - 1.0f / (1 << 20);
    struct Entry {
        uint32_t b, e;
        float lb;
        float off[3];
    };
    Entry stack[64];  // depth <= log2(2^32 / 2) + 1
    int sp = 0;
    uint32_t b = 0, e = n;
    float lb = 0, off[3] = {0, 0, 0};
    for (;;) {
        while (e - b > leaf) {
            const uint32_t m = b + (e - b) / 2;
            const Photon& pm = P[m];
            const float d2 = detail::dist2(pm.position, q);
            if (d2 < thr) visit(m, d2);
            const int axis = pm.split_axis();
            const float diff = detail::coord(q, axis) - detail::coord(pm.position, axis);
            const float far_lb = lb - off[axis] * off[axis] + diff * diff;
            uint32_t fb, fe;
            if (diff < 0) {
                fb = m + 1, fe = e, e = m;
            } else {
                fb = b, fe = m, b = m + 1;
            }
            if (far_lb * kSlack < thr && fb < fe) {
                Entry& s = stack[sp++];
                s.b = fb, s.e = fe, s.lb = far_lb;
                s.off[0] = off[0], s.off[1] = off[1], s.off[2] = off[2];
                s.off[axis] = diff;
            }
        }
        for (uint32_t i = b; i < e; ++i) {
            const float d2 = detail::dist2(P[i].position, q);
            if (d2 < thr) visit(i, d2);
        }
        for (;;) {
            if (sp == 0) return;
            const Entry& s = stack[--sp];
            if (s.lb * kSlack < thr) {
                b = s.b, e = s.e, lb = s.lb;
                off[0] = s.off[0], off[1] = s.off[1], off[2] = s.off[2];
                break;
            }
        }
    }
}

template <class Accept>
KnnResult PhotonKdTree::knn_if(Vec3 q, uint32_t k, float max_dist2, Neighbour* out, Accept&& accept) const {
    KnnResult r;
    if (k == 0 || !(max_dist2 >= 0)) return r;
    // Fill out[] until it holds k photons, then keep it a max-heap on dist2 and replace its top
    // whenever something nearer turns up: O(log k) per accepted photon, where a sorted array (as
    // nanoflann's) costs O(k). thr is the acceptance bound: the heap top once full.
    float thr = detail::above(max_dist2);
    uint32_t count = 0;
    traverse(q, thr, [&](uint32_t i, float d2) {
        if (!accept(photons_[i])) return;
        if (count < k) {
            out[count++] = {i, d2};
            if (count == k) {
                std::make_heap(out, out + k,
                               [](const Neighbour& a, const Neighbour& b) { return a.dist2 < b.dist2; });
                thr = out[0].dist2;
            }
        } else {
            out[0] = {i, d2};
            detail::sift_down(out, k);
            thr = out[0].dist2;
        }
    });
    r.count = count;
    if (count == k) {
        r.max_dist2 = out[0].dist2;
    } else {
        for (uint32_t i = 0; i < count; ++i) r.max_dist2 = std::max(r.max_dist2, out[i].dist2);
    }
    return r;
}

template <class F>
void PhotonKdTree::for_each_in_radius(Vec3 q, float radius2, F&& f) const {
    if (!(radius2 >= 0)) return;
    const float thr = detail::above(radius2);
    traverse(q, thr, [&](uint32_t i, float d2) { f(i, d2); });
}

}  // namespace phos::photon
