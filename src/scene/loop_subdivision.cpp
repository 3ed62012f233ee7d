// Loop subdivision (Loop 1987) with pbrt-v4's limit positions and limit normals: the mesh is held
// as triangles with, for each directed edge, the directed edge running the other way (its twin),
// rebuilt at each level; a vertex's one-ring is walked through the twins.
#include "scene/loop_subdivision.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "core/error.h"

namespace phos::scene {
namespace {

// Double precision: the weights are applied level after level.
struct P3 {
    double x = 0, y = 0, z = 0;
    P3() = default;
    P3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    P3 operator+(P3 o) const { return {x + o.x, y + o.y, z + o.z}; }
    P3 operator-(P3 o) const { return {x - o.x, y - o.y, z - o.z}; }
    P3 operator*(double s) const { return {x * s, y * s, z * s}; }
    P3& operator+=(P3 o) { return *this = *this + o; }
};
P3 cross(P3 a, P3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(P3 a, P3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

using Face = std::array<uint32_t, 3>;
constexpr int64_t kNone = -1;

// Corners are 3 f + k: vertex k of face f, and also the directed edge from it to vertex k + 1.
inline int64_t next_corner(int64_t c) { return c - c % 3 + (c % 3 + 1) % 3; }
inline int64_t prev_corner(int64_t c) { return c - c % 3 + (c % 3 + 2) % 3; }

struct Mesh {
    std::vector<P3> p;
    std::vector<Face> faces;
    std::vector<int64_t> twin;       // per corner: the corner whose edge runs the other way, or kNone
    std::vector<int64_t> corner;     // per vertex: one corner at it
    std::vector<uint32_t> faces_at;  // per vertex: how many corners are at it
    // Per vertex: the one-ring (in pbrt's order: for a boundary vertex the two boundary neighbours
    // first and last), in ring_data[ring_start[v] .. ring_start[v + 1]).
    std::vector<size_t> ring_start;
    std::vector<uint32_t> ring_data;
    std::vector<uint8_t> boundary;

    uint32_t at(int64_t c) const { return faces[size_t(c / 3)][size_t(c % 3)]; }
    size_t valence(uint32_t v) const { return ring_start[v + 1] - ring_start[v]; }
    const uint32_t* ring(uint32_t v) const { return ring_data.data() + ring_start[v]; }
};

// Twins, a corner per vertex and the one-rings of every vertex.
void build_topology(Mesh& m) {
    const size_t nc = 3 * m.faces.size(), nv = m.p.size();
    std::unordered_map<uint64_t, int64_t> directed;
    directed.reserve(nc);
    const auto key = [](uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; };
    m.corner.assign(nv, kNone);
    m.faces_at.assign(nv, 0);
    for (size_t c = 0; c < nc; ++c) {
        const uint32_t a = m.at(int64_t(c)), b = m.at(next_corner(int64_t(c)));
        if (!directed.emplace(key(a, b), int64_t(c)).second)
            throw InputError("the edge from vertex " + std::to_string(a) + " to vertex " + std::to_string(b) +
                             " belongs to two triangles that run it the same way (an edge of more than two "
                             "triangles, or triangles oriented inconsistently)");
        m.corner[a] = int64_t(c);
        ++m.faces_at[a];
    }
    m.twin.assign(nc, kNone);
    for (size_t c = 0; c < nc; ++c) {
        const auto it = directed.find(key(m.at(next_corner(int64_t(c))), m.at(int64_t(c))));
        if (it != directed.end()) m.twin[c] = it->second;
    }

    m.ring_start.assign(nv + 1, 0);
    m.ring_data.clear();
    m.ring_data.reserve(nc + nv);
    m.boundary.assign(nv, 0);
    for (uint32_t v = 0; v < nv; ++v) {
        m.ring_start[v] = m.ring_data.size();
        const int64_t c0 = m.corner[v];
        // Around v through the face across the edge (v, next): interior if that comes back to c0.
        uint32_t visited = 0;
        int64_t c = c0;
        bool open = false;
        do {
            m.ring_data.push_back(m.at(next_corner(c)));
            ++visited;
            const int64_t t = m.twin[size_t(c)];
            if (t == kNone) {
                open = true;
                break;
            }
            c = next_corner(t);
        } while (c != c0 && visited <= m.faces_at[v]);
        if (open) {
            // A boundary vertex: go forward to the last face, then walk back across the other edges.
            m.ring_data.resize(m.ring_start[v]);
            m.boundary[v] = 1;
            c = c0;
            for (uint32_t steps = 0; m.twin[size_t(c)] != kNone && steps <= m.faces_at[v]; ++steps)
                c = next_corner(m.twin[size_t(c)]);
            m.ring_data.push_back(m.at(next_corner(c)));
            visited = 0;
            while (c != kNone && visited <= m.faces_at[v]) {
                m.ring_data.push_back(m.at(prev_corner(c)));
                ++visited;
                c = m.twin[size_t(prev_corner(c))];
            }
        }
        if (visited != m.faces_at[v])
            throw InputError("the triangles at vertex " + std::to_string(v) +
                             " do not form one fan (a non-manifold vertex)");
    }
    m.ring_start[nv] = m.ring_data.size();
}

// Warren's weight for an interior vertex of valence n (pbrt's beta).
double beta(size_t n) { return n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * double(n)); }

// (1 - n w) p + w (sum of the ring): the even rule (w = beta) and the limit rule (w = gamma).
P3 weight_ring(const Mesh& m, uint32_t v, double w) {
    const size_t n = m.valence(v);
    P3 sum;
    for (size_t i = 0; i < n; ++i) sum += m.p[m.ring(v)[i]];
    return m.p[v] * (1 - double(n) * w) + sum * w;
}

// (1 - 2 w) p + w (the two boundary neighbours).
P3 weight_boundary(const Mesh& m, uint32_t v, double w) {
    const size_t n = m.valence(v);
    return m.p[v] * (1 - 2 * w) + (m.p[m.ring(v)[0]] + m.p[m.ring(v)[n - 1]]) * w;
}

// One level: four triangles per triangle.
void refine(Mesh& m) {
    const size_t nv = m.p.size(), nf = m.faces.size();
    std::vector<P3> p(nv);
    for (uint32_t v = 0; v < nv; ++v)
        p[v] = m.boundary[v] ? weight_boundary(m, v, 1.0 / 8.0) : weight_ring(m, v, beta(m.valence(v)));
    // The odd vertex of each edge, made by the first of its two corners.
    std::vector<uint32_t> odd(3 * nf);
    for (size_t c = 0; c < 3 * nf; ++c) {
        const int64_t t = m.twin[c];
        if (t != kNone && size_t(t) < c) {
            odd[c] = odd[size_t(t)];
            continue;
        }
        const P3 a = m.p[m.at(int64_t(c))], b = m.p[m.at(next_corner(int64_t(c)))];
        P3 q;
        if (t == kNone) {
            q = (a + b) * 0.5;
        } else {
            const P3 c_opp = m.p[m.at(prev_corner(int64_t(c)))], d_opp = m.p[m.at(prev_corner(t))];
            q = (a + b) * (3.0 / 8.0) + (c_opp + d_opp) * (1.0 / 8.0);
        }
        odd[c] = uint32_t(p.size());
        p.push_back(q);
    }
    std::vector<Face> faces;
    faces.reserve(4 * nf);
    for (size_t f = 0; f < nf; ++f) {
        const Face& v = m.faces[f];
        const uint32_t e0 = odd[3 * f], e1 = odd[3 * f + 1], e2 = odd[3 * f + 2];
        faces.push_back({v[0], e0, e2});
        faces.push_back({v[1], e1, e0});
        faces.push_back({v[2], e2, e1});
        faces.push_back({e0, e1, e2});
    }
    m.p = std::move(p);
    m.faces = std::move(faces);
    build_topology(m);
}

// The limit surface's tangents at a vertex (Halstead, Kass and DeRose 1993; pbrt's masks), from the
// limit positions of the vertex and its ring.
P3 limit_normal(const Mesh& m, uint32_t v) {
    const size_t n = m.valence(v);
    const uint32_t* r = m.ring(v);
    const double pi = 3.14159265358979323846;
    P3 s, t;
    if (!m.boundary[v]) {
        for (size_t j = 0; j < n; ++j) {
            s += m.p[r[j]] * std::cos(2 * pi * double(j) / double(n));
            t += m.p[r[j]] * std::sin(2 * pi * double(j) / double(n));
        }
    } else {
        s = m.p[r[n - 1]] - m.p[r[0]];
        const P3 pv = m.p[v];
        if (n == 2) {
            t = m.p[r[0]] + m.p[r[1]] - pv * 2;
        } else if (n == 3) {
            t = m.p[r[1]] - pv;
        } else if (n == 4) {
            t = m.p[r[0]] * -1 + m.p[r[1]] * 2 + m.p[r[2]] * 2 - m.p[r[3]] - pv * 2;
        } else {
            const double theta = pi / double(n - 1);
            t = (m.p[r[0]] + m.p[r[n - 1]]) * std::sin(theta);
            for (size_t k = 1; k + 1 < n; ++k)
                t += m.p[r[k]] * ((2 * std::cos(theta) - 2) * std::sin(double(k) * theta));
            t = t * -1;
        }
    }
    return cross(s, t);
}

}  // namespace

TriangleMesh loop_subdivide(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices,
                            int levels) {
    if (levels < 0) throw InputError("the number of levels (" + std::to_string(levels) + ") is negative");
    if (indices.empty() || indices.size() % 3 != 0)
        throw InputError("the number of indices (" + std::to_string(indices.size()) +
                         ") is not a positive multiple of 3");
    // Only the vertices some triangle uses, renumbered in order of first use.
    Mesh m;
    std::vector<int64_t> remap(positions.size(), kNone);
    for (size_t i = 0; i < indices.size(); i += 3) {
        Face f;
        for (int k = 0; k < 3; ++k) {
            const uint32_t idx = indices[i + size_t(k)];
            if (idx >= positions.size())
                throw InputError("vertex index " + std::to_string(idx) + " out of range (" +
                                 std::to_string(positions.size()) + " vertices)");
            if (remap[idx] == kNone) {
                remap[idx] = int64_t(m.p.size());
                const Vec3 q = positions[idx];
                m.p.emplace_back(q.x, q.y, q.z);
            }
            f[size_t(k)] = uint32_t(remap[idx]);
        }
        if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2])
            throw InputError("triangle " + std::to_string(i / 3) + " repeats a vertex");
        m.faces.push_back(f);
    }
    build_topology(m);
    for (int level = 0; level < levels; ++level) refine(m);

    // Every vertex to its limit position, then the normals from the limit positions.
    std::vector<P3> limit(m.p.size());
    for (uint32_t v = 0; v < m.p.size(); ++v)
        limit[v] = m.boundary[v]
                       ? weight_boundary(m, v, 1.0 / 5.0)
                       : weight_ring(m, v, 1.0 / (double(m.valence(v)) + 3.0 / (8.0 * beta(m.valence(v)))));
    m.p = std::move(limit);
    // The winding's side at each vertex (area-weighted face normals), for degenerate tangents.
    std::vector<P3> winding(m.p.size());
    for (const Face& f : m.faces) {
        const P3 n = cross(m.p[f[1]] - m.p[f[0]], m.p[f[2]] - m.p[f[0]]);
        for (uint32_t v : f) winding[v] += n;
    }
    TriangleMesh out;
    out.positions.reserve(m.p.size());
    out.normals.reserve(m.p.size());
    for (uint32_t v = 0; v < m.p.size(); ++v) {
        // pbrt's S x T, with the ring in pbrt's order, points against the winding; where the
        // tangents are degenerate, the winding's normal reversed likewise.
        P3 n = limit_normal(m, v);
        double len = std::sqrt(dot(n, n));
        if (!(len > 0) || !std::isfinite(len)) n = winding[v] * -1, len = std::sqrt(dot(n, n));
        n = len > 0 ? n * (1 / len) : P3(0, 0, 1);
        out.positions.emplace_back(float(m.p[v].x), float(m.p[v].y), float(m.p[v].z));
        out.normals.emplace_back(float(n.x), float(n.y), float(n.z));
    }
    out.indices.reserve(3 * m.faces.size());
    for (const Face& f : m.faces) out.indices.insert(out.indices.end(), f.begin(), f.end());
    return out;
}

}  // namespace phos::scene
