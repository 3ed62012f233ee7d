// A stand-in for tev in tests: listens on 127.0.0.1 at an ephemeral port, accepts one client on a
// thread and decodes its packets as strictly as tev's Ipc.cpp reads them (and stricter: no
// trailing bytes). It can also misbehave: hang up after the first packet, or never read.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace phos::display::test {

struct CreatePacket {
    bool grab_focus = false;
    std::string name;
    int width = 0, height = 0;
    std::vector<std::string> channels;
};

struct UpdatePacket {
    bool grab_focus = false;
    std::string name;
    std::vector<std::string> channels;
    int x = 0, y = 0, width = 0, height = 0;
    std::vector<std::int64_t> offsets, strides;
    std::vector<float> data;  // exactly the floats tev requires

    // Channel c of region pixel (px, py), read the way tev reads it.
    float value(int c, int px, int py) const {
        return data[size_t(offsets[c] + (int64_t(px) + int64_t(py) * width) * strides[c])];
    }
};

class FakeTevServer {
public:
    enum class Mode {
        decode,             // read and decode until the client hangs up
        close_after_first,  // decode one packet, then close the connection
        never_read,         // accept, then read nothing (a stalled tev), small receive buffer
    };

    explicit FakeTevServer(Mode mode = Mode::decode);
    ~FakeTevServer();
    FakeTevServer(const FakeTevServer&) = delete;
    FakeTevServer& operator=(const FakeTevServer&) = delete;

    int port() const { return port_; }
    std::string address() const { return "127.0.0.1:" + std::to_string(port_); }

    // Waits for the client to hang up (at most `timeout`), then stops; true if it hung up.
    // The results below are complete once this has returned.
    bool wait(std::chrono::milliseconds timeout = std::chrono::seconds(20));

    const std::vector<CreatePacket>& creates() const { return creates_; }
    const std::vector<UpdatePacket>& updates() const { return updates_; }
    // Packet types in arrival order, and every protocol violation seen.
    const std::vector<int>& types() const { return types_; }
    const std::vector<std::string>& errors() const { return errors_; }

private:
    void run();
    void decode(const unsigned char* p, std::size_t n);

    Mode mode_;
    int listen_fd_ = -1;
    int port_ = 0;
    std::atomic<bool> stop_{false};
    std::atomic<bool> hung_up_{false};
    std::thread thread_;
    std::vector<CreatePacket> creates_;
    std::vector<UpdatePacket> updates_;
    std::vector<int> types_;
    std::vector<std::string> errors_;
};

}  // namespace phos::display::test
