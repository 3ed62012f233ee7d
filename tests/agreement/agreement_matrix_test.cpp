// The agreement matrix: every integrator that claims a scene (integrators::claims) renders it at a
// modest budget with two seeds and is compared, block by block, with two high-budget renders of the
// scene's reference integrator (integrators::agreement_reference: path, or bdpt where path cannot
// render the caustics): the mean of every 8 x 8 block, per colour channel, within a tolerance made
// of the noise both show between their seeds, the bias the integrator documents (its kernel) and
// a floor, and the image means within theirs (film/block_agreement.h, app/lib/agreement.h). The
// scenes are in tests/agreement/scenes; between them they hold the features the integrators must
// agree on. A failure names the scene, the integrator, the reference, the block, its ratio and
// its tolerance, and prints the scene's whole table.
//
// The default suite runs the small version: nine scenes at 32 x 32, fixed seeds and sample /
// iteration budgets (deterministic), about 90 s with ctest -j2 on 2 cores (Release).
// PHOS_AGREEMENT=full runs the larger one: every scene at 64 x 64, twice the budgets (about 14
// minutes; the slowest row, frosted-pane-point, about 230 s).
//
// The tolerance's sigmas are chosen for the whole matrix: with N comparisons (blocks x channels x
// integrators x scenes) each is held to a false-failure chance of 1e-4 / N under Gaussian noise, so
// the matrix as a whole fails by chance less than once in 10^4 runs.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <string>
#include <vector>

#include "app/lib/agreement.h"
#include "core/log.h"
#include "film/block_agreement.h"
#include "integrators/registry.h"

namespace phos::app {
namespace {

using integrators::IntegratorKind;

bool full() {
    const char* v = std::getenv("PHOS_AGREEMENT");
    return v && std::strcmp(v, "full") == 0;
}

// Samples per pixel or iterations for each integrator at the small version's 32 x 32 (the full
// version takes twice as many at 64 x 64); the reference takes `reference` of its own units: 8 to
// 16 times the tested integrators', so that their noise dominates the comparison.
struct Budgets {
    int path = 64, photonmap = 8, ppm = 32, sppm = 32, bdpt = 32, vcm = 32;
    int reference = 512;

    int of(IntegratorKind k) const {
        switch (k) {
            case IntegratorKind::Path:
                return path;
            case IntegratorKind::PhotonMap:
                return photonmap;
            case IntegratorKind::Ppm:
                return ppm;
            case IntegratorKind::Sppm:
                return sppm;
            case IntegratorKind::Bdpt:
                return bdpt;
            case IntegratorKind::Vcm:
                return vcm;
            default:
                return 0;
        }
    }
};

struct Row {
    std::string scene;  // in tests/agreement/scenes
    Budgets budgets;
    bool in_small = true;  // also in the default suite
};

// Photon counts for 32 x 32 and 64 x 64 images (the defaults are for 512 x 512): what every row
// renders with.
const std::vector<std::pair<std::string, std::string>> kPhotonOptions{
    {"photons-per-iter", "20000"}, {"global", "20000"},         {"caustic", "20000"},
    {"indirect", "20000"},         {"volume-photons", "20000"}, {"volume-caustic-photons", "20000"},
};

// gtest prints a row by its scene.
void PrintTo(const Row& row, std::ostream* out) { *out << row.scene; }

const std::vector<Row>& rows() {
    // The default suite's rows between them hold every material, light and medium kind but the grid
    // medium, a light declared inside fog and a medium inside glass, which the full version adds.
    static const std::vector<Row> r{
        // homogeneous smoke bounded by one interface quad, the light inside it declaring no medium
        {"a-smoke-box.pbrt", {}, true},
        // a point light's caustic through glass: bdpt is the reference, path takes no part
        {"a-caustic-point.scn", {}, true},
        // glass and mirror spheres, an area light's caustic on a checker texture
        {"glass-mirror-checker.pbrt", {}, true},
        // point, spot and two-sided area lights, a rough conductor
        {"spot-point-twosided.pbrt", {}, true},
        // an image environment light, thin glass, an image texture
        {"thin-glass-sky.pbrt", {}, true},
        // a directional light and a constant sky outside homogeneous fog
        {"sun-sky-fog.pbrt", {}, true},
        // .scn: modified Phong, frosted glass, a spot light, a spherical texture
        {"phong-frosted-spot.scn", {}, true},
        // .scn: a room lit only through a frosted pane (sharp glossy transmission, point light).
        // Path reaches the point light only by next-event estimation from inside the pane, through
        // its exponent-300 lobe: a heavy-tailed estimate whose image mean scatters by about 6 %
        // per seed at 128 spp (and regularisation's widened lobes lose a little light at that
        // budget), so path gets 32 times its usual samples here (0.986 and 0.994 at 4096 spp).
        {"frosted-pane-point.scn", Budgets{.path = 2048}, true},
        // spectral: a blackbody area light, measured gold, a dispersive glass sphere's caustic
        {"spectral-caustics.pbrt", {}, true},
        // an area light's caustics through glass and in a mirror
        {"a-glass-mirror.pbrt", {}, false},
        // rough conductors and a rough dielectric
        {"cornell-rough-area.pbrt", {}, false},
        // spot and point lights declared inside fog
        {"fog-spot-inside.pbrt", {}, false},
        // media inside glass
        {"glass-media-area.pbrt", {}, false},
        // a chromatic grid medium, a point light inside it and a spot light outside
        {"grid-smoke-point.pbrt", {}, false},
        // .scene: smoke with the light inside, murky glass inside the smoke, a sky
        {"smoke-murky-sky.scene", {}, false},
        // the smoke box with the light declaring no medium again
        {"smoke-quad-light.pbrt", {}, false},
    };
    return r;
}

int image_size() { return full() ? 64 : 32; }

// The family of comparisons the tolerance is chosen for: every row's blocks x channels for each of
// the six consistent integrators.
double comparisons() {
    double n = 0;
    for (const Row& r : rows())
        if (full() || r.in_small) n += 6.0 * film::block_comparisons(image_size(), image_size(), 8);
    return n;
}

class AgreementMatrix : public ::testing::TestWithParam<Row> {};

TEST_P(AgreementMatrix, IntegratorsAgreeWithTheReference) {
    const Row& row = GetParam();
    if (!full() && !row.in_small) GTEST_SKIP() << "in PHOS_AGREEMENT=full only";
    log::set_quiet(true);
    RenderCommand settings;
    settings.scene_path = std::string(PHOS_SOURCE_DIR) + "/tests/agreement/scenes/" + row.scene;
    settings.render.width = settings.render.height = image_size();
    settings.given = {"width", "height"};
    for (const auto& [name, value] : kPhotonOptions)
        for (const BoundTable& b : settings.tables())
            if (const options::Option* o = b.table->find(name)) {
                o->set(b.object, {value});
                settings.given.insert(name);
            }
    const AgreementScene scene(settings, image_size());

    const int scale = full() ? 2 : 1;
    AgreementRequest request;
    request.seed = 1;
    request.blocks.sigmas = film::tolerance_sigmas(comparisons());
    for (const integrators::IntegratorInfo& i : integrators::integrators())
        if (integrators::claims(i.kind, scene.scene()))
            request.tested.push_back({i.kind, {scale * row.budgets.of(i.kind), 0}});
    request.reference = {integrators::agreement_reference(scene.scene()), {scale * row.budgets.reference, 0}};
    const AgreementReport report = run_agreement(scene, request);
    const std::string table = agreement_text(report);
    std::printf("%s\n", table.c_str());

    const std::string reference = integrators::integrator(report.reference.kind).name;
    for (const AgreementRow& r : report.rows) {
        const std::string who =
            row.scene + ": " + integrators::integrator(r.kind).name + " against " + reference;
        const film::Agreement& a = r.agreement;
        EXPECT_TRUE(a.mean_agrees()) << who << ": image mean ratio " << a.mean_ratio << ", tolerance ±"
                                     << a.mean_tolerance;
        for (const film::BlockComparison& b : a.failing)
            ADD_FAILURE() << who << ": " << film::describe(b) << ", tolerance " << b.tolerance;
    }
    if (!report.agrees()) ADD_FAILURE() << row.scene << ":\n" << table;
}

std::string row_name(const ::testing::TestParamInfo<Row>& info) {
    std::string s = info.param.scene;
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
}

INSTANTIATE_TEST_SUITE_P(agreement, AgreementMatrix, ::testing::ValuesIn(rows()), row_name);

}  // namespace
}  // namespace phos::app
