// A client for the tev image viewer's TCP protocol, so a render can be watched as it converges
// (`phos render --tev [HOST:PORT]`, like pbrt-v4's --display-server). Plain POSIX sockets; sends
// are bounded in time, never raise SIGPIPE, and after the first failure the client goes quiet.
//
// Wire format, checked against tev's own reader and writer: Tom94/tev src/Ipc.cpp and
// include/tev/Ipc.h (IpcPacket::setCreateImage / setUpdateImage, interpretAsCreateImage /
// interpretAsUpdateImage, IStream / OStream, SocketConnection::service), both in the 1.2x
// releases (TEV_NAMESPACE_BEGIN era) and today's, which agree; Tom94/tev src/Channel.cpp
// (Channel::updateTile); and mmp/pbrt-v4 src/pbrt/util/display.cpp (a client that sends the same
// CreateImage). Integers are little-endian, floats IEEE-754 binary32 little-endian, strings are
// bytes ended by a NUL, a bool is one byte (tev reads `== 1` as true):
//
//   every packet   u32 length (bytes, counting these 4) | u8 type | payload
//   CreateImage 4  u8 grabFocus | name | i32 width | i32 height | i32 nChannels |
//                  nChannels x channel name
//   UpdateImageV3  u8 grabFocus | name | i32 nChannels | nChannels x channel name |
//             6    i32 x | i32 y | i32 width | i32 height |
//                  nChannels x i64 offset | nChannels x i64 stride | float data
//
// Note that x, y, width, height come before the offsets and strides. Channel c of region pixel
// (px, py) is data[offset[c] + (px + py * width) * stride[c]], rows top to bottom; tev requires at
// least max_c(offset[c] + (width * height - 1) * stride[c] + 1) floats. This client sends pixels
// interleaved (offset[c] = c, stride[c] = nChannels) and exactly that many floats. tev ignores an
// update whose rectangle does not fit its image, or that names an unknown channel or image, and
// buffers a whole packet in memory before decoding it, so regions are split into packets of at
// most TevClientOptions::max_floats_per_packet floats (whole rows, or row pieces for very wide
// images). tev 1.2x listens on IPv4 only, at 127.0.0.1:14158 by default.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace phos::display {

inline constexpr int kTevDefaultPort = 14158;

// Where tev listens. `host` is a name or a numeric address (IPv6 without brackets).
struct TevAddress {
    std::string host = "127.0.0.1";
    int port = kTevDefaultPort;

    // "host:port", an IPv6 host in brackets ("[::1]:14158").
    std::string to_string() const;
};

// Parses the --tev argument: "HOST:PORT", "HOST", ":PORT", "[IPV6]:PORT", a bare IPv6 address,
// or "" (all defaults). Throws InputError naming `option` for a bad port (not a number, outside
// [1, 65535], empty after ':') or an unclosed '['; the host is only checked when connecting.
TevAddress parse_tev_address(std::string_view text, std::string_view option = "--tev");

struct TevClientOptions {
    int connect_timeout_ms = 1000;  // for the whole connect(), over every address the host has
    // Longest wait for tev to take any more bytes (SO_SNDTIMEO); one packet may take at most
    // 8 times this in all (a tev that reads a byte now and then cannot hold the render either).
    int send_timeout_ms = 3000;
    std::size_t max_floats_per_packet = std::size_t(1) << 20;  // 4 MiB of pixel data
};

// One connection to tev. Not thread-safe: use it from one thread (e.g. the preview thread).
// Every call returns false on failure with the reason in error(). A failed connect or a failed
// send (tev closed, stalled past the timeout, ...) leaves the client not ok(): the connection is
// closed and later calls return false at once without touching error(), so the caller can print
// one warning and carry on rendering. Bad arguments return false but keep the connection.
class TevClient {
public:
    explicit TevClient(TevClientOptions options = {}) : options_(options) {}
    ~TevClient() { close(); }
    TevClient(const TevClient&) = delete;
    TevClient& operator=(const TevClient&) = delete;

    // Closes any previous connection, then connects to `address` within
    // options().connect_timeout_ms.
    bool connect(const TevAddress& address);

    // Opens (or replaces) image `name` in tev, every channel zero.
    bool create_image(const std::string& name, int width, int height,
                      const std::vector<std::string>& channel_names, bool grab_focus = true);

    // Sets the width x height region at (x, y) of image `name`. `data` is interleaved by pixel:
    // channel c of region pixel (px, py) is data[py * row_stride + px * channel_names.size() + c],
    // rows top to bottom; `row_stride` (in floats) 0 means width * channel_names.size(), so a
    // sub-rectangle of a larger interleaved buffer can be sent in place. An empty region sends
    // nothing and succeeds.
    bool update_image(const std::string& name, const std::vector<std::string>& channel_names, int x, int y,
                      int width, int height, const float* data, std::size_t row_stride = 0);

    void close();

    // Connected and no send has failed.
    bool ok() const { return fd_ >= 0; }
    const std::string& error() const { return error_; }
    const TevClientOptions& options() const { return options_; }
    std::uint64_t bytes_sent() const { return bytes_sent_; }

private:
    bool fail(std::string reason);  // closes, records the reason, returns false
    bool usable();                  // ok(), else records why not (first time only)
    bool send_packet(const std::vector<unsigned char>& packet);

    TevClientOptions options_;
    int fd_ = -1;
    std::string peer_;  // "host:port", for messages
    std::string error_;
    std::uint64_t bytes_sent_ = 0;
};

}  // namespace phos::display
