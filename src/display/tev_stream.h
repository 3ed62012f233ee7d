// `phos render --tev [HOST:PORT]`: a thread that streams the live image to a running tev viewer
// (display/tev_client.h): the image is created once with a channel group per layer (R, G, B
// for the image, direct.R, ... for the film's layers and AOVs; created again when layers appear),
// then the whole image is sent whenever it changed, at most four times a second, and once more at
// the end. A tev that is not running or goes away mid-render is one warning; the render goes on.
#pragma once

#include <atomic>
#include <string>
#include <thread>

#include "display/live_image.h"
#include "display/tev_client.h"

namespace phos::display {

class TevStream {
public:
    TevStream() = default;
    ~TevStream() { finish(); }
    TevStream(const TevStream&) = delete;
    TevStream& operator=(const TevStream&) = delete;

    // Starts streaming `image` to `address` as the tev image `name`.
    void start(const LiveImage& image, const TevAddress& address, const std::string& name);
    // Waits until the final image (the live image is finished) has been sent, then disconnects.
    void finish();
    // Bytes sent so far (for -v).
    uint64_t bytes_sent() const { return bytes_.load(); }

private:
    std::thread thread_;
    std::atomic<uint64_t> bytes_{0};
};

}  // namespace phos::display
