// Tests of display/tev_client against a fake tev (fake_tev_server.h) that decodes packets the
// way tev does: the create packet's fields, updates that cover every pixel once per frame with
// the values intact, and failures (no server, a server that hangs up or stalls, a connect that
// cannot complete) that return false in bounded time without SIGPIPE.
#include "display/tev_client.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <bit>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <limits>
#include <thread>
#include <tuple>
#include <vector>

#include "core/error.h"
#include "display/fake_tev_server.h"

namespace phos::display {
namespace {

using test::FakeTevServer;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::vector<std::string> channel_names(int n) {
    std::vector<std::string> all = {"R", "G", "B", "A", "albedo.R", "albedo.G", "albedo.B"};
    return std::vector<std::string>(all.begin(), all.begin() + n);
}

// Distinct for every frame, pixel and channel, and exact in a float.
float pattern(int frame, int width, int x, int y, int c, int nc) {
    float v = float(frame * 1000000 + ((y * width + x) * nc + c)) + 0.25f;
    return (x + y) % 2 ? -v : v;
}

std::vector<float> frame_data(int frame, int width, int height, int nc) {
    std::vector<float> d(size_t(width) * height * nc);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < nc; ++c)
                d[(size_t(y) * width + x) * nc + c] = pattern(frame, width, x, y, c, nc);
    return d;
}

// Port `port` on 127.0.0.1.
TevAddress loopback(int port) { return {"127.0.0.1", port}; }

// A port on 127.0.0.1 that nothing listens on (bound, then released).
int unused_port() {
    int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof(addr);
    EXPECT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
    EXPECT_EQ(::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len), 0);
    ::close(fd);
    return ntohs(addr.sin_port);
}

// ---- parse_tev_address ----

TEST(ParseTevAddress, AcceptsEveryForm) {
    auto a = parse_tev_address("");
    EXPECT_EQ(a.host, "127.0.0.1");
    EXPECT_EQ(a.port, 14158);
    EXPECT_EQ(a.to_string(), "127.0.0.1:14158");

    a = parse_tev_address("localhost");
    EXPECT_EQ(a.host, "localhost");
    EXPECT_EQ(a.port, 14158);

    a = parse_tev_address(":1234");
    EXPECT_EQ(a.host, "127.0.0.1");
    EXPECT_EQ(a.port, 1234);

    a = parse_tev_address("render-box.local:65535");
    EXPECT_EQ(a.host, "render-box.local");
    EXPECT_EQ(a.port, 65535);

    a = parse_tev_address("[::1]:9000");
    EXPECT_EQ(a.host, "::1");
    EXPECT_EQ(a.port, 9000);
    EXPECT_EQ(a.to_string(), "[::1]:9000");

    a = parse_tev_address("[::1]");
    EXPECT_EQ(a.host, "::1");
    EXPECT_EQ(a.port, 14158);

    a = parse_tev_address("fe80::1");
    EXPECT_EQ(a.host, "fe80::1");
    EXPECT_EQ(a.port, 14158);
}

std::string parse_error(std::string_view text, std::string_view option = "--tev") {
    try {
        parse_tev_address(text, option);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(ParseTevAddress, BadPortsAreInputErrorsNamingTheOption) {
    EXPECT_EQ(parse_error("localhost:abc"),
              "--tev: 'localhost:abc': port 'abc' is not a number (expected HOST:PORT, HOST or :PORT, e.g. "
              "127.0.0.1:14158)");
    EXPECT_NE(parse_error("localhost:-1").find("port '-1' is not a number"), std::string::npos);
    EXPECT_NE(parse_error("localhost:+80").find("port '+80' is not a number"), std::string::npos);
    EXPECT_NE(parse_error("localhost:0").find("port 0 is not in [1, 65535]"), std::string::npos);
    EXPECT_NE(parse_error("localhost:65536").find("port 65536 is not in [1, 65535]"), std::string::npos);
    EXPECT_NE(parse_error("localhost:99999999999999999999").find("is not in [1, 65535]"), std::string::npos);
    EXPECT_NE(parse_error("localhost:").find("the port is empty"), std::string::npos);
    EXPECT_NE(parse_error(":").find("the port is empty"), std::string::npos);
    EXPECT_NE(parse_error("[::1").find("missing ']'"), std::string::npos);
    EXPECT_NE(parse_error("[::1]x").find("expected ':' after ']'"), std::string::npos);
    EXPECT_EQ(parse_error("h:0", "tev").rfind("tev: 'h:0': ", 0), 0u);
}

// ---- the protocol ----

TEST(TevClient, CreatePacketCarriesTheImage) {
    FakeTevServer server;
    TevClient client;
    ASSERT_TRUE(client.connect(loopback(server.port()))) << client.error();
    EXPECT_TRUE(client.ok());
    EXPECT_TRUE(client.create_image("phos — cornell box.pbrt (1234)", 640, 480, {"R", "G", "B"}));
    EXPECT_TRUE(client.create_image("second", 3, 2, {"Y"}, /*grab_focus=*/false));
    client.close();
    EXPECT_FALSE(client.ok());
    ASSERT_TRUE(server.wait());

    EXPECT_TRUE(server.errors().empty()) << server.errors().front();
    ASSERT_EQ(server.creates().size(), 2u);
    const auto& c = server.creates()[0];
    EXPECT_TRUE(c.grab_focus);
    EXPECT_EQ(c.name, "phos — cornell box.pbrt (1234)");
    EXPECT_EQ(c.width, 640);
    EXPECT_EQ(c.height, 480);
    EXPECT_EQ(c.channels, (std::vector<std::string>{"R", "G", "B"}));
    const auto& d = server.creates()[1];
    EXPECT_FALSE(d.grab_focus);
    EXPECT_EQ(d.name, "second");
    EXPECT_EQ(d.width, 3);
    EXPECT_EQ(d.height, 2);
    EXPECT_EQ(d.channels, (std::vector<std::string>{"Y"}));
    EXPECT_EQ(server.types(), (std::vector<int>{4, 4}));
}

// (channel count, max floats per packet): whole images, bands of rows, single rows, pieces of
// rows that do not divide the width, one pixel per packet.
class TevClientFrames : public ::testing::TestWithParam<std::tuple<int, std::size_t>> {};

TEST_P(TevClientFrames, UpdatesCoverEveryPixelOncePerFrame) {
    auto [nc, max_floats] = GetParam();
    const int w = 37, h = 23, frames = 2;
    const std::string name = "frames";
    const auto names = channel_names(nc);

    FakeTevServer server;
    TevClientOptions options;
    options.max_floats_per_packet = max_floats;
    TevClient client(options);
    ASSERT_TRUE(client.connect(loopback(server.port()))) << client.error();
    ASSERT_TRUE(client.create_image(name, w, h, names));
    for (int f = 0; f < frames; ++f) {
        auto data = frame_data(f, w, h, nc);
        ASSERT_TRUE(client.update_image(name, names, 0, 0, w, h, data.data())) << client.error();
    }
    client.close();
    ASSERT_TRUE(server.wait());
    ASSERT_TRUE(server.errors().empty()) << server.errors().front();
    ASSERT_EQ(server.creates().size(), 1u);
    ASSERT_FALSE(server.updates().empty());

    // Which frame a packet belongs to is read from its values; within a frame every pixel and
    // channel must arrive exactly once, with its value bit for bit.
    std::vector<int> seen(size_t(frames) * w * h * nc, 0);
    int last_frame = 0;
    for (const auto& u : server.updates()) {
        EXPECT_FALSE(u.grab_focus);
        EXPECT_EQ(u.name, name);
        EXPECT_EQ(u.channels, names);
        EXPECT_LE(u.data.size(), std::max<std::size_t>(max_floats, std::size_t(nc)));
        ASSERT_GE(u.x, 0);
        ASSERT_GE(u.y, 0);
        ASSERT_LE(u.x + u.width, w);
        ASSERT_LE(u.y + u.height, h);
        int frame = int(std::abs(u.value(0, 0, 0))) / 1000000;
        ASSERT_LT(frame, frames);
        EXPECT_GE(frame, last_frame) << "frames interleaved";
        last_frame = frame;
        for (int py = 0; py < u.height; ++py)
            for (int px = 0; px < u.width; ++px)
                for (int c = 0; c < nc; ++c) {
                    int x = u.x + px, y = u.y + py;
                    EXPECT_EQ(std::bit_cast<uint32_t>(u.value(c, px, py)),
                              std::bit_cast<uint32_t>(pattern(frame, w, x, y, c, nc)));
                    ++seen[((size_t(frame) * h + y) * w + x) * nc + c];
                }
    }
    for (size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "entry " << i;
}

INSTANTIATE_TEST_SUITE_P(
    ChunkSizes, TevClientFrames,
    ::testing::Values(std::make_tuple(3, std::size_t(1) << 20), std::make_tuple(3, std::size_t(37 * 3 * 5)),
                      std::make_tuple(3, std::size_t(37 * 3 + 5)), std::make_tuple(3, std::size_t(37 * 3)),
                      std::make_tuple(3, std::size_t(100)), std::make_tuple(4, std::size_t(30)),
                      std::make_tuple(1, std::size_t(7)), std::make_tuple(7, std::size_t(1))));

TEST(TevClient, SendsASubRectangleOfALargerBufferInPlace) {
    const int bw = 50, bh = 40, nc = 3;
    const int x0 = 5, y0 = 7, w = 20, h = 9;
    auto buffer = frame_data(0, bw, bh, nc);
    FakeTevServer server;
    TevClientOptions options;
    options.max_floats_per_packet = 50;  // pieces of rows
    TevClient client(options);
    ASSERT_TRUE(client.connect(loopback(server.port())));
    ASSERT_TRUE(client.create_image("sub", bw, bh, channel_names(nc)));
    const float* corner = buffer.data() + (size_t(y0) * bw + x0) * nc;
    ASSERT_TRUE(client.update_image("sub", channel_names(nc), x0, y0, w, h, corner, size_t(bw) * nc));
    client.close();
    ASSERT_TRUE(server.wait());
    ASSERT_TRUE(server.errors().empty()) << server.errors().front();
    std::vector<int> seen(size_t(bw) * bh, 0);
    for (const auto& u : server.updates())
        for (int py = 0; py < u.height; ++py)
            for (int px = 0; px < u.width; ++px) {
                int x = u.x + px, y = u.y + py;
                ++seen[size_t(y) * bw + x];
                for (int c = 0; c < nc; ++c) EXPECT_EQ(u.value(c, px, py), pattern(0, bw, x, y, c, nc));
            }
    for (int y = 0; y < bh; ++y)
        for (int x = 0; x < bw; ++x) {
            bool inside = x >= x0 && x < x0 + w && y >= y0 && y < y0 + h;
            EXPECT_EQ(seen[size_t(y) * bw + x], inside ? 1 : 0) << x << "," << y;
        }
}

TEST(TevClient, SpecialFloatsArriveBitForBit) {
    const std::vector<float> values = {0.0f,
                                       -0.0f,
                                       std::numeric_limits<float>::denorm_min(),
                                       -std::numeric_limits<float>::min(),
                                       std::numeric_limits<float>::max(),
                                       std::numeric_limits<float>::lowest(),
                                       std::numeric_limits<float>::infinity(),
                                       -std::numeric_limits<float>::infinity(),
                                       std::bit_cast<float>(0x7fc12345u),  // a NaN with a payload
                                       1e-30f,
                                       3.14159265f,
                                       -65504.0f};
    const int w = int(values.size());
    FakeTevServer server;
    TevClient client;
    ASSERT_TRUE(client.connect(loopback(server.port())));
    ASSERT_TRUE(client.create_image("floats", w, 1, {"Y"}));
    ASSERT_TRUE(client.update_image("floats", {"Y"}, 0, 0, w, 1, values.data()));
    client.close();
    ASSERT_TRUE(server.wait());
    ASSERT_TRUE(server.errors().empty()) << server.errors().front();
    ASSERT_EQ(server.updates().size(), 1u);
    for (int i = 0; i < w; ++i)
        EXPECT_EQ(std::bit_cast<uint32_t>(server.updates()[0].value(0, i, 0)),
                  std::bit_cast<uint32_t>(values[i]))
            << "value " << i;
}

TEST(TevClient, BadArgumentsFailButKeepTheConnection) {
    FakeTevServer server;
    TevClient client;
    ASSERT_TRUE(client.connect(loopback(server.port())));
    float px[6] = {1, 2, 3, 4, 5, 6};
    EXPECT_FALSE(client.create_image("a", 0, 4, {"R"}));
    EXPECT_NE(client.error().find("empty image"), std::string::npos);
    EXPECT_FALSE(client.create_image("a", 2, 1, {}));
    EXPECT_FALSE(client.create_image(std::string("a\0b", 3), 2, 1, {"R"}));
    EXPECT_FALSE(client.update_image("a", {"R", ""}, 0, 0, 1, 1, px));
    EXPECT_FALSE(client.update_image("a", {"R"}, -1, 0, 1, 1, px));
    EXPECT_FALSE(client.update_image("a", {"R"}, 0, 0, 3, 1, px, 2));
    EXPECT_NE(client.error().find("row stride"), std::string::npos);
    EXPECT_FALSE(client.update_image("a", {"R"}, std::numeric_limits<int>::max(), 0, 2, 1, px));
    EXPECT_FALSE(client.update_image("a", {"R"}, 0, 0, 1, 1, nullptr));
    EXPECT_TRUE(client.update_image("a", {"R"}, 0, 0, 0, 5, nullptr));  // empty: nothing to send
    EXPECT_TRUE(client.ok());
    EXPECT_TRUE(client.create_image("a", 2, 3, {"R"}));
    EXPECT_TRUE(client.update_image("a", {"R"}, 0, 0, 2, 3, px));
    client.close();
    ASSERT_TRUE(server.wait());
    EXPECT_TRUE(server.errors().empty()) << server.errors().front();
    EXPECT_EQ(server.types(), (std::vector<int>{4, 6}));
}

// ---- failures ----

TEST(TevClient, NothingWorksBeforeConnecting) {
    TevClient client;
    EXPECT_FALSE(client.ok());
    EXPECT_FALSE(client.create_image("a", 1, 1, {"R"}));
    EXPECT_EQ(client.error(), "not connected to tev");
    float v = 1;
    EXPECT_FALSE(client.update_image("a", {"R"}, 0, 0, 1, 1, &v));
}

TEST(TevClient, ConnectingWhereNoServerListensFailsCleanly) {
    std::signal(SIGPIPE, SIG_DFL);  // a SIGPIPE would end the test program
    int port = unused_port();
    TevClient client;
    auto t0 = Clock::now();
    EXPECT_FALSE(client.connect(loopback(port)));
    EXPECT_LT(seconds_since(t0), 5.0);
    EXPECT_FALSE(client.ok());
    EXPECT_NE(client.error().find("cannot connect to tev at 127.0.0.1:" + std::to_string(port)),
              std::string::npos)
        << client.error();
    EXPECT_NE(client.error().find("is tev running?"), std::string::npos) << client.error();
    std::string first = client.error();
    float v = 1;
    EXPECT_FALSE(client.create_image("a", 1, 1, {"R"}));
    EXPECT_FALSE(client.update_image("a", {"R"}, 0, 0, 1, 1, &v));
    EXPECT_EQ(client.error(), first);  // the reason stays the first one
}

// A listener whose accept queue is full drops new connection requests (Linux), so a connect
// there can only end by timing out.
TEST(TevClient, ConnectGivesUpAfterItsTimeout) {
    int lfd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof(addr);
    ASSERT_EQ(::bind(lfd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
    ASSERT_EQ(::listen(lfd, 0), 0);
    ASSERT_EQ(::getsockname(lfd, reinterpret_cast<sockaddr*>(&addr), &len), 0);
    std::vector<int> fillers;
    for (int i = 0; i < 4; ++i) {
        int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
        ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr));
        fillers.push_back(fd);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));

    TevClientOptions options;
    options.connect_timeout_ms = 300;
    TevClient client(options);
    auto t0 = Clock::now();
    EXPECT_FALSE(client.connect(loopback(ntohs(addr.sin_port))));
    double took = seconds_since(t0);
    EXPECT_GE(took, 0.25);
    EXPECT_LT(took, 5.0);
    EXPECT_NE(client.error().find("timed out"), std::string::npos) << client.error();
    for (int fd : fillers) ::close(fd);
    ::close(lfd);
}

TEST(TevClient, AServerThatHangsUpMakesLaterUpdatesFail) {
    std::signal(SIGPIPE, SIG_DFL);  // a SIGPIPE would end the test program
    FakeTevServer server(FakeTevServer::Mode::close_after_first);
    TevClient client;
    ASSERT_TRUE(client.connect(loopback(server.port())));
    ASSERT_TRUE(client.create_image("gone", 64, 64, {"R", "G", "B"}));
    auto data = frame_data(0, 64, 64, 3);
    auto t0 = Clock::now();
    bool failed = false;
    for (int i = 0; i < 2000 && !failed && seconds_since(t0) < 20; ++i) {
        failed = !client.update_image("gone", {"R", "G", "B"}, 0, 0, 64, 64, data.data());
        if (!failed) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_TRUE(failed) << "updates kept succeeding after the server closed";
    EXPECT_LT(seconds_since(t0), 20.0);
    EXPECT_FALSE(client.ok());
    EXPECT_NE(client.error().find("lost the connection to tev at " + server.address()), std::string::npos)
        << client.error();
    std::string first = client.error();
    auto t1 = Clock::now();
    for (int i = 0; i < 100; ++i)
        EXPECT_FALSE(client.update_image("gone", {"R", "G", "B"}, 0, 0, 64, 64, data.data()));
    EXPECT_FALSE(client.create_image("gone", 64, 64, {"R"}));
    EXPECT_LT(seconds_since(t1), 1.0);  // no-ops once broken
    EXPECT_EQ(client.error(), first);
    server.wait(std::chrono::milliseconds(0));
    EXPECT_EQ(server.types().front(), 4);
}

TEST(TevClient, AServerThatStopsReadingMakesSendsTimeOut) {
    std::signal(SIGPIPE, SIG_DFL);
    FakeTevServer server(FakeTevServer::Mode::never_read);
    TevClientOptions options;
    options.send_timeout_ms = 200;
    TevClient client(options);
    ASSERT_TRUE(client.connect(loopback(server.port())));
    ASSERT_TRUE(client.create_image("stalled", 1024, 1024, {"R", "G", "B"}));
    std::vector<float> data(size_t(1024) * 1024 * 3, 0.5f);
    auto t0 = Clock::now();
    bool failed = false;
    for (int i = 0; i < 20 && !failed; ++i)
        failed = !client.update_image("stalled", {"R", "G", "B"}, 0, 0, 1024, 1024, data.data());
    double took = seconds_since(t0);
    ASSERT_TRUE(failed) << "sends to a server that reads nothing kept succeeding";
    EXPECT_LT(took, 15.0);
    EXPECT_FALSE(client.ok());
    EXPECT_NE(client.error().find("took no data for 200 ms"), std::string::npos) << client.error();
}

TEST(TevClient, ReconnectsAfterABrokenConnection) {
    TevClient client;
    EXPECT_FALSE(client.connect(loopback(unused_port())));
    FakeTevServer server;
    ASSERT_TRUE(client.connect(loopback(server.port()))) << client.error();
    EXPECT_TRUE(client.error().empty());
    EXPECT_TRUE(client.create_image("again", 1, 1, {"R"}));
    float v = 2;
    EXPECT_TRUE(client.update_image("again", {"R"}, 0, 0, 1, 1, &v));
    EXPECT_GT(client.bytes_sent(), 0u);
    client.close();
    ASSERT_TRUE(server.wait());
    EXPECT_EQ(server.types(), (std::vector<int>{4, 6}));
}

}  // namespace
}  // namespace phos::display
