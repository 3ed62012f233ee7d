// The integrator registry: every row is what its integrator does (the layers it writes, what its
// budget counts, whether it traces pixels, the options it checks), names parse into kinds once,
// make_integrator takes only option structs inside their tables' ranges, reporting a bad one
// with the tables' wording (the integrators themselves never check or name flags), and the
// agreement rules say which integrators claim a scene and which is its reference.
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

// The agreement rules (registry.h claims, agreement_reference, agreement_bias): the floor scene
// with a glass sphere added, lit by its area light, by a point light, or through glowing fog.
TEST(Registry, AgreementClaimsReferencesAndBiases) {
    scene::Scene area = floor_scene();
    scene::Material glass;
    glass.transmission = Rgb(1.0f);
    glass.ior = 1.5f;
    area.materials.push_back(glass);
    area.shapes.push_back(testing::sphere({0, 0.3f, 0}, 0.3f, int(area.materials.size()) - 1));
    scene::Scene point = area;
    scene::Light p;
    p.kind = scene::Light::Kind::Point;
    p.position = Vec3(0.5f, 1.2f, 0);
    p.color = Rgb(5.0f);
    point.lights.push_back(p);
    scene::Scene frosted = point;  // a rough dielectric has no delta lobe
    frosted.materials.back().transmission_shininess = 100;
    scene::Scene matte = point;  // a dielectric rougher than the default --sharp-glossy
    matte.materials.back().transmission_shininess = 5;
    scene::Scene fog = floor_scene();
    scene::Medium glow;
    glow.sigma_a = Rgb(0.5f);
    glow.emission = Rgb(1.0f);
    fog.media.push_back(glow);

    for (const IntegratorInfo& row : integrators()) {
        const bool consistent = row.convergence != Convergence::Inconsistent;
        EXPECT_EQ(claims(row.kind, area), consistent) << row.name;
        EXPECT_EQ(claims(row.kind, frosted), consistent) << row.name;
        EXPECT_EQ(claims(row.kind, matte), consistent) << row.name;
        // Path tracing cannot find the point light's caustic through the glass.
        EXPECT_EQ(claims(row.kind, point), consistent && row.kind != IntegratorKind::Path) << row.name;
        // Photons are not emitted from media: ppm and sppm miss what glowing fog lights.
        const bool photons_only = row.kind == IntegratorKind::Ppm || row.kind == IntegratorKind::Sppm;
        EXPECT_EQ(claims(row.kind, fog), consistent && !photons_only) << row.name;
        // The unbiased have no bias allowance; the kernel methods a kernel and an image share.
        const film::BiasAllowance bias = agreement_bias(row.kind);
        const bool unbiased = row.convergence == Convergence::Unbiased || !consistent;
        EXPECT_EQ(bias.kernel == 0 && bias.image == 0, unbiased) << row.name;
    }
    EXPECT_EQ(integrator(IntegratorKind::Whitted).convergence, Convergence::Inconsistent);
    // path regularises sharp lobes after rough bounces by a bandwidth that shrinks (--regularize).
    EXPECT_EQ(integrator(IntegratorKind::Path).convergence, Convergence::Consistent);
    EXPECT_EQ(integrator(IntegratorKind::Bdpt).convergence, Convergence::Unbiased);
    EXPECT_EQ(integrator(IntegratorKind::PhotonMap).convergence, Convergence::KernelBiased);
    for (const IntegratorKind k :
         {IntegratorKind::Path, IntegratorKind::Ppm, IntegratorKind::Sppm, IntegratorKind::Vcm})
        EXPECT_EQ(integrator(k).convergence, Convergence::Consistent);
    EXPECT_EQ(agreement_reference(area), IntegratorKind::Path);
    // A point light behind sharp frosted glass: path finds its light only by next-event estimation
    // inside the glass (fireflies), bdpt carries it on light paths.
    EXPECT_EQ(agreement_reference(frosted), IntegratorKind::Bdpt);
    EXPECT_EQ(agreement_reference(matte), IntegratorKind::Path);
    EXPECT_EQ(agreement_reference(point), IntegratorKind::Bdpt);
    EXPECT_EQ(agreement_reference(fog), IntegratorKind::Path);
}

}  // namespace
}  // namespace phos::integrators
