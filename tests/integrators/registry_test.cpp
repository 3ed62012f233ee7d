// The integrator registry: every row is what its integrator does (the layers it writes, what its
// budget counts, whether it traces pixels, the options it checks), names parse into kinds once,
// and make_integrator takes only option structs inside their tables' ranges, reporting a bad one
// with the tables' wording (the integrators themselves never check or name flags).
#include "integrators/registry.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.h"
#include "core/stats.h"
#include "film/film.h"
#include "render/path_recorder.h"
#include "render/prepared.h"
#include "support/shapes.h"

namespace phos::integrators {
namespace {

std::string error_of(IntegratorKind kind, const IntegratorConfig& c) {
    try {
        make_integrator(kind, c);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// A diffuse floor under a square area light, seen from above.
scene::Scene floor_scene() {
    scene::Scene s;
    scene::Material white, black;
    white.diffuse = Rgb(0.7f);
    s.materials = {white, black};
    scene::Shape floor = testing::quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
    floor.material = 0;
    s.shapes.push_back(floor);
    scene::Shape light =
        testing::quad({-0.3f, 1.5f, -0.3f}, {0.3f, 1.5f, -0.3f}, {0.3f, 1.5f, 0.3f}, {-0.3f, 1.5f, 0.3f});
    light.material = 1;
    s.add_area_light(light, Rgb(10.0f));
    scene::Camera cam;
    cam.eye = Vec3(0, 1, 1.5f);
    cam.forward = Vec3(0, -0.6f, -1);
    cam.up = Vec3(0, 1, 0);
    cam.fov = 1.0f;
    s.camera = cam;
    return s;
}

struct Rendered {
    RenderDone done;
    std::vector<std::string> layers;
    size_t traced_paths = 0;
    std::string checkpoint_name;  // the integrator its final checkpoint names
};

// A 4 x 4 render of 2 samples or iterations with --layers, pixel (1, 2) traced, checkpointed.
Rendered render(IntegratorKind kind) {
    RenderOptions opt;
    opt.width = opt.height = 4;
    opt.spp = 2;
    opt.seed = 3;
    opt.layers = true;
    Stats stats;
    const scene::Scene s = floor_scene();
    Prepared P(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    IntegratorConfig config;
    config.photon_map.global.photons = 2000;
    config.photon_map.caustic.photons = 2000;
    config.progressive.photons_per_iter = 2000;
    Rendered r;
    config.budget.observers.on_checkpoint = [&](const ProgressiveState& s) {
        r.checkpoint_name = s.integrator;
    };
    PathRecorder trace(1, 2);
    {
        const TraceRequest request(&trace);
        r.done = make_integrator(kind, config)->render(P, film, progress);
    }
    r.layers = film.layer_names();
    r.traced_paths = trace.paths().size();
    return r;
}

TEST(Registry, RowsAreInKindOrderAndNamesParseToTheirKinds) {
    const std::vector<std::string> names{"whitted", "path", "photonmap", "ppm", "sppm", "bdpt", "vcm"};
    ASSERT_EQ(integrators().size(), names.size());
    const options::Choices<IntegratorKind> choices = integrator_choices();
    for (size_t i = 0; i < names.size(); ++i) {
        const IntegratorInfo& row = integrators()[i];
        EXPECT_EQ(size_t(row.kind), i) << row.name;
        EXPECT_EQ(row.name, names[i]);
        EXPECT_EQ(find_integrator(names[i]), row.kind);
        EXPECT_EQ(&integrator(row.kind), &row);
        EXPECT_EQ(choices[i].name, names[i]);
        EXPECT_EQ(choices[i].value, row.kind);
    }
    EXPECT_EQ(find_integrator("magic"), std::nullopt);
    EXPECT_EQ(find_integrator("PATH"), std::nullopt);
    EXPECT_THROW(integrator_kind("magic"), InputError);
}

// Each integrator, rendered through its row's make(), writes exactly the row's layers, counts
// what the row says (samples per pixel: every pixel's samples; iterations: no pixel samples),
// records a traced pixel exactly when the row says it does, and names itself in checkpoints by
// the row's name.
TEST(Registry, EveryRowIsWhatItsIntegratorDoes) {
    for (const IntegratorInfo& row : integrators()) {
        const Rendered r = render(row.kind);
        std::vector<std::string> layers;
        for (const Component c : row.layers) layers.push_back(component_name(c));
        std::sort(layers.begin(), layers.end());  // as the film lists them
        EXPECT_EQ(r.layers, layers) << row.name;
        EXPECT_EQ(r.done.units, 2u) << row.name;
        EXPECT_EQ(r.done.target, 2u) << row.name;
        EXPECT_TRUE(r.done.started && !r.done.interrupted) << row.name;
        if (row.counts == Counts::SamplesPerPixel)
            EXPECT_EQ(r.done.samples, 4u * 4u * 2u) << row.name;
        else
            EXPECT_EQ(r.done.samples, 0u) << row.name;
        EXPECT_EQ(r.traced_paths > 0, row.traces) << row.name;
        EXPECT_EQ(r.checkpoint_name, row.name);
    }
}

TEST(Registry, OptionSetsNameTheirIntegratorsInTableOrder) {
    const options::IntegratorSet set = integrator_set({IntegratorKind::Vcm, IntegratorKind::Ppm});
    EXPECT_EQ(integrator_names(set, "/"), "ppm/vcm");
    EXPECT_EQ(integrator_names(set, " "), "ppm vcm");
    options::Option o;
    EXPECT_TRUE(applies(o, IntegratorKind::Path));  // no set: every integrator
    o.applies_to = set;
    EXPECT_TRUE(applies(o, IntegratorKind::Ppm));
    EXPECT_FALSE(applies(o, IntegratorKind::Sppm));
}

TEST(Registry, RefusesOptionsOutsideTheirTables) {
    IntegratorConfig c;
    EXPECT_EQ(error_of(IntegratorKind::Sppm, c), "");
    c.progressive.alpha = 0;
    EXPECT_EQ(error_of(IntegratorKind::Sppm, c), "--alpha: 0 is not in (0, 1]");
    c = {};
    c.photon_map.caustic.samples = 0;
    EXPECT_EQ(error_of(IntegratorKind::PhotonMap, c), "--caustic-samples: 0 is not in [1, 100000]");
    c = {};
    c.photon_map.global.cone_k = 0.5f;
    EXPECT_EQ(error_of(IntegratorKind::PhotonMap, c), "--global-cone-k: 0.5 is not in [1, 1000000]");
    c = {};
    c.budget.settings.checkpoint_every = 0;
    EXPECT_EQ(error_of(IntegratorKind::Path, c), "--checkpoint-every: 0 is not in [1, 1073741824]");
}

// make_integrator checks the option struct a row reads, and only that one.
TEST(Registry, ChecksTheOptionsItsIntegratorReads) {
    IntegratorConfig bad_map, bad_progressive;
    bad_map.photon_map.caustic.samples = 0;
    bad_progressive.progressive.alpha = 0;
    for (const IntegratorInfo& row : integrators()) {
        EXPECT_EQ(error_of(row.kind, bad_map).empty(), row.reads != Reads::PhotonMap) << row.name;
        EXPECT_EQ(error_of(row.kind, bad_progressive).empty(), row.reads != Reads::Progressive) << row.name;
    }
}

}  // namespace
}  // namespace phos::integrators
