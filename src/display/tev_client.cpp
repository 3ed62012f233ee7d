// The tev client: address parsing, a connect bounded in time, packet encoding (layout in
// tev_client.h) and sends that give up rather than block or raise SIGPIPE.
#include "display/tev_client.h"

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <limits>
#include <utility>

#include "core/error.h"

namespace phos::display {
namespace {

constexpr unsigned char kCreateImage = 4;
constexpr unsigned char kUpdateImageV3 = 6;

using Clock = std::chrono::steady_clock;

std::string errno_text(int err) { return std::strerror(err); }

// Appends little-endian values to a packet; begin() leaves room for the length, finish() fills it.
class PacketWriter {
public:
    explicit PacketWriter(std::vector<unsigned char>& out) : out_(out) {}

    void begin(unsigned char type) {
        out_.clear();
        u32(0);
        out_.push_back(type);
    }
    void u8(unsigned char v) { out_.push_back(v); }
    void u32(std::uint32_t v) {
        for (int i = 0; i < 4; ++i) out_.push_back(static_cast<unsigned char>(v >> (8 * i)));
    }
    void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
    void i64(std::int64_t v) {
        auto u = static_cast<std::uint64_t>(v);
        for (int i = 0; i < 8; ++i) out_.push_back(static_cast<unsigned char>(u >> (8 * i)));
    }
    void str(const std::string& s) {
        out_.insert(out_.end(), s.begin(), s.end());
        out_.push_back(0);
    }
    void floats(const float* p, std::size_t n) {
        std::size_t at = out_.size();
        out_.resize(at + 4 * n);
        if constexpr (std::endian::native == std::endian::little) {
            if (n > 0) std::memcpy(out_.data() + at, p, 4 * n);
        } else {
            for (std::size_t i = 0; i < n; ++i) {
                auto u = std::bit_cast<std::uint32_t>(p[i]);
                for (int b = 0; b < 4; ++b) out_[at + 4 * i + b] = static_cast<unsigned char>(u >> (8 * b));
            }
        }
    }
    // False when the packet is too long for its u32 length.
    bool finish() {
        if (out_.size() > std::numeric_limits<std::uint32_t>::max()) return false;
        auto n = static_cast<std::uint32_t>(out_.size());
        for (int i = 0; i < 4; ++i) out_[i] = static_cast<unsigned char>(n >> (8 * i));
        return true;
    }

private:
    std::vector<unsigned char>& out_;
};

// Why a channel list cannot be sent, or "".
std::string check_channels(const std::vector<std::string>& names) {
    if (names.empty()) return "no channels";
    if (names.size() > 4096) return "too many channels";
    for (const std::string& n : names) {
        if (n.empty()) return "empty channel name";
        if (n.find('\0') != std::string::npos) return "channel name contains a NUL";
    }
    return "";
}

std::string check_name(const std::string& name) {
    if (name.find('\0') != std::string::npos) return "image name contains a NUL";
    return "";
}

// A rectangle of the region (coordinates relative to its corner) that goes in one packet.
struct Chunk {
    int x, y, width, height;
};

// Whole rows while a row fits in `max_floats`, else pieces of single rows; row-major order, so
// the chunks cover the region exactly once.
std::vector<Chunk> plan_chunks(int width, int height, std::size_t channels, std::size_t max_floats) {
    std::vector<Chunk> chunks;
    max_floats = std::max(max_floats, channels);
    std::size_t row_floats = std::size_t(width) * channels;
    if (row_floats <= max_floats) {
        int rows = int(std::min<std::size_t>(max_floats / row_floats, std::size_t(height)));
        for (int y = 0; y < height; y += rows) chunks.push_back({0, y, width, std::min(rows, height - y)});
    } else {
        int cols = int(std::min<std::size_t>(max_floats / channels, std::size_t(width)));
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; x += cols) chunks.push_back({x, y, std::min(cols, width - x), 1});
    }
    return chunks;
}

void write_update_header(PacketWriter& w, const std::string& name, const std::vector<std::string>& channels,
                         int x, int y, int width, int height) {
    auto n = static_cast<std::int32_t>(channels.size());
    w.begin(kUpdateImageV3);
    w.u8(0);  // grabFocus: only the create packet takes focus
    w.str(name);
    w.i32(n);
    for (const std::string& c : channels) w.str(c);
    w.i32(x);
    w.i32(y);
    w.i32(width);
    w.i32(height);
    for (std::int32_t c = 0; c < n; ++c) w.i64(c);  // offsets: interleaved by pixel
    for (std::int32_t c = 0; c < n; ++c) w.i64(n);  // strides
}

// Waits until a non-blocking connect on `fd` finishes or `deadline` passes; "" on success.
std::string finish_connect(int fd, Clock::time_point deadline) {
    for (;;) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) return "timed out";
        pollfd p{fd, POLLOUT, 0};
        int r = ::poll(&p, 1, int(std::min<long long>(left, 1 << 30)));
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) return errno_text(errno);
        if (r == 0) return "timed out";
        int err = 0;
        socklen_t len = sizeof(err);
        if (::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) != 0) return errno_text(errno);
        return err == 0 ? "" : errno_text(err);
    }
}

[[noreturn]] void bad_address(std::string_view option, std::string_view text, const std::string& why) {
    throw InputError(
        std::string(option) + ": '" + std::string(text) + "': " + why +
        " (expected HOST:PORT, HOST or :PORT, e.g. 127.0.0.1:" + std::to_string(kTevDefaultPort) + ")");
}

int parse_port(std::string_view option, std::string_view text, std::string_view port) {
    if (port.empty()) bad_address(option, text, "the port is empty");
    for (char c : port)
        if (c < '0' || c > '9') bad_address(option, text, "port '" + std::string(port) + "' is not a number");
    int value = port.size() > 5 ? 0 : std::stoi(std::string(port));  // only digits here
    if (value < 1 || value > 65535)
        bad_address(option, text, "port " + std::string(port) + " is not in [1, 65535]");
    return value;
}

}  // namespace

std::string TevAddress::to_string() const {
    bool v6 = host.find(':') != std::string::npos;
    return (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

TevAddress parse_tev_address(std::string_view text, std::string_view option) {
    TevAddress a;
    std::string_view host = text;
    std::string_view port;
    bool has_port = false;
    if (!text.empty() && text.front() == '[') {
        std::size_t close = text.find(']');
        if (close == std::string_view::npos) bad_address(option, text, "missing ']' after the IPv6 address");
        host = text.substr(1, close - 1);
        std::string_view rest = text.substr(close + 1);
        if (!rest.empty()) {
            if (rest.front() != ':') bad_address(option, text, "expected ':' after ']'");
            port = rest.substr(1);
            has_port = true;
        }
    } else if (std::count(text.begin(), text.end(), ':') == 1) {
        std::size_t colon = text.find(':');
        host = text.substr(0, colon);
        port = text.substr(colon + 1);
        has_port = true;
    }  // no ':' (a host), or several (a bare IPv6 address): the default port
    if (!host.empty()) a.host = std::string(host);
    if (has_port) a.port = parse_port(option, text, port);
    return a;
}

void TevClient::close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

bool TevClient::fail(std::string reason) {
    close();
    error_ = std::move(reason);
    return false;
}

bool TevClient::usable() {
    if (ok()) return true;
    if (error_.empty()) error_ = "not connected to tev";
    return false;
}

bool TevClient::connect(const TevAddress& address) {
    close();
    error_.clear();
    bytes_sent_ = 0;
    peer_ = address.to_string();
    auto deadline = Clock::now() + std::chrono::milliseconds(std::max(options_.connect_timeout_ms, 1));

    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_NUMERICSERV;
    addrinfo* found = nullptr;
    std::string port = std::to_string(address.port);
    int gai = ::getaddrinfo(address.host.c_str(), port.c_str(), &hints, &found);
    if (gai != 0) return fail("cannot resolve tev host '" + address.host + "': " + ::gai_strerror(gai));

    std::string why = "no address";
    for (addrinfo* ai = found; ai; ai = ai->ai_next) {
        int fd = ::socket(ai->ai_family, ai->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, ai->ai_protocol);
        if (fd < 0) {
            why = errno_text(errno);
            continue;
        }
        int r = ::connect(fd, ai->ai_addr, ai->ai_addrlen);
        why = r == 0 ? "" : errno != EINPROGRESS ? errno_text(errno) : finish_connect(fd, deadline);
        if (why.empty()) {
            fd_ = fd;
            break;
        }
        ::close(fd);
        if (Clock::now() >= deadline) break;
    }
    ::freeaddrinfo(found);
    if (fd_ < 0) {
        std::string hint = why == errno_text(ECONNREFUSED) ? " (is tev running?)" : "";
        return fail("cannot connect to tev at " + peer_ + ": " + why + hint);
    }

    // Blocking sends from here on, each bounded by SO_SNDTIMEO; Nagle off so that a small last
    // packet goes out at once.
    int flags = ::fcntl(fd_, F_GETFL, 0);
    if (flags < 0 || ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK) < 0)
        return fail("cannot set up the tev socket: " + errno_text(errno));
    int ms = std::max(options_.send_timeout_ms, 1);
    timeval tv{ms / 1000, (ms % 1000) * 1000};
    if (::setsockopt(fd_, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof(tv)) != 0)
        return fail("cannot set the tev send timeout: " + errno_text(errno));
    int one = 1;
    ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));  // only a latency nicety
    return true;
}

bool TevClient::send_packet(const std::vector<unsigned char>& packet) {
    int ms = std::max(options_.send_timeout_ms, 1);
    auto deadline = Clock::now() + 8 * std::chrono::milliseconds(ms);
    std::size_t sent = 0;
    while (sent < packet.size()) {
        // MSG_NOSIGNAL: a closed connection is an EPIPE here, not a SIGPIPE killing phos.
        ssize_t r = ::send(fd_, packet.data() + sent, packet.size() - sent, MSG_NOSIGNAL);
        if (r > 0) {
            sent += std::size_t(r);
            bytes_sent_ += std::uint64_t(r);
        } else if (r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            return fail("tev at " + peer_ + " took no data for " + std::to_string(ms) + " ms");
        } else if (r < 0 && errno != EINTR) {
            return fail("lost the connection to tev at " + peer_ + ": " + errno_text(errno));
        }
        if (sent < packet.size() && Clock::now() > deadline)
            return fail("tev at " + peer_ + " is reading too slowly");
    }
    return true;
}

bool TevClient::create_image(const std::string& name, int width, int height,
                             const std::vector<std::string>& channel_names, bool grab_focus) {
    if (!usable()) return false;
    std::string bad = check_name(name);
    if (bad.empty()) bad = check_channels(channel_names);
    if (bad.empty() && (width <= 0 || height <= 0)) bad = "empty image";
    if (!bad.empty()) {
        error_ = "tev create_image: " + bad;
        return false;
    }
    std::vector<unsigned char> packet;
    PacketWriter w(packet);
    w.begin(kCreateImage);
    w.u8(grab_focus ? 1 : 0);
    w.str(name);
    w.i32(width);
    w.i32(height);
    w.i32(static_cast<std::int32_t>(channel_names.size()));
    for (const std::string& c : channel_names) w.str(c);
    if (!w.finish()) {
        error_ = "tev create_image: packet too long";
        return false;
    }
    return send_packet(packet);
}

bool TevClient::update_image(const std::string& name, const std::vector<std::string>& channel_names, int x,
                             int y, int width, int height, const float* data, std::size_t row_stride) {
    if (!usable()) return false;
    std::size_t nc = channel_names.size();
    std::string bad = check_name(name);
    if (bad.empty()) bad = check_channels(channel_names);
    if (bad.empty() && (x < 0 || y < 0 || width < 0 || height < 0)) bad = "negative region";
    if (bad.empty() && (std::int64_t(x) + width > std::numeric_limits<std::int32_t>::max() ||
                        std::int64_t(y) + height > std::numeric_limits<std::int32_t>::max()))
        bad = "region out of range";
    if (row_stride == 0) row_stride = std::size_t(width) * nc;
    if (bad.empty() && row_stride < std::size_t(width) * nc) bad = "row stride shorter than a row";
    if (bad.empty() && !data && width > 0 && height > 0) bad = "no data";
    if (!bad.empty()) {
        error_ = "tev update_image: " + bad;
        return false;
    }
    if (width == 0 || height == 0) return true;
    std::vector<unsigned char> packet;
    PacketWriter w(packet);
    for (const Chunk& c : plan_chunks(width, height, nc, options_.max_floats_per_packet)) {
        write_update_header(w, name, channel_names, x + c.x, y + c.y, c.width, c.height);
        for (int row = c.y; row < c.y + c.height; ++row)
            w.floats(data + std::size_t(row) * row_stride + std::size_t(c.x) * nc, std::size_t(c.width) * nc);
        if (!w.finish()) {
            error_ = "tev update_image: packet too long";
            return false;
        }
        if (!send_packet(packet)) return false;
    }
    return true;
}

}  // namespace phos::display
