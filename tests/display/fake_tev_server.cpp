// The fake tev server's socket loop and its packet decoder (layout in display/tev_client.h).
#include "display/fake_tev_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace phos::display::test {
namespace {

// Reads little-endian fields; throws std::runtime_error past the end, as tev's IStream does.
class Reader {
public:
    Reader(const unsigned char* p, std::size_t n) : p_(p), n_(n) {}
    std::uint64_t uint(int bytes) {
        need(std::size_t(bytes));
        std::uint64_t v = 0;
        for (int i = 0; i < bytes; ++i) v |= std::uint64_t(p_[at_ + i]) << (8 * i);
        at_ += std::size_t(bytes);
        return v;
    }
    int i32() { return int(std::int32_t(std::uint32_t(uint(4)))); }
    std::int64_t i64() { return std::int64_t(uint(8)); }
    bool flag() {
        auto b = uint(1);
        if (b > 1) throw std::runtime_error("bool byte " + std::to_string(b));
        return b == 1;
    }
    std::string str() {
        std::string s;
        for (;;) {
            auto c = char(uint(1));
            if (c == '\0') return s;
            s += c;
        }
    }
    float f32() {
        auto u = std::uint32_t(uint(4));
        float f;
        std::memcpy(&f, &u, 4);
        return f;
    }
    std::size_t left() const { return n_ - at_; }

private:
    void need(std::size_t k) {
        if (n_ - at_ < k) throw std::runtime_error("read past the end of the packet");
    }
    const unsigned char* p_;
    std::size_t n_;
    std::size_t at_ = 0;
};

}  // namespace

FakeTevServer::FakeTevServer(Mode mode) : mode_(mode) {
    listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (listen_fd_ < 0) throw std::runtime_error("socket failed");
    if (mode_ == Mode::never_read) {
        int small = 4096;  // inherited by the accepted socket: the client's sends stall sooner
        ::setsockopt(listen_fd_, SOL_SOCKET, SO_RCVBUF, &small, sizeof(small));
    }
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = 0;
    socklen_t len = sizeof(addr);
    if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0 ||
        ::listen(listen_fd_, 4) != 0 ||
        ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
        ::close(listen_fd_);
        throw std::runtime_error(std::string("cannot listen: ") + std::strerror(errno));
    }
    port_ = ntohs(addr.sin_port);
    thread_ = std::thread([this] { run(); });
}

FakeTevServer::~FakeTevServer() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    if (listen_fd_ >= 0) ::close(listen_fd_);
}

bool FakeTevServer::wait(std::chrono::milliseconds timeout) {
    auto end = std::chrono::steady_clock::now() + timeout;
    while (!hung_up_ && std::chrono::steady_clock::now() < end)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    return hung_up_;
}

void FakeTevServer::run() {
    int fd = -1;
    while (!stop_ && fd < 0) {
        pollfd p{listen_fd_, POLLIN, 0};
        if (::poll(&p, 1, 20) > 0) fd = ::accept(listen_fd_, nullptr, nullptr);
    }
    if (fd < 0) return;

    std::vector<unsigned char> buf;
    std::vector<unsigned char> chunk(1 << 16);
    std::size_t decoded_packets = 0;
    while (!stop_) {
        if (mode_ == Mode::never_read) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            continue;
        }
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, 20) <= 0) continue;
        ssize_t r = ::recv(fd, chunk.data(), chunk.size(), 0);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) {
            if (!buf.empty()) errors_.push_back("connection ended inside a packet");
            hung_up_ = true;
            break;
        }
        buf.insert(buf.end(), chunk.begin(), chunk.begin() + r);
        // Whole packets, as tev's SocketConnection::service cuts them.
        while (buf.size() >= 4) {
            std::size_t len = buf[0] | buf[1] << 8 | buf[2] << 16 | std::size_t(buf[3]) << 24;
            if (len < 5) {
                errors_.push_back("packet length " + std::to_string(len));
                buf.clear();
                break;
            }
            if (buf.size() < len) break;
            decode(buf.data(), len);
            buf.erase(buf.begin(), buf.begin() + std::ptrdiff_t(len));
            ++decoded_packets;
        }
        if (mode_ == Mode::close_after_first && decoded_packets > 0) break;
    }
    ::close(fd);
}

void FakeTevServer::decode(const unsigned char* p, std::size_t n) {
    try {
        Reader in(p, n);
        in.uint(4);  // the length, already checked
        int type = int(in.uint(1));
        types_.push_back(type);
        if (type == 4) {  // CreateImage
            CreatePacket c;
            c.grab_focus = in.flag();
            c.name = in.str();
            c.width = in.i32();
            c.height = in.i32();
            int nc = in.i32();
            if (nc <= 0) throw std::runtime_error("create: channel count " + std::to_string(nc));
            for (int i = 0; i < nc; ++i) c.channels.push_back(in.str());
            if (in.left() != 0) throw std::runtime_error("create: trailing bytes");
            creates_.push_back(std::move(c));
        } else if (type == 6) {  // UpdateImageV3
            UpdatePacket u;
            u.grab_focus = in.flag();
            u.name = in.str();
            int nc = in.i32();
            if (nc <= 0) throw std::runtime_error("update: channel count " + std::to_string(nc));
            for (int i = 0; i < nc; ++i) u.channels.push_back(in.str());
            u.x = in.i32();
            u.y = in.i32();
            u.width = in.i32();
            u.height = in.i32();
            for (int i = 0; i < nc; ++i) u.offsets.push_back(in.i64());
            for (int i = 0; i < nc; ++i) u.strides.push_back(in.i64());
            std::int64_t pixels = std::int64_t(u.width) * u.height;
            if (pixels <= 0) throw std::runtime_error("update: empty region");
            std::int64_t need = 0;  // tev's stridedImageDataSize
            for (int c = 0; c < nc; ++c)
                need = std::max(need, u.offsets[c] + (pixels - 1) * u.strides[c] + 1);
            if (in.left() != std::size_t(need) * 4)
                throw std::runtime_error("update: " + std::to_string(in.left()) + " data bytes, expected " +
                                         std::to_string(need * 4));
            for (std::int64_t i = 0; i < need; ++i) u.data.push_back(in.f32());
            updates_.push_back(std::move(u));
        } else {
            throw std::runtime_error("unexpected packet type " + std::to_string(type));
        }
    } catch (const std::exception& e) {
        errors_.push_back(e.what());
    }
}

}  // namespace phos::display::test
