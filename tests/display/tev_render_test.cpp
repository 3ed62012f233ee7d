// `phos render --tev` against the fake tev server: one create, then updates whose last covers every
// pixel with the rendered image's values (compared with the PFM output); a tev that is not running
// or hangs up mid-render is a warning, the render completes and writes its image.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "display/fake_tev_server.h"
#include "io/image/image_io.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kScene = source_path("scenes/cornell-diffuse.scn");

TEST(TevRender, StreamsTheImageAsItConverges) {
    display::test::FakeTevServer tev;
    TempDir dir;
    const std::string out = dir.file("out.pfm");
    const auto r =
        run_phos("render " + kScene + " --integrator path --width 40 --height 30 --spp 64 --layers --tev " +
                 tev.address() + " -o " + out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    ASSERT_TRUE(tev.wait());
    EXPECT_TRUE(tev.errors().empty()) << tev.errors().front();
    ASSERT_GE(tev.creates().size(), 1u);
    const display::test::CreatePacket& c = tev.creates().back();
    EXPECT_EQ(c.width, 40);
    EXPECT_EQ(c.height, 30);
    ASSERT_GE(c.channels.size(), 3u);
    EXPECT_EQ(c.channels[0], "R");
    EXPECT_NE(std::find(c.channels.begin(), c.channels.end(), "direct.G"), c.channels.end());
    ASSERT_FALSE(tev.updates().empty());
    // The updates after the last create: every pixel covered; the final values are the image's.
    const Image image = io::read_image(out);
    std::vector<int> covered(40 * 30, 0);
    std::vector<float> last(40 * 30 * 3, -1.0f);
    for (const display::test::UpdatePacket& u : tev.updates()) {
        EXPECT_EQ(u.name, c.name);
        for (int y = 0; y < u.height; ++y)
            for (int x = 0; x < u.width; ++x) {
                const size_t p = size_t(u.y + y) * 40 + size_t(u.x + x);
                ++covered[p];
                for (int k = 0; k < 3; ++k) last[p * 3 + size_t(k)] = u.value(k, x, y);
            }
    }
    int missing = 0, wrong = 0;
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
            const size_t p = size_t(y) * 40 + size_t(x);
            missing += covered[p] == 0;
            for (int k = 0; k < 3; ++k)
                wrong += std::abs(last[p * 3 + size_t(k)] - image.at(x, y)[k]) > 1e-6f;
        }
    EXPECT_EQ(missing, 0);
    EXPECT_EQ(wrong, 0) << "the last update is not the written image";
    std::printf("%zu creates, %zu updates\n", tev.creates().size(), tev.updates().size());
}

TEST(TevRender, AMissingOrVanishingTevIsAWarning) {
    TempDir dir;
    {
        // Nothing listens on this port (the server is gone once constructed and destroyed).
        int port = 0;
        {
            display::test::FakeTevServer gone;
            port = gone.port();
        }
        const auto r = run_phos("render " + kScene +
                                " --integrator path --width 16 --height 16 --spp 4 --tev 127.0.0.1:" +
                                std::to_string(port) + " -o " + dir.file("a.pfm"));
        EXPECT_EQ(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find("warning: --tev: "), std::string::npos) << r.output;
        EXPECT_TRUE(std::filesystem::exists(dir.file("a.pfm")));
    }
    {
        display::test::FakeTevServer rude(display::test::FakeTevServer::Mode::close_after_first);
        const auto r =
            run_phos("render " + kScene + " --integrator path --width 64 --height 64 --spp 64 --tev " +
                     rude.address() + " -o " + dir.file("b.pfm"));
        EXPECT_EQ(r.exit_code, 0) << r.output;
        EXPECT_TRUE(std::filesystem::exists(dir.file("b.pfm")));
    }
    const auto bad = run_phos("render " + kScene + " --tev 127.0.0.1:99999 -o " + dir.file("c.pfm"));
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("c.pfm")));
}

}  // namespace
}  // namespace phos::testing
