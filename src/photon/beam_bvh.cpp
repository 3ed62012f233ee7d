// Deterministic, parallel construction of the photon-sphere BVH (see beam_bvh.h).
#include "photon/beam_bvh.h"

#include <tbb/parallel_invoke.h>

#include <string>

#include "core/error.h"

namespace phos::photon {
namespace {

using Node = BeamBvh::Node;

// Ranges above this size build their two halves as parallel tasks.
constexpr uint32_t kParallelSubtrees = 1u << 12;

// Nodes of the subtree over n spheres: it depends on n alone (median splits), which is what lets
// the halves of a range be built in parallel into slots known in advance.
uint32_t subtree_nodes(uint32_t n, uint32_t leaf) {
    if (n <= leaf) return 1;
    return 1 + subtree_nodes(n / 2, leaf) + subtree_nodes(n - n / 2, leaf);
}

struct Builder {
    PhotonSphere* s;
    Node* nodes;
    uint32_t leaf;
    float pad;

    void build(uint32_t node, uint32_t b, uint32_t e) const {
        Node& n = nodes[node];
        float clo[3] = {kInf, kInf, kInf}, chi[3] = {-kInf, -kInf, -kInf};
        for (int a = 0; a < 3; ++a) n.lo[a] = kInf, n.hi[a] = -kInf;
        for (uint32_t i = b; i < e; ++i) {
            const Vec3 p = s[i].position;
            const float r = s[i].radius + pad;
            for (int a = 0; a < 3; ++a) {
                clo[a] = std::min(clo[a], p[a]), chi[a] = std::max(chi[a], p[a]);
                n.lo[a] = std::min(n.lo[a], p[a] - r), n.hi[a] = std::max(n.hi[a], p[a] + r);
            }
        }
        if (e - b <= leaf) {
            n.offset = b, n.count = e - b;
            return;
        }
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
        // nth_element is a pure function of its input order, so the split is deterministic.
        const uint32_t m = b + (e - b) / 2;
        std::nth_element(s + b, s + m, s + e, [axis](const PhotonSphere& x, const PhotonSphere& y) {
            return x.position[axis] < y.position[axis];
        });
        const uint32_t right = node + 1 + subtree_nodes(m - b, leaf);
        n.offset = right, n.count = 0;
        if (e - b > kParallelSubtrees)
            tbb::parallel_invoke([&] { build(node + 1, b, m); }, [&] { build(right, m, e); });
        else
            build(node + 1, b, m), build(right, m, e);
    }
};

}  // namespace

void BeamBvh::save(ByteWriter& out) const {
    out.put_vector(nodes_);
    out.put_vector(spheres_);
}

void BeamBvh::load(ByteReader& in) {
    nodes_ = in.get_vector<Node>();
    spheres_ = in.get_vector<PhotonSphere>();
    if (!nodes_.empty() && !is_tree(nodes_, spheres_.size())) in.fail("inconsistent beam tree");
}

bool BeamBvh::is_tree(std::span<const Node> nodes, size_t spheres) {
    // The builder's layout: the subtree of node i fills the slots [i, e); an interior node's left
    // child is i + 1 and its right child `offset` splits the rest. Ranges shrink at every step, so
    // for_each_hit ends, and its 64-entry stack holds a path of at most 64 nodes.
    struct Range {
        size_t i, e;
        int depth;
    };
    std::vector<Range> todo{{0, nodes.size(), 1}};
    while (!todo.empty()) {
        const Range r = todo.back();
        todo.pop_back();
        const Node& n = nodes[r.i];
        if (n.count > 0) {
            if (r.e != r.i + 1 || n.offset > spheres || n.count > spheres - n.offset) return false;
            continue;
        }
        if (!(r.i + 1 < n.offset && n.offset < r.e) || r.depth >= 64) return false;
        todo.push_back({r.i + 1, n.offset, r.depth + 1});
        todo.push_back({n.offset, r.e, r.depth + 1});
    }
    return true;
}

void BeamBvh::build(std::vector<PhotonSphere> spheres, uint32_t leaf_size) {
    nodes_.clear();
    spheres_ = std::move(spheres);
    if (spheres_.size() >= (1u << 31)) throw InputError("beam BVH: too many photons for 32-bit indices");
    const uint32_t n = uint32_t(spheres_.size());
    if (n == 0) return;
    float extent = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const PhotonSphere& s = spheres_[i];
        if (!is_finite(s.position) || !std::isfinite(s.radius) || s.radius < 0)
            throw InputError("beam BVH: photon " + std::to_string(i) +
                             " has a non-finite position or radius");
        extent = std::max(extent, max_component(abs(s.position)) + s.radius);
    }
    const uint32_t leaf = std::max(leaf_size, 1u);
    nodes_.resize(subtree_nodes(n, leaf));
    Builder{spheres_.data(), nodes_.data(), leaf, 1e-6f * extent}.build(0, 0, n);
}

}  // namespace phos::photon
