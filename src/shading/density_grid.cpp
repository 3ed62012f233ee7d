// Density grids (uniform and sparse NanoVDB) and the majorant grid walked by a 3D DDA.
#include "shading/density_grid.h"

#include <nanovdb/NanoVDB.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace phos::shading {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

bool finite3(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Intersection of two boxes (empty if they do not overlap).
Bounds intersect(const Bounds& a, const Bounds& b) {
    Bounds r;
    r.lo = max(a.lo, b.lo);
    r.hi = min(a.hi, b.hi);
    if (r.lo.x > r.hi.x || r.lo.y > r.hi.y || r.lo.z > r.hi.z) return Bounds{};
    return r;
}

// Trilinear interpolation at continuous sample coordinates (x, y, z) between the samples
// value(i, j, k) at the integer points around them.
template <class Value>
float trilinear(float x, float y, float z, Value&& value) {
    const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const int ix = int(fx), iy = int(fy), iz = int(fz);
    const float dx = x - fx, dy = y - fy, dz = z - fz;
    auto lerp = [](float t, float a, float b) { return (1 - t) * a + t * b; };
    const float d00 = lerp(dx, value(ix, iy, iz), value(ix + 1, iy, iz));
    const float d10 = lerp(dx, value(ix, iy + 1, iz), value(ix + 1, iy + 1, iz));
    const float d01 = lerp(dx, value(ix, iy, iz + 1), value(ix + 1, iy, iz + 1));
    const float d11 = lerp(dx, value(ix, iy + 1, iz + 1), value(ix + 1, iy + 1, iz + 1));
    return lerp(dz, lerp(dy, d00, d10), lerp(dy, d01, d11));
}

// pbrt-v4's SampledGrid over the box [p0, p1]: samples at cell centres, trilinear in between,
// samples outside the index range count as 0; density 0 outside the box.
class UniformDensityGrid final : public DensityGrid {
public:
    explicit UniformDensityGrid(const scene::Medium& m)
        : nx_(m.nx), ny_(m.ny), nz_(m.nz), values_(m.density), p0_(m.p0), p1_(m.p1) {
        if (nx_ <= 0 || ny_ <= 0 || nz_ <= 0)
            throw InputError("medium \"" + m.name + "\": grid resolution must be positive");
        if (values_.size() != size_t(nx_) * size_t(ny_) * size_t(nz_))
            throw InputError("medium \"" + m.name + "\": " + std::to_string(values_.size()) +
                             " density values for a " + std::to_string(nx_) + "x" + std::to_string(ny_) +
                             "x" + std::to_string(nz_) + " grid");
        if (!(p0_.x < p1_.x && p0_.y < p1_.y && p0_.z < p1_.z) || !finite3(p0_) || !finite3(p1_))
            throw InputError("medium \"" + m.name + "\": grid bounds need p0 < p1");
        for (float v : values_)
            if (!std::isfinite(v)) throw InputError("medium \"" + m.name + "\": density is not finite");
        bounds_.lo = p0_;
        bounds_.hi = p1_;
    }

    float density(Vec3 p) const override {
        if (!inside(p)) return 0.0f;
        const Vec3 s = sample_coords(p);
        return trilinear(s.x, s.y, s.z, [this](int x, int y, int z) { return at(x, y, z); });
    }

    Bounds bounds() const override { return bounds_; }

    // The samples whose trilinear support (i - 1, i + 1) touches the box: floor(s_lo) ..
    // floor(s_hi) + 1. sample_coords is monotone in p, so every point of the box maps in between.
    float max_density(const Bounds& box) const override {
        const Bounds b = intersect(box, bounds_);
        if (b.empty()) return 0.0f;
        const Vec3 lo = sample_coords(b.lo), hi = sample_coords(b.hi);
        const int x0 = std::max(0, int(std::floor(lo.x))), x1 = std::min(nx_ - 1, int(std::floor(hi.x)) + 1);
        const int y0 = std::max(0, int(std::floor(lo.y))), y1 = std::min(ny_ - 1, int(std::floor(hi.y)) + 1);
        const int z0 = std::max(0, int(std::floor(lo.z))), z1 = std::min(nz_ - 1, int(std::floor(hi.z)) + 1);
        float m = 0.0f;
        for (int z = z0; z <= z1; ++z)
            for (int y = y0; y <= y1; ++y) {
                const float* row = &values_[(size_t(z) * size_t(ny_) + size_t(y)) * size_t(nx_)];
                for (int x = x0; x <= x1; ++x) m = std::max(m, row[x]);
            }
        return m;
    }

private:
    bool inside(Vec3 p) const {
        return p.x >= p0_.x && p.x <= p1_.x && p.y >= p0_.y && p.y <= p1_.y && p.z >= p0_.z && p.z <= p1_.z;
    }
    // pbrt: Bounds3::Offset, then u * n - 0.5.
    Vec3 sample_coords(Vec3 p) const {
        return {(p.x - p0_.x) / (p1_.x - p0_.x) * float(nx_) - 0.5f,
                (p.y - p0_.y) / (p1_.y - p0_.y) * float(ny_) - 0.5f,
                (p.z - p0_.z) / (p1_.z - p0_.z) * float(nz_) - 0.5f};
    }
    float at(int x, int y, int z) const {
        if (x < 0 || y < 0 || z < 0 || x >= nx_ || y >= ny_ || z >= nz_) return 0.0f;
        return values_[(size_t(z) * size_t(ny_) + size_t(y)) * size_t(nx_) + size_t(x)];
    }

    int nx_, ny_, nz_;
    std::vector<float> values_;
    Vec3 p0_, p1_;
    Bounds bounds_;
};

// A NanoVDB float grid, sampled trilinearly in index space (voxel centres at integer coordinates,
// as nanovdb::SampleFromVoxels<.., 1> does). The density is taken as 0 outside the index box
// [bbox.min - 1, bbox.max + 1] of the active voxels, the whole support of their interpolation
// (pbrt-v4 clips to the world box of the active voxel centres, half a voxel less on each side).
// max_density uses a dense grid of block maxima over every stored value (active or not, tiles
// included), so it never underestimates whatever the node statistics say.
class SparseDensityGrid final : public DensityGrid {
public:
    using Grid = nanovdb::FloatGrid;

    explicit SparseDensityGrid(const scene::Medium& m) : keep_(m.sparse.buffer) {
        const std::string what = "medium \"" + m.name + "\" (" + m.sparse.file + ")";
        if (!keep_ || m.sparse.bytes < sizeof(nanovdb::GridData))
            throw InputError(what + ": no sparse density grid");
        if (reinterpret_cast<uintptr_t>(keep_.get()) % NANOVDB_DATA_ALIGNMENT != 0)
            throw InputError(what + ": the NanoVDB buffer is not " + std::to_string(NANOVDB_DATA_ALIGNMENT) +
                             "-byte aligned");
        grid_ = reinterpret_cast<const Grid*>(keep_.get());
        if (!grid_->isValid() || grid_->gridSize() > m.sparse.bytes)
            throw InputError(what + ": not a valid NanoVDB grid");
        if (grid_->gridType() != nanovdb::GridType::Float)
            throw InputError(what + ": grid \"" + std::string(grid_->gridName()) + "\" is not a float grid");
        if (grid_->isEmpty() || grid_->activeVoxelCount() == 0 || grid_->indexBBox().empty())
            throw InputError(what + ": grid \"" + std::string(grid_->gridName()) + "\" is empty");
        const nanovdb::CoordBBox ib = grid_->indexBBox();
        for (int a = 0; a < 3; ++a) {
            ilo_[a] = float(ib.min()[a]) - 1.0f;
            ihi_[a] = float(ib.max()[a]) + 1.0f;
        }
        for (int c = 0; c < 8; ++c) {
            const nanovdb::Vec3f q(c & 1 ? ihi_[0] : ilo_[0], c & 2 ? ihi_[1] : ilo_[1],
                                   c & 4 ? ihi_[2] : ilo_[2]);
            const nanovdb::Vec3f w = grid_->indexToWorldF(q);
            bounds_.extend(Vec3(w[0], w[1], w[2]));
        }
        if (!finite3(bounds_.lo) || !finite3(bounds_.hi))
            throw InputError(what + ": the grid's transform is not usable");
        build_blocks(ib);
    }

    float density(Vec3 p) const override {
        const nanovdb::Vec3f q = grid_->worldToIndexF(nanovdb::Vec3f(p.x, p.y, p.z));
        for (int a = 0; a < 3; ++a)
            if (!(q[a] >= ilo_[a] && q[a] <= ihi_[a])) return 0.0f;
        auto acc = grid_->getAccessor();
        return trilinear(q[0], q[1], q[2],
                         [&](int x, int y, int z) { return acc.getValue(nanovdb::Coord(x, y, z)); });
    }

    Bounds bounds() const override { return bounds_; }

    float max_density(const Bounds& box) const override {
        const Bounds b = intersect(box, bounds_);
        if (b.empty()) return 0.0f;
        // The box in index space (its 8 corners: the map may rotate), then the voxels whose
        // values a trilinear lookup inside it can read, with one voxel of slack for rounding.
        float lo[3] = {kInfinity, kInfinity, kInfinity}, hi[3] = {-kInfinity, -kInfinity, -kInfinity};
        for (int c = 0; c < 8; ++c) {
            const nanovdb::Vec3f q = grid_->worldToIndexF(
                nanovdb::Vec3f(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z));
            for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], q[a]), hi[a] = std::max(hi[a], q[a]);
        }
        int b0[3], b1[3];
        for (int a = 0; a < 3; ++a) {
            const float l = std::max(lo[a], ilo_[a]), h = std::min(hi[a], ihi_[a]);
            if (!(l <= h)) return 0.0f;
            const int v0 = int(std::floor(l)) - 1, v1 = int(std::floor(h)) + 2;
            b0[a] = std::max(0, block_of(v0, a));
            b1[a] = std::min(nb_[a] - 1, block_of(v1, a));
            if (b0[a] > b1[a]) return 0.0f;
        }
        float m = 0.0f;
        for (int z = b0[2]; z <= b1[2]; ++z)
            for (int y = b0[1]; y <= b1[1]; ++y)
                for (int x = b0[0]; x <= b1[0]; ++x) m = std::max(m, block_max_[block_index(x, y, z)]);
        return m;
    }

private:
    int block_of(int voxel, int axis) const {
        return int(std::floor(float(voxel - borigin_[axis]) / float(bsize_)));
    }
    size_t block_index(int x, int y, int z) const {
        return (size_t(z) * size_t(nb_[1]) + size_t(y)) * size_t(nb_[0]) + size_t(x);
    }
    // max over the blocks overlapping the voxel cube [o, o + dim) (clipped to the block grid).
    void splat(const nanovdb::Coord& o, int dim, float value) {
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            const int64_t v0 = std::max<int64_t>(o[a], borigin_[a]);
            const int64_t v1 = std::min<int64_t>(int64_t(o[a]) + dim - 1,
                                                 int64_t(borigin_[a]) + int64_t(nb_[a]) * bsize_ - 1);
            if (v0 > v1) return;
            lo[a] = block_of(int(v0), a);
            hi[a] = block_of(int(v1), a);
        }
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) {
                    float& b = block_max_[block_index(x, y, z)];
                    b = std::max(b, value);
                }
    }

    void build_blocks(const nanovdb::CoordBBox& ib) {
        // Voxels a lookup inside the bounds may read: [min - 1, max + 2]. Blocks are aligned
        // powers of two >= 8 (a leaf lies in one block), grown until there are at most 2^21.
        int64_t vlo[3], vhi[3];
        for (int a = 0; a < 3; ++a) vlo[a] = int64_t(ib.min()[a]) - 1, vhi[a] = int64_t(ib.max()[a]) + 2;
        bsize_ = 8;
        for (;;) {
            int64_t total = 1;
            for (int a = 0; a < 3; ++a) {
                const int64_t b0 = (vlo[a] >= 0 ? vlo[a] / bsize_ : -((-vlo[a] + bsize_ - 1) / bsize_));
                const int64_t b1 = (vhi[a] >= 0 ? vhi[a] / bsize_ : -((-vhi[a] + bsize_ - 1) / bsize_));
                borigin_[a] = int(b0 * bsize_);
                nb_[a] = int(b1 - b0 + 1);
                total *= nb_[a];
            }
            if (total <= (int64_t(1) << 21) || bsize_ >= (1 << 20)) break;
            bsize_ *= 2;
        }
        const auto& tree = grid_->tree();
        const float background = tree.background();
        block_max_.assign(size_t(nb_[0]) * size_t(nb_[1]) * size_t(nb_[2]), std::max(0.0f, background));

        using Leaf = nanovdb::NanoLeaf<float>;
        const Leaf* leaves = tree.getFirstLeaf();
        for (uint32_t i = 0; i < tree.nodeCount(0); ++i) {
            const Leaf& leaf = leaves[i];
            float m = -kInfinity;
            for (uint32_t k = 0; k < Leaf::SIZE; ++k) m = std::max(m, leaf.data()->getValue(k));
            splat(leaf.origin(), int(Leaf::DIM), m);
        }
        auto tiles = [&](const auto* nodes, uint32_t count) {
            using Node = std::remove_cv_t<std::remove_pointer_t<decltype(nodes)>>;
            const int child_dim = int(Node::ChildNodeType::DIM);
            for (uint32_t i = 0; i < count; ++i) {
                const Node& node = nodes[i];
                for (uint32_t n = 0; n < Node::SIZE; ++n) {
                    if (node.childMask().isOn(n)) continue;
                    const float v = node.data()->getValue(n);
                    if (v > background && v > 0.0f) splat(node.offsetToGlobalCoord(n), child_dim, v);
                }
            }
        };
        tiles(tree.getFirstLower(), tree.nodeCount(1));
        tiles(tree.getFirstUpper(), tree.nodeCount(2));
        const auto& root = tree.root();
        using Upper = nanovdb::NanoUpper<float>;
        for (uint32_t i = 0; i < root.tileCount(); ++i) {
            const auto* tile = root.data()->tile(i);
            if (tile->isChild() || !(tile->value > background && tile->value > 0.0f)) continue;
            splat(tile->origin(), int(Upper::DIM), tile->value);
        }
    }

    std::shared_ptr<const void> keep_;
    const Grid* grid_ = nullptr;
    float ilo_[3], ihi_[3];  // index-space box where the density may be non-zero
    Bounds bounds_;
    int bsize_ = 8, borigin_[3] = {0, 0, 0}, nb_[3] = {1, 1, 1};
    std::vector<float> block_max_;
};

}  // namespace

std::unique_ptr<DensityGrid> make_density_grid(const scene::Medium& medium) {
    switch (medium.kind) {
        case scene::Medium::Kind::Homogeneous:
            return nullptr;
        case scene::Medium::Kind::UniformGrid:
            return std::make_unique<UniformDensityGrid>(medium);
        case scene::Medium::Kind::Sparse:
            return std::make_unique<SparseDensityGrid>(medium);
    }
    return nullptr;
}

// ---------------------------------------------------------------------------------------------
// MajorantGrid

namespace {
// The coordinate of grid plane k (0..res) along an axis: the one formula the cell boxes and the
// DDA share.
float plane(const Bounds& b, int axis, int k, int res) {
    if (k >= res) return b.hi[axis];
    return b.lo[axis] + (b.hi[axis] - b.lo[axis]) * (float(k) / float(res));
}
}  // namespace

MajorantGrid::MajorantGrid(const DensityGrid& grid, int res)
    : res_(std::max(1, res)), bounds_(grid.bounds()) {
    max_.assign(size_t(res_) * size_t(res_) * size_t(res_), 0.0f);
    if (bounds_.empty()) return;
    for (int z = 0; z < res_; ++z)
        for (int y = 0; y < res_; ++y)
            for (int x = 0; x < res_; ++x) {
                Bounds cell;
                const int c[3] = {x, y, z};
                for (int a = 0; a < 3; ++a) {
                    // A little slack so that points the DDA puts in this cell, up to rounding,
                    // lie inside the box whose maximum it reports.
                    const float lo = plane(bounds_, a, c[a], res_), hi = plane(bounds_, a, c[a] + 1, res_);
                    const float eps = 1e-3f * (hi - lo) + 1e-6f * std::max(std::abs(lo), std::abs(hi));
                    cell.lo[a] = lo - eps;
                    cell.hi[a] = hi + eps;
                }
                max_[size_t((z * res_ + y) * res_ + x)] = grid.max_density(cell);
            }
}

MajorantGrid::Segments MajorantGrid::segments(Vec3 o, Vec3 d, float t0, float t1) const {
    Segments s;
    s.grid_ = this;
    s.done_ = true;
    if (bounds_.empty() || !finite3(o) || !finite3(d) || std::isnan(t0) || std::isnan(t1)) return s;
    // Slab test against the bounds.
    float tmin = t0, tmax = t1;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0f) {
            if (o[a] < bounds_.lo[a] || o[a] > bounds_.hi[a]) return s;
            continue;
        }
        float tn = (bounds_.lo[a] - o[a]) / d[a], tf = (bounds_.hi[a] - o[a]) / d[a];
        if (tn > tf) std::swap(tn, tf);
        tmin = std::max(tmin, tn);
        tmax = std::min(tmax, tf);
    }
    if (!(tmin < tmax)) return s;
    s.t_ = tmin;
    s.t_end_ = tmax;
    const Vec3 p = o + d * tmin;
    for (int a = 0; a < 3; ++a) {
        const float ext = bounds_.hi[a] - bounds_.lo[a];
        int c = ext > 0 ? int(std::floor((p[a] - bounds_.lo[a]) / ext * float(res_))) : 0;
        c = std::clamp(c, 0, res_ - 1);
        s.cell_[a] = c;
        if (d[a] > 0.0f) {
            s.step_[a] = 1;
            s.out_[a] = res_;
            s.next_t_[a] = (plane(bounds_, a, c + 1, res_) - o[a]) / d[a];
        } else if (d[a] < 0.0f) {
            s.step_[a] = -1;
            s.out_[a] = -1;
            s.next_t_[a] = (plane(bounds_, a, c, res_) - o[a]) / d[a];
        } else {
            s.step_[a] = 0;
            s.out_[a] = -2;
            s.next_t_[a] = kInfinity;
        }
        s.delta_t_[a] =
            d[a] != 0.0f ? (bounds_.hi[a] - bounds_.lo[a]) / float(res_) / std::abs(d[a]) : kInfinity;
    }
    s.o_ = o;
    s.d_ = d;
    s.done_ = false;
    return s;
}

bool MajorantGrid::Segments::next(float& ta, float& tb, float& max_density) {
    while (!done_) {
        int axis = 0;
        if (next_t_[1] < next_t_[axis]) axis = 1;
        if (next_t_[2] < next_t_[axis]) axis = 2;
        const float a = t_;
        float b = std::min(std::max(next_t_[axis], a), t_end_);
        const float m = grid_->max_at(cell_[0], cell_[1], cell_[2]);
        // Advance to the next cell (or finish).
        if (next_t_[axis] >= t_end_) {
            done_ = true;
        } else {
            cell_[axis] += step_[axis];
            if (cell_[axis] == out_[axis]) {
                done_ = true;  // left the grid: the slab test's end, up to rounding
                b = t_end_;
            } else {
                const int k = step_[axis] > 0 ? cell_[axis] + 1 : cell_[axis];
                next_t_[axis] = (plane(grid_->bounds_, axis, k, grid_->res_) - o_[axis]) / d_[axis];
            }
        }
        t_ = b;
        if (b > a) {
            ta = a;
            tb = b;
            max_density = m;
            return true;
        }
    }
    return false;
}

}  // namespace phos::shading
