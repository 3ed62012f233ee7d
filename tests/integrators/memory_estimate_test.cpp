// Tests of the render memory model: which phase and item dominate, and how the estimate scales
// with the photon budgets, the image and the scene's triangles (the end-to-end comparison with
// measured peaks is tests/app/memory_test.cpp).
#include "integrators/memory_estimate.h"

#include <gtest/gtest.h>

namespace phos::integrators {
namespace {

// A scene of one mesh with `triangles` triangles (their shape does not matter to the model).
scene::Scene mesh_scene(size_t triangles) {
    scene::Scene s;
    s.materials.emplace_back();
    scene::Shape shape;
    shape.mesh.positions.assign(triangles + 2, Vec3(0.0f));
    for (size_t t = 0; t < triangles; ++t)
        shape.mesh.indices.insert(shape.mesh.indices.end(), {uint32_t(t), uint32_t(t + 1), uint32_t(t + 2)});
    s.shapes.push_back(shape);
    return s;
}

uint64_t item(const MemoryEstimate& e, const std::string& name) {
    for (const MemoryItem& i : e.items)
        if (i.name == name) return i.bytes;
    return 0;
}

TEST(MemoryEstimate, PhotonBudgetDominatesAndTheTreeBuildsInPlace) {
    const scene::Scene scene = mesh_scene(12);
    MemoryEstimateInputs in;
    in.integrator = IntegratorKind::PhotonMap;
    in.photon_map.global.photons = 1'500'000'000;
    const MemoryEstimate e = estimate_memory(scene, in);
    ASSERT_FALSE(e.items.empty());
    EXPECT_EQ(e.items[0].name, "photon maps");
    // The traced photons (24 B each) are written once into their final array and the k-d tree
    // permutes that array in place: no phase needs a second copy, so tracing, the build and the
    // render all hold 24 B per photon; the render phase adds the irradiance cache (a 24-byte
    // point per 4 photons, its tree built in place too), so it is the peak.
    EXPECT_EQ(e.phase, "render");
    EXPECT_GT(e.total, uint64_t(30 * 1.5e9));
    EXPECT_LT(e.total, uint64_t(31 * 1.5e9));
    EXPECT_NE(e.breakdown().find("photon maps 36."), std::string::npos) << e.breakdown();
    EXPECT_NE(e.breakdown().find("irradiance cache 9.0"), std::string::npos) << e.breakdown();

    // Twice the photons, about twice the memory.
    in.photon_map.global.photons = 3'000'000'000;
    const double ratio = double(estimate_memory(scene, in).total) / double(e.total);
    EXPECT_NEAR(ratio, 2.0, 0.01);
}

TEST(MemoryEstimate, ProgressiveStateScalesWithPixels) {
    const scene::Scene scene = mesh_scene(12);
    MemoryEstimateInputs in;
    in.integrator = IntegratorKind::Sppm;
    in.render.width = in.render.height = 4000;
    const MemoryEstimate e = estimate_memory(scene, in);
    EXPECT_EQ(e.phase, "render");
    EXPECT_EQ(e.items[0].name, "visible points");
    EXPECT_GT(item(e, "pixel statistics"), uint64_t(64) * 16'000'000 - 1);
    EXPECT_GT(item(e, "film"), 0u);
    in.progressive.eye_samples = 4;  // sppm ignores it; ppm keeps 4 hit points per pixel
    EXPECT_EQ(estimate_memory(scene, in).total, e.total);
    in.integrator = IntegratorKind::Ppm;
    EXPECT_GT(estimate_memory(scene, in).total, 3 * e.total);
}

TEST(MemoryEstimate, TrianglesDominateTheBvhBuild) {
    MemoryEstimateInputs in;
    in.integrator = IntegratorKind::Path;
    in.render.width = in.render.height = 64;
    const MemoryEstimate e = estimate_memory(mesh_scene(4'000'000), in);
    EXPECT_EQ(e.phase, "BVH build");
    EXPECT_EQ(e.items[0].name, "accelerator");
    EXPECT_GT(item(e, "scene"), uint64_t(4'000'000) * 12);
    // Embree's copy (24 B per triangle here) and the BVH at its build peak.
    EXPECT_GT(item(e, "accelerator"), uint64_t(4'000'000) * 100);
}

TEST(MemoryEstimate, LayersAndAovsAddFilm) {
    const scene::Scene scene = mesh_scene(12);
    MemoryEstimateInputs in;
    in.integrator = IntegratorKind::Path;
    in.render.width = in.render.height = 1000;
    const uint64_t plain = item(estimate_memory(scene, in), "film");
    in.render.layers = true;
    in.render.aovs = {"albedo"};
    EXPECT_GT(item(estimate_memory(scene, in), "film"), 4 * plain);  // 6 layers and a copy + writing
}

}  // namespace
}  // namespace phos::integrators
