// A bounding volume hierarchy over photon spheres (volume photons, each with its own kernel radius)
// for the beam radiance estimate (beam_estimate.h): one query visits every photon whose sphere a
// ray segment passes through, instead of one k-nearest search per ray-marching step.
//
// Layout. The spheres are permuted so that every node owns a contiguous range of them; nodes are
// 32 bytes (box, and either the index of the second child or the leaf's first sphere and count)
// in depth-first order, so a node's first child is the next node. A range of more than
// `leaf_size` spheres splits at its middle element by sphere centre along the axis where the
// centres spread most (no surface-area heuristic: the spheres of a volume map overlap heavily, and
// a segment meets hundreds of them, so balanced leaves are what matters). The node count of a
// subtree depends only on its sphere count, so both halves of a large range are built in parallel
// into preassigned node slots: the tree is identical at any thread count.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/byte_buffer.h"
#include "core/vec.h"

namespace phos::photon {

// A volume photon with the radius of its kernel, as the beam estimate reads it (40 bytes): the
// photon record's power and direction are decoded once here rather than at each of the hundreds
// of rays that pass through the sphere.
struct PhotonSphere {
    Vec3 position;
    float radius = 0;
    Rgb power;  // W
    Vec3 wi;    // unit, towards where the photon came from
};

// Where a segment o + t d, t in [0, t_end] (d unit), passes through a sphere: t of the centre's
// projection, the squared distance of the centre from the line, and the chord clipped to the
// segment, [t0, t1].
struct SphereHit {
    float t, dist2, t0, t1;
};

// True (and `hit` filled) if the segment passes through the open ball: the centre is nearer the
// line than the radius and the chord overlaps [0, t_end] in more than a point. The BVH query and
// the brute-force reference both decide with this function.
inline bool segment_hits_sphere(Vec3 o, Vec3 d, float t_end, const PhotonSphere& s, SphereHit& hit) {
    const Vec3 v = s.position - o;
    const float t = dot(v, d);
    const Vec3 w = v - d * t;  // the perpendicular, without the cancellation of |v|^2 - t^2
    const float dist2 = dot(w, w), r2 = s.radius * s.radius;
    if (!(dist2 < r2)) return false;
    const float h = std::sqrt(r2 - dist2);
    hit = {t, dist2, std::max(t - h, 0.0f), std::min(t + h, t_end)};
    return hit.t0 < hit.t1;
}

class BeamBvh {
public:
    // Spheres per leaf. A segment through a volume map meets spheres by the hundreds, and testing
    // one is cheaper than visiting a node: on 200 k photons (bench/beam_estimate_bench) leaves of
    // 16 to 32 were fastest, 4 was 1.3 x slower.
    static constexpr uint32_t kDefaultLeafSize = 16;

    BeamBvh() = default;
    // Replaces the contents with `spheres` in tree order. Runs in the calling thread's oneTBB arena.
    // Throws InputError for non-finite centres or radii and for more than 2^31 spheres.
    void build(std::vector<PhotonSphere> spheres, uint32_t leaf_size = kDefaultLeafSize);

    // Saves and restores the tree exactly (checkpoints); load checks every node's range.
    void save(ByteWriter& out) const;
    void load(ByteReader& in);

    size_t size() const { return spheres_.size(); }
    bool empty() const { return spheres_.empty(); }
    // Spheres in tree order (the index for_each_hit reports points into this).
    std::span<const PhotonSphere> spheres() const { return spheres_; }
    size_t memory_bytes() const {
        return nodes_.capacity() * sizeof(Node) + spheres_.capacity() * sizeof(PhotonSphere);
    }

    // Calls f(uint32_t index, const SphereHit&) for every sphere that o + t d, t in [0, t_end]
    // passes through (segment_hits_sphere), in an order that depends only on the tree and the
    // segment. d must be unit length.
    template <class F>
    void for_each_hit(Vec3 o, Vec3 d, float t_end, F&& f) const;

    // count == 0: an inner node whose second child is nodes_[offset] (the first is the next
    // node); otherwise a leaf holding spheres_[offset, offset + count). The box holds the spheres
    // with a margin of 1e-6 of the scene's extent, so that rounding in the box test never drops a
    // sphere that segment_hits_sphere accepts.
    struct Node {
        float lo[3];
        uint32_t offset;
        float hi[3];
        uint32_t count;
    };
    std::span<const Node> nodes() const { return nodes_; }
    // True if `nodes` (not empty) has the layout build() gives, over `spheres` spheres: what
    // load() asks of bytes before for_each_hit may walk them.
    static bool is_tree(std::span<const Node> nodes, size_t spheres);

private:
    std::vector<Node> nodes_;
    std::vector<PhotonSphere> spheres_;
};

// Reference answer for tests: the same query by testing every sphere, in array order.
template <class F>
void for_each_hit_brute_force(std::span<const PhotonSphere> spheres, Vec3 o, Vec3 d, float t_end, F&& f) {
    SphereHit hit;
    for (uint32_t i = 0; i < uint32_t(spheres.size()); ++i)
        if (segment_hits_sphere(o, d, t_end, spheres[i], hit)) f(i, hit);
}

// ---- implementation of the template ----

template <class F>
void BeamBvh::for_each_hit(Vec3 o, Vec3 d, float t_end, F&& f) const {
    if (nodes_.empty() || !(t_end > 0)) return;
    // Slab test against [0, t_end]. A zero direction component gets a huge inverse instead of
    // infinity, so a segment lying in a slab's plane gives 0 * 1e30 = 0 rather than NaN.
    float inv[3], org[3] = {o.x, o.y, o.z};
    for (int a = 0; a < 3; ++a) inv[a] = d[a] != 0 ? 1.0f / d[a] : 1e30f;
    const Node* nodes = nodes_.data();
    const auto overlaps = [&](const Node& n) {
        float t0 = 0, t1 = t_end;
        for (int a = 0; a < 3; ++a) {  // min / max rather than a swap: no branches
            const float ta = (n.lo[a] - org[a]) * inv[a], tb = (n.hi[a] - org[a]) * inv[a];
            t0 = std::max(t0, std::min(ta, tb));
            t1 = std::min(t1, std::max(ta, tb));
        }
        return t0 <= t1;
    };
    uint32_t stack[64];  // depth <= log2(2^31) + 1: the tree is balanced
    int sp = 0;
    uint32_t i = 0;
    if (!overlaps(nodes[0])) return;
    SphereHit hit;
    for (;;) {
        const Node& n = nodes[i];
        if (n.count == 0) {
            // Both children are tested before descending, so the stack holds only overlapping ones.
            const bool a = overlaps(nodes[i + 1]), b = overlaps(nodes[n.offset]);
            if (a && b) stack[sp++] = n.offset;
            if (a || b) {
                i = a ? i + 1 : n.offset;
                continue;
            }
        } else {
            for (uint32_t k = n.offset; k < n.offset + n.count; ++k)
                if (segment_hits_sphere(o, d, t_end, spheres_[k], hit)) f(k, hit);
        }
        if (sp == 0) return;
        i = stack[--sp];
    }
}

}  // namespace phos::photon
