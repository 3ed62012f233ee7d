// Ray throughput of the Embree layer (single thread): closest-hit and occlusion queries for camera
// and random rays on a procedural mesh scene of ~240k triangles, plus an analytic-sphere scene.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "accel/embree_scene.h"
#include "core/rng.h"

namespace {

using namespace phos;

// Closed UV-sphere / torus meshes, counter-clockwise from outside.
scene::Shape uv_sphere(Vec3 c, float r, int nu, int nv) {
    scene::Shape s;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const float th = kPi * float(j) / float(nv), ph = 2 * kPi * float(i) / float(nu);
            s.mesh.positions.push_back(
                c + Vec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)) * r);
        }
    auto id = [&](int i, int j) { return uint32_t(j * nu + i % nu); };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            if (j > 0) s.mesh.indices.insert(s.mesh.indices.end(), {id(i, j), id(i + 1, j), id(i, j + 1)});
            if (j + 1 < nv)
                s.mesh.indices.insert(s.mesh.indices.end(), {id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return s;
}

scene::Shape torus(Vec3 c, float R, float r, int nu, int nv) {
    scene::Shape s;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const float u = 2 * kPi * float(i) / float(nu), v = 2 * kPi * float(j) / float(nv);
            s.mesh.positions.push_back(c + Vec3((R + r * std::cos(v)) * std::cos(u), r * std::sin(v),
                                                (R + r * std::cos(v)) * std::sin(u)));
        }
    auto id = [&](int i, int j) { return uint32_t((j % nv) * nu + i % nu); };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            s.mesh.indices.insert(s.mesh.indices.end(), {id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i, j),
                                                         id(i + 1, j + 1), id(i + 1, j)});
    return s;
}

// A 6x6 grid of alternating finely tessellated spheres and tori standing on a floor slab.
const scene::Scene& mesh_scene() {
    static const scene::Scene sc = [] {
        scene::Scene s;
        for (int x = 0; x < 6; ++x)
            for (int z = 0; z < 6; ++z) {
                const Vec3 c(3.0f * float(x) - 7.5f, 1.2f, 3.0f * float(z) - 7.5f);
                s.shapes.push_back((x + z) % 2 ? uv_sphere(c, 1.2f, 64, 32) : torus(c, 1.0f, 0.35f, 96, 48));
            }
        scene::Shape floor;
        floor.kind = scene::Shape::Kind::Box;
        floor.box_min = {-10, -0.5f, -10};
        floor.box_max = {10, 0, 10};
        s.shapes.push_back(floor);
        return s;
    }();
    return sc;
}

const scene::Scene& analytic_scene() {
    static const scene::Scene sc = [] {
        scene::Scene s;
        for (int x = 0; x < 20; ++x)
            for (int z = 0; z < 20; ++z) {
                scene::Shape sp;
                sp.kind = scene::Shape::Kind::Sphere;
                sp.center = {float(x) - 9.5f, 0.4f, float(z) - 9.5f};
                sp.radius = 0.4f;
                s.shapes.push_back(sp);
            }
        return s;
    }();
    return sc;
}

constexpr int kWidth = 256, kHeight = 256;

// Pinhole camera outside the scene looking at its centre.
std::vector<Ray> camera_rays(const Bounds& b) {
    const Vec3 target = b.center();
    const Vec3 eye = target + Vec3(0, 0.5f, -0.8f) * length(b.extent());
    const Vec3 fwd = normalize(target - eye), right = normalize(cross(Vec3(0, 1, 0), fwd)),
               up = cross(fwd, right);
    const float tan_half = std::tan(0.5f * 45.0f * kPi / 180.0f);
    std::vector<Ray> rays;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const float sx = (2 * (float(x) + 0.5f) / kWidth - 1) * tan_half;
            const float sy = (1 - 2 * (float(y) + 0.5f) / kHeight) * tan_half;
            rays.push_back({eye, normalize(fwd + right * sx + up * sy)});
        }
    return rays;
}

std::vector<Ray> random_rays(const Bounds& b) {
    Sampler rng(42);
    std::vector<Ray> rays(size_t(kWidth) * kHeight);
    for (auto& r : rays) {
        r.origin = b.lo + b.extent() * Vec3(rng.next(), rng.next(), rng.next());
        const float z = 1 - 2 * rng.next(), ph = 2 * kPi * rng.next(),
                    s = std::sqrt(std::max(0.0f, 1 - z * z));
        r.dir = {s * std::cos(ph), s * std::sin(ph), z};
    }
    return rays;
}

struct Fixture {
    accel::EmbreeScene scene;
    std::vector<Ray> camera, random;
    explicit Fixture(const scene::Scene& sc)
        : scene(sc), camera(camera_rays(scene.bounds())), random(random_rays(scene.bounds())) {}
};

Fixture& mesh_fixture() {
    static Fixture f(mesh_scene());
    return f;
}
Fixture& analytic_fixture() {
    static Fixture f(analytic_scene());
    return f;
}

void run(benchmark::State& state, const accel::EmbreeScene& es, const std::vector<Ray>& rays,
         bool occlusion) {
    size_t hits = 0;
    for (auto _ : state) {
        for (const Ray& r : rays) {
            if (occlusion) {
                hits += es.occluded(r);
            } else {
                accel::SurfaceHit h;
                hits += es.intersect(r, h);
            }
        }
    }
    benchmark::DoNotOptimize(hits);
    state.counters["rays/s"] =
        benchmark::Counter(double(state.iterations()) * double(rays.size()), benchmark::Counter::kIsRate);
    state.counters["hit%"] = 100.0 * double(hits) / (double(state.iterations()) * double(rays.size()));
}

void BM_MeshCameraClosest(benchmark::State& s) { run(s, mesh_fixture().scene, mesh_fixture().camera, false); }
void BM_MeshCameraOcclusion(benchmark::State& s) {
    run(s, mesh_fixture().scene, mesh_fixture().camera, true);
}
void BM_MeshRandomClosest(benchmark::State& s) { run(s, mesh_fixture().scene, mesh_fixture().random, false); }
void BM_MeshRandomOcclusion(benchmark::State& s) {
    run(s, mesh_fixture().scene, mesh_fixture().random, true);
}
void BM_AnalyticCameraClosest(benchmark::State& s) {
    run(s, analytic_fixture().scene, analytic_fixture().camera, false);
}
void BM_AnalyticRandomOcclusion(benchmark::State& s) {
    run(s, analytic_fixture().scene, analytic_fixture().random, true);
}

void BM_MeshBuild(benchmark::State& state) {
    for (auto _ : state) {
        accel::EmbreeScene es(mesh_scene());
        benchmark::DoNotOptimize(es.bounds());
    }
    size_t tris = 0;
    for (const auto& sh : mesh_scene().shapes) tris += sh.mesh.triangle_count();
    state.counters["triangles"] = double(tris);
}

BENCHMARK(BM_MeshCameraClosest)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeshCameraOcclusion)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeshRandomClosest)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeshRandomOcclusion)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AnalyticCameraClosest)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AnalyticRandomOcclusion)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeshBuild)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
