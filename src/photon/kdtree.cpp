// Parallel, deterministic construction of the implicit photon k-d tree, the unfiltered kNN query
// and the brute-force reference query.
#include "photon/kdtree.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <bit>
#include <limits>

#include "core/error.h"

namespace phos::photon {

namespace {

// The build sorts these 16-byte keys rather than the 20-byte photons (less memory traffic, and the
// key remembers where its photon came from); the photons are gathered once at the end.
struct Key {
    float p[3];
    uint32_t index;
};

struct Box {
    float lo[3] = {kInf, kInf, kInf};
    float hi[3] = {-kInf, -kInf, -kInf};
    void grow(const Key& k) {
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], k.p[a]), hi[a] = std::max(hi[a], k.p[a]);
    }
    void merge(const Box& o) {
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], o.lo[a]), hi[a] = std::max(hi[a], o.hi[a]);
    }
};

// Ranges above this size split their work with oneTBB; min/max are exact, so the parallel
// bounding box equals the serial one.
constexpr uint32_t kParallelBox = 1u << 18;
constexpr uint32_t kParallelSubtrees = 1u << 14;

Box bounds(const Key* keys, uint32_t b, uint32_t e) {
    if (e - b < kParallelBox) {
        Box box;
        for (uint32_t i = b; i < e; ++i) box.grow(keys[i]);
        return box;
    }
    return tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(b, e, 1u << 16), Box{},
        [&](const tbb::blocked_range<uint32_t>& r, Box box) {
            for (uint32_t i = r.begin(); i < r.end(); ++i) box.grow(keys[i]);
            return box;
        },
        [](Box x, const Box& y) {
            x.merge(y);
            return x;
        });
}

float median3(float a, float b, float c) { return std::max(std::min(a, b), std::min(std::max(a, b), c)); }

// Puts the element of rank k (by coordinate `axis`) of a[0, n) at a[k], smaller-or-equal ones
// before it and greater-or-equal ones after, like std::nth_element but 2-4x faster here: a
// quickselect with a ninther pivot and a branchless Lomuto partition (a swap per element, no
// mispredicted branches). Runs of equal coordinates (photons on an axis-aligned wall, duplicates)
// are peeled off by a second `<=` pass so they cannot make it quadratic, and an unlucky pivot
// sequence falls back to introselect. Deterministic: a pure function of the input order.
void select_kth(Key* a, uint32_t n, uint32_t k, int axis) {
    uint32_t lo = 0, hi = n;
    const auto less = [axis](const Key& x, const Key& y) { return x.p[axis] < y.p[axis]; };
    for (int budget = 2 * std::bit_width(n) + 8; hi - lo > 32; --budget) {
        if (budget == 0) {
            std::nth_element(a + lo, a + k, a + hi, less);
            return;
        }
        const uint32_t len = hi - lo, st = len / 8;
        const auto v = [&](uint32_t i) { return a[lo + i].p[axis]; };
        const float pivot = median3(median3(v(0), v(st), v(2 * st)), median3(v(3 * st), v(4 * st), v(5 * st)),
                                    median3(v(6 * st), v(7 * st), v(len - 1)));
        const auto partition = [&](auto below) {
            uint32_t s = lo;
            for (uint32_t i = lo; i < hi; ++i) {
                const Key t = a[i];
                const bool b = below(t.p[axis]);
                a[i] = a[s];
                a[s] = t;
                s += b;
            }
            return s;
        };
        uint32_t s = partition([pivot](float x) { return x < pivot; });
        if (s == lo) {  // the pivot is the minimum: split off everything equal to it
            s = partition([pivot](float x) { return x <= pivot; });
            if (k < s) return;
            lo = s;
        } else if (k < s) {
            hi = s;
        } else {
            lo = s;
        }
    }
    std::sort(a + lo, a + hi, less);
}

void build_range(Key* keys, uint8_t* axes, uint32_t b, uint32_t e, uint32_t leaf) {
    while (e - b > leaf) {
        // Split on the axis where the points (not the cell) spread most: photons lie on planes,
        // and a tight box never picks an axis along which all points agree, so no level is wasted.
        const Box box = bounds(keys, b, e);
        int axis = 0;
        float extent = box.hi[0] - box.lo[0];
        for (int a = 1; a < 3; ++a) {
            if (box.hi[a] - box.lo[a] > extent) axis = a, extent = box.hi[a] - box.lo[a];
        }
        const uint32_t m = b + (e - b) / 2;
        select_kth(keys + b, e - b, m - b, axis);
        axes[m] = uint8_t(axis);
        if (e - b > kParallelSubtrees) {
            tbb::parallel_invoke([=] { build_range(keys, axes, b, m, leaf); },
                                 [=] { build_range(keys, axes, m + 1, e, leaf); });
            return;
        }
        build_range(keys, axes, b, m, leaf);
        b = m + 1;  // loop on the right subtree instead of recursing
    }
}

}  // namespace

void PhotonKdTree::save(ByteWriter& out) const {
    out.put(leaf_size_);
    out.put_vector(photons_);
    out.put_vector(input_index_);
}

void PhotonKdTree::load(ByteReader& in) {
    leaf_size_ = in.get<uint32_t>();
    photons_ = in.get_vector<Photon>();
    input_index_ = in.get_vector<uint32_t>();
    if (leaf_size_ == 0 || photons_.size() > size_t(0xfffffffeu) ||
        (!input_index_.empty() && input_index_.size() != photons_.size()))
        in.fail("inconsistent photon map");
}

void PhotonKdTree::build(std::span<const Photon> photons, const KdTreeOptions& options) {
    if (photons.size() >= std::numeric_limits<uint32_t>::max() - 1)
        throw InputError("photon map: too many photons for 32-bit indices");
    const uint32_t n = uint32_t(photons.size());
    const uint32_t leaf = std::max<uint32_t>(options.leaf_size, 2);

    std::vector<Key> keys(n);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 1u << 14),
                      [&](const tbb::blocked_range<uint32_t>& r) {
                          for (uint32_t i = r.begin(); i < r.end(); ++i) {
                              const Vec3 p = photons[i].position;
                              keys[i] = {{p.x, p.y, p.z}, i};
                          }
                      });
    for (const Key& k : keys) {
        if (!std::isfinite(k.p[0]) || !std::isfinite(k.p[1]) || !std::isfinite(k.p[2]))
            throw InputError("photon map: photon " + std::to_string(k.index) + " has a non-finite position");
    }
    std::vector<uint8_t> axes(n, 3);  // 3 = leaf photon
    if (n > 0) build_range(keys.data(), axes.data(), 0, n, leaf);

    // Built aside and swapped in, so `photons` may even be this tree's own array.
    std::vector<Photon> tree(n);
    std::vector<uint32_t> input_index(options.keep_input_index ? n : 0);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 1u << 14),
                      [&](const tbb::blocked_range<uint32_t>& r) {
                          for (uint32_t i = r.begin(); i < r.end(); ++i) {
                              tree[i] = photons[keys[i].index];
                              tree[i].set_split_axis(axes[i]);
                              if (!input_index.empty()) input_index[i] = keys[i].index;
                          }
                      });
    photons_.swap(tree);
    input_index_.swap(input_index);
    leaf_size_ = leaf;
}

KnnResult PhotonKdTree::knn(Vec3 q, uint32_t k, float max_dist2, Neighbour* out) const {
    return knn_if(q, k, max_dist2, out, [](const Photon&) { return true; });
}

KnnResult knn_brute_force(std::span<const Photon> photons, Vec3 q, uint32_t k, float max_dist2,
                          Neighbour* out) {
    KnnResult r;
    if (k == 0 || !(max_dist2 >= 0)) return r;
    std::vector<Neighbour> all;
    for (uint32_t i = 0; i < photons.size(); ++i) {
        const float d2 = detail::dist2(photons[i].position, q);
        if (d2 <= max_dist2) all.push_back({i, d2});
    }
    const auto less = [](const Neighbour& a, const Neighbour& b) {
        return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.index < b.index);
    };
    const size_t m = std::min<size_t>(k, all.size());
    std::partial_sort(all.begin(), all.begin() + m, all.end(), less);
    std::copy(all.begin(), all.begin() + m, out);
    r.count = uint32_t(m);
    r.max_dist2 = m > 0 ? all[m - 1].dist2 : 0.0f;
    return r;
}

}  // namespace phos::photon
