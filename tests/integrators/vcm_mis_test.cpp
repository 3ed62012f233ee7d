// The recursive MIS weights of bdpt and vcm (integrators/vcm_mis.h) against their definition: for
// one explicit path, every strategy that can make it is replayed through the same recursion the
// integrator runs (light subpath from the light, camera subpath from the camera, then the
// connection, the emitter hit, direct light sampling, light tracing or the merge), and the weights
// of all of them must add up to 1 (Veach 1997, eq. 9.3's condition for an unbiased combination).
// Paths have 1 to 5 inner vertices, each on a Lambertian surface, a mirror-like delta surface or in
// an isotropic medium, lit by an area or a point light; merging is on (vcm, with and without
// merging next to the light, at every camera vertex or only at the camera's first non-delta one)
// or off (bpt); direct light takes one or several samples at the camera's first vertex. A wrong
// term in any update, a missing strategy or one counted twice moves the sum away from 1.
#include "integrators/vcm_mis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/vec.h"

namespace phos::integrators::vcm {
namespace {

constexpr float kPi_ = 3.14159265358979f;

struct PathVertex {
    Vec3 p;
    Vec3 n;  // unit normal (surfaces); unused in media
    bool medium = false;
    bool delta = false;  // a delta surface (mirror): no connection, light sample or merge here
};

// The strategy set under test: the integrator's Iteration in small.
struct Strategies {
    bool merge = false;         // vcm (else bpt)
    float eta = 0;              // pi r^2 N_light
    bool merge_direct = false;  // merging next to the light
    bool merge_every = true;    // merging at every camera vertex, else at the first non-delta one
    int direct_samples = 1;     // light samples at the camera's first non-delta vertex
    // Merging at the first non-delta vertex only: the probability that the camera subpath goes on
    // past that vertex (--vcm-continue; the integrator takes it at Lambert surfaces only).
    float go_on = 1;
};

struct TestPath {
    std::vector<PathVertex> x;  // x[0] on the light, x[k] the camera
    bool point_light = false;
    float light_area = 0.3f;         // area light: pdf_pos = 1 / area
    Vec3 camera_forward;             // pinhole: direction pdf 1 / (A cos^3)
    float camera_plane_area = 0.8f;  // A
};

float cos_at(const PathVertex& v, Vec3 dir) { return v.medium ? 1.0f : std::fabs(dot(v.n, dir)); }
// Scattering pdf at inner vertex v for direction `out` (Lambert: cos / pi; medium: 1 / 4 pi).
float pdf_at(const PathVertex& v, Vec3 out) { return v.medium ? 1 / (4 * kPi_) : cos_at(v, out) / kPi_; }
Vec3 dir(const PathVertex& a, const PathVertex& b) { return normalize(b.p - a.p); }
float dist(const PathVertex& a, const PathVertex& b) { return length(b.p - a.p); }

struct Light {
    float direct_pdf_a, emit_pdf_pos;
    bool delta;
};

// The light's emission density from x0 towards `to` (position x direction).
float emit_pdf(const TestPath& t, Vec3 to) {
    if (t.point_light) return 1 / (4 * kPi_);
    return (1 / t.light_area) * std::max(0.0f, dot(t.x[0].n, to)) / kPi_;
}
float direct_pdf_a(const TestPath& t) { return t.point_light ? 1.0f : 1 / t.light_area; }
float camera_pdf(const TestPath& t, Vec3 d) {
    const float c = dot(d, t.camera_forward);
    return 1 / (t.camera_plane_area * c * c * c);
}

// Whether x[i] may merge at all: a non-delta surface, and not next to the light (x[1]) unless
// merging there is on.
bool can_merge(const TestPath& t, int i, const Strategies& s) {
    const PathVertex& v = t.x[size_t(i)];
    return s.merge && !v.medium && !v.delta && (s.merge_direct || i >= 2);
}
// Whether x[i] is the camera subpath's first non-delta vertex: every vertex between it and the
// camera is a delta surface.
bool first_non_delta(const TestPath& t, int i) {
    for (size_t j = size_t(i) + 1; j + 1 < t.x.size(); ++j)
        if (!t.x[j].delta) return false;
    return true;
}

// The factor of the camera subpath's density of going on from x[i]: go_on where x[i] is its first
// non-delta vertex on a surface and merging is there only, else 1.
float go_on_at(const TestPath& t, int i, const Strategies& st) {
    const PathVertex& v = t.x[size_t(i)];
    return st.merge && !st.merge_every && !v.medium && !v.delta && first_non_delta(t, i) ? st.go_on : 1.0f;
}

// The light subpath's state at x[i] (arrived, before scattering at x[i]), i >= 1. Merging at x[1]
// (next to the light) only with `merge_direct`, as the integrator marks light vertices; no merging
// terms at all on the light side when merging is only at the camera's first non-delta vertex
// (trace_light_path's merge_terms).
SubpathMis light_state(const TestPath& t, int i, const MisFactors& f, const Strategies& st) {
    const Vec3 d01 = dir(t.x[0], t.x[1]);
    SubpathMis m = start_light(direct_pdf_a(t), emit_pdf(t, d01), t.point_light ? 1.0f : dot(t.x[0].n, d01),
                               t.point_light, false, f);
    for (int j = 1; j <= i; ++j) {
        arrive(m, dist(t.x[j - 1], t.x[j]), cos_at(t.x[j], dir(t.x[j], t.x[j - 1])), true);
        if (j == i) break;
        const Vec3 out = dir(t.x[j], t.x[j + 1]), back = dir(t.x[j], t.x[j - 1]);
        if (t.x[j].delta)
            scatter_delta(m, cos_at(t.x[j], out));
        else
            scatter(m, cos_at(t.x[j], out), pdf_at(t.x[j], out), pdf_at(t.x[j], back),
                    st.merge_every && can_merge(t, j, st), f);
    }
    return m;
}

// The camera subpath's state at x[i] (arrived), i <= k - 1; i == 0 reaches the light. Like the
// integrator, the camera subpath does not know which vertex is next to the light: every non-delta
// surface vertex (or only the first one) is mergeable when it scatters (the emitter hit's weight
// takes the last one out).
SubpathMis camera_state(const TestPath& t, int i, const MisFactors& f, const Strategies& st) {
    const int k = int(t.x.size()) - 1;
    SubpathMis m = start_camera(camera_pdf(t, dir(t.x[k], t.x[k - 1])));
    for (int j = k - 1; j >= i; --j) {
        arrive(m, dist(t.x[j + 1], t.x[j]),
               j == 0 ? (t.point_light ? 1.0f : dot(t.x[0].n, dir(t.x[0], t.x[1])))
                      : cos_at(t.x[j], dir(t.x[j], t.x[j + 1])),
               true);
        if (j == i) break;
        const Vec3 out = dir(t.x[j], t.x[j - 1]), back = dir(t.x[j], t.x[j + 1]);
        const PathVertex& v = t.x[size_t(j)];
        if (v.delta)
            scatter_delta(m, cos_at(v, out));
        else
            scatter(m, cos_at(v, out), pdf_at(v, out) * go_on_at(t, j, st), pdf_at(v, back),
                    st.merge && !v.medium && (st.merge_every || first_non_delta(t, j)), f);
    }
    return m;
}

// Sum of the weights of every strategy that makes path t; `count` (if given) receives how many
// strategies there are (none for L S D S E paths with a point light and no merging).
double weight_sum(const TestPath& t, const Strategies& st, int* count = nullptr) {
    const MisFactors f = MisFactors::of(true, st.merge, st.eta);
    const int k = int(t.x.size()) - 1;  // x[k] is the camera
    const auto delta = [&](int i) { return t.x[size_t(i)].delta; };
    // Merging at x[i] as a strategy: seen from the camera side (x[i] the camera subpath's last
    // vertex, or the light subpath's vertex next to the camera in light tracing), and from the
    // light side of a connection (x[i] the light subpath's last vertex, a camera vertex beyond).
    const auto merge_camera = [&](int i) {
        return can_merge(t, i, st) && (st.merge_every || first_non_delta(t, i));
    };
    const auto merge_light = [&](int i) { return can_merge(t, i, st) && st.merge_every; };
    // Light sampling at the camera's first non-delta vertex takes direct_samples samples: paths
    // whose vertex next to the light is that vertex count that strategy direct_samples times
    // (multi-sample MIS).
    const float n = !delta(1) && first_non_delta(t, 1) ? float(st.direct_samples) : 1.0f;
    double sum = 0;
    int strategies = 0;
    // s = 0: the camera subpath hits the light (impossible for a point light).
    if (!t.point_light) {
        const SubpathMis c = camera_state(t, 0, f, st);
        ++strategies;
        sum += emitter_hit_weight(c, n * direct_pdf_a(t), emit_pdf(t, dir(t.x[0], t.x[1])), st.merge_direct);
    }
    // s = 1: direct light sampling at x[1] from the camera side.
    if (!delta(1)) {
        const SubpathMis c = camera_state(t, 1, f, st);
        const Vec3 to_light = dir(t.x[1], t.x[0]), back = dir(t.x[1], t.x[2]);
        const float d = dist(t.x[0], t.x[1]);
        const float cos_light = t.point_light ? 1.0f : dot(t.x[0].n, -to_light);
        const float direct_w = t.point_light ? 0.0f : n * direct_pdf_a(t) * d * d / cos_light;
        ++strategies;
        sum += direct_light_weight(c, pdf_at(t.x[1], to_light) * go_on_at(t, 1, st), pdf_at(t.x[1], back),
                                   n * direct_pdf_a(t), emit_pdf(t, -to_light), direct_w, merge_camera(1),
                                   cos_at(t.x[1], to_light) / (d * d), f);
    }
    // Inner connections: light subpath to x[s-1], camera subpath to x[s], s = 2 .. k - 1.
    for (int s = 2; s <= k - 1; ++s) {
        if (delta(s - 1) || delta(s)) continue;
        const SubpathMis l = light_state(t, s - 1, f, st), c = camera_state(t, s, f, st);
        const PathVertex &a = t.x[size_t(s - 1)], &b = t.x[size_t(s)];
        const Vec3 ab = dir(a, b);
        const float d2 = dist(a, b) * dist(a, b);
        const float camera_pdf_a = go_on_at(t, s, st) * pdf_at(b, -ab) * cos_at(a, ab) / d2;  // b reaching a
        const float light_pdf_a = pdf_at(a, ab) * cos_at(b, ab) / d2;  // a's BSDF reaching b
        const float w_l =
            connect_side(l, camera_pdf_a, pdf_at(a, dir(a, t.x[size_t(s - 2)])), merge_light(s - 1), f);
        const float w_c =
            connect_side(c, light_pdf_a, pdf_at(b, dir(b, t.x[size_t(s + 1)])), merge_camera(s), f);
        ++strategies;
        sum += 1 / (w_l + 1 + w_c);
    }
    // t = 1: light tracing from x[k-1] onto the camera (x[k-1] is the camera's first vertex).
    if (!delta(k - 1)) {
        SubpathMis l = light_state(t, k - 1, f, st);
        if (k == 2) l.dVCM *= mis(n);
        const PathVertex& a = t.x[size_t(k - 1)];
        const Vec3 to_cam = dir(a, t.x[size_t(k)]);
        const float d = dist(a, t.x[size_t(k)]);
        const float camera_pdf_a = camera_pdf(t, -to_cam) * cos_at(a, to_cam) / (d * d);
        const float rev = pdf_at(a, dir(a, t.x[size_t(k - 2)])) * go_on_at(t, k - 1, st);
        ++strategies;
        sum += 1 / (1 + connect_side(l, camera_pdf_a, rev, merge_camera(k - 1), f));
    }
    // Merges at every inner vertex where merging is a strategy.
    for (int i = 1; i <= k - 1; ++i) {
        if (!merge_camera(i)) continue;
        SubpathMis l = light_state(t, i, f, st);
        if (i == 1) l.dVCM *= mis(n);  // merging next to the light: as light tracing
        const SubpathMis c = camera_state(t, i, f, st);
        const Vec3 to_light_prev = dir(t.x[size_t(i)], t.x[size_t(i - 1)]);
        const Vec3 to_cam_prev = dir(t.x[size_t(i)], t.x[size_t(i + 1)]);
        ++strategies;
        sum += merge_weight(c, l, pdf_at(t.x[size_t(i)], to_light_prev) * go_on_at(t, i, st),
                            pdf_at(t.x[size_t(i)], to_cam_prev), f);
    }
    if (count) *count = strategies;
    return sum;
}

// A random path with `inner` inner vertices: points in a box, surface normals facing both
// neighbours (so every cosine is positive), some vertices in a medium.
TestPath random_path(uint64_t seed, int inner, bool point_light, bool media, bool deltas = false) {
    Sampler rng(seed, 0x6d6973ULL, uint64_t(inner),
                uint64_t(point_light) * 2 + uint64_t(media) + (deltas ? 0x100u : 0u));
    TestPath t;
    t.point_light = point_light;
    for (int i = 0; i < inner + 2; ++i) {
        PathVertex v;
        v.p = Vec3(rng.next(), rng.next(), rng.next()) * 2.0f - Vec3(1.0f);
        v.p.z += 3.0f * float(i) / float(inner + 1);  // spread along z: no two points coincide
        v.medium = media && i > 0 && i <= inner && rng.next() < 0.5f;
        v.delta = deltas && !v.medium && i > 0 && i <= inner && rng.next() < 0.4f;
        t.x.push_back(v);
    }
    for (size_t i = 0; i < t.x.size(); ++i) {
        Vec3 sum(0.0f);
        if (i > 0) sum += dir(t.x[i], t.x[i - 1]);
        if (i + 1 < t.x.size()) sum += dir(t.x[i], t.x[i + 1]);
        t.x[i].n = normalize(sum);
    }
    t.camera_forward = dir(t.x.back(), t.x[t.x.size() - 2]);
    return t;
}

TEST(VcmMis, WeightsOfAllStrategiesSumToOne) {
    int checked = 0;
    for (int inner = 1; inner <= 5; ++inner)
        for (int point = 0; point < 2; ++point)
            for (int media = 0; media < 2; ++media)
                for (uint64_t seed = 0; seed < 20; ++seed) {
                    const TestPath t = random_path(seed, inner, point != 0, media != 0);
                    const auto where = [&] {
                        return ", inner " + std::to_string(inner) + " point " + std::to_string(point) +
                               " media " + std::to_string(media) + " seed " + std::to_string(seed);
                    };
                    // bpt: connections only, with one and with four light samples at the first vertex.
                    for (int n : {1, 4})
                        EXPECT_NEAR(weight_sum(t, {false, 0.0f, false, true, n}), 1.0, 2e-4)
                            << "bpt, direct samples " << n << where();
                    // vcm with a small and a large merging area.
                    for (float eta : {1e-3f, 0.5f, 40.0f})
                        for (bool direct : {false, true})
                            for (bool every : {true, false})
                                for (int n : {1, 3})
                                    for (float go_on : {1.0f, 0.2f, 1e-3f}) {
                                        if (every && go_on < 1) continue;
                                        EXPECT_NEAR(weight_sum(t, {true, eta, direct, every, n, go_on}), 1.0,
                                                    2e-4)
                                            << "vcm eta " << eta
                                            << (direct ? ", merging next to the light" : "")
                                            << (every ? ", merging everywhere"
                                                      : ", merging at the first vertex")
                                            << ", direct samples " << n << ", going on " << go_on << where();
                                    }
                    ++checked;
                }
    EXPECT_EQ(checked, 400);
}

// Paths through delta surfaces (mirrors): strategies end only at non-delta vertices, and merging
// at the camera's first non-delta vertex is found behind a chain of mirrors.
TEST(VcmMis, WeightsSumToOneThroughDeltaVertices) {
    int checked = 0, first_behind_mirror = 0, merging_only = 0;
    for (int inner = 2; inner <= 5; ++inner)
        for (int point = 0; point < 2; ++point)
            for (uint64_t seed = 0; seed < 40; ++seed) {
                const TestPath t = random_path(seed, inner, point != 0, false, true);
                int deltas = 0;
                for (const PathVertex& v : t.x) deltas += v.delta ? 1 : 0;
                if (deltas == 0 || deltas == inner) continue;  // no delta, or nothing can make it
                first_behind_mirror += t.x[t.x.size() - 2].delta ? 1 : 0;
                for (int n : {1, 2}) {
                    int strategies = 0;
                    const double bpt = weight_sum(t, {false, 0.0f, false, true, n}, &strategies);
                    if (strategies == 0) {  // only merging makes it: a point light's S D S
                        ++merging_only;
                        continue;
                    }
                    EXPECT_NEAR(bpt, 1.0, 2e-4)
                        << "bpt, inner " << inner << " point " << point << " seed " << seed;
                }
                for (float eta : {1e-3f, 0.5f, 40.0f})
                    for (bool every : {true, false})
                        for (float go_on : {1.0f, 1e-3f}) {
                            if (every && go_on < 1) continue;
                            EXPECT_NEAR(weight_sum(t, {true, eta, false, every, 2, go_on}), 1.0, 2e-4)
                                << "vcm eta " << eta << (every ? " everywhere" : " first") << ", going on "
                                << go_on << ", inner " << inner << " point " << point << " seed " << seed;
                        }
                ++checked;
            }
    EXPECT_GT(checked, 150);
    EXPECT_GT(first_behind_mirror, 40);  // the camera's first vertex is a mirror often enough
    EXPECT_GT(merging_only, 0);          // and some paths only vcm can make
}

// With merging at the camera's first non-delta vertex only, the merging area eta enters the light
// subpath's state only as the factor 1 / eta^2 of dVM (its dVCM and dVC hold no merging term), so
// vcm traces light subpaths with vc = 1 and merging multiplies dVM by the merging pixel's own vc
// (per-pixel radii; camera_subpath.cpp). Its merging weights are the ones of the light state traced
// with that pixel's eta; dVC and dVCM are the same bits.
TEST(VcmMis, FirstVertexMergingFactorsEtaOutOfTheLightSubpath) {
    int checked = 0;
    for (int inner = 1; inner <= 5; ++inner)
        for (uint64_t seed = 0; seed < 20; ++seed) {
            const TestPath t = random_path(seed, inner, seed % 2 == 1, seed % 3 == 0);
            const int k = int(t.x.size()) - 1;
            for (float eta : {1e-3f, 0.5f, 40.0f}) {
                const Strategies st{true, eta, false, false, 2};
                const MisFactors f = MisFactors::of(true, true, eta), unit{0.0f, 1.0f};
                for (int i = 1; i <= k - 1; ++i) {
                    const SubpathMis a = light_state(t, i, f, st), b = light_state(t, i, unit, st);
                    EXPECT_EQ(a.dVCM, b.dVCM);
                    EXPECT_EQ(a.dVC, b.dVC);
                    EXPECT_NEAR(b.dVM * f.vc, a.dVM, 1e-5 * std::fabs(a.dVM))
                        << "eta " << eta << ", vertex " << i;
                    if (t.x[size_t(i)].medium || t.x[size_t(i)].delta) continue;
                    // Merging there as the camera's first vertex (the camera state as it arrives).
                    const SubpathMis c = camera_state(t, i, f, st);
                    SubpathMis scaled = b;
                    scaled.dVM *= f.vc;
                    const Vec3 in = dir(t.x[size_t(i)], t.x[size_t(i - 1)]),
                               out = dir(t.x[size_t(i)], t.x[size_t(i + 1)]);
                    const float wa =
                        merge_weight(c, a, pdf_at(t.x[size_t(i)], in), pdf_at(t.x[size_t(i)], out), f);
                    const float wb =
                        merge_weight(c, scaled, pdf_at(t.x[size_t(i)], in), pdf_at(t.x[size_t(i)], out), f);
                    EXPECT_NEAR(wb / wa, 1.0, 1e-5) << "eta " << eta << ", vertex " << i;
                    ++checked;
                }
            }
        }
    EXPECT_GT(checked, 300);
}

// The weights are not trivially 1: on a path where light tracing and the emitter hit compete,
// neither takes everything (power heuristic, not a winner-takes-all choice).
TEST(VcmMis, StrategiesShareThePath) {
    const TestPath t = random_path(3, 1, false, false);
    const MisFactors f = MisFactors::of(true, false, 0);
    const SubpathMis c = camera_state(t, 0, f, Strategies{});
    const float w0 = emitter_hit_weight(c, direct_pdf_a(t), emit_pdf(t, dir(t.x[0], t.x[1])));
    EXPECT_GT(w0, 0.001f);
    EXPECT_LT(w0, 0.999f);
}

}  // namespace
}  // namespace phos::integrators::vcm
