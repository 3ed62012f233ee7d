// The tev streaming thread (see tev_stream.h).
#include "display/tev_stream.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "core/log.h"

namespace phos::display {
namespace {

// tev's channel names for the layers: "R", "G", "B" for the image, "layer.R"... for the others.
std::vector<std::string> channels_of(const std::vector<std::string>& layers) {
    std::vector<std::string> out;
    for (const std::string& layer : layers)
        for (const char* c : {"R", "G", "B"})
            out.push_back(layer == "image" ? std::string(c) : layer + "." + c);
    return out;
}

}  // namespace

void TevStream::start(const LiveImage& image, const TevAddress& address, const std::string& name) {
    thread_ = std::thread([this, &image, address, name] {
        using clock = std::chrono::steady_clock;
        TevClient tev;
        if (!tev.connect(address)) {
            log::warn("--tev: " + tev.error() + "; not streaming (is tev running?)");
            return;
        }
        const int w = image.width(), h = image.height();
        std::vector<std::string> created;
        uint64_t sent = 0;
        for (;;) {
            image.wait(sent, 0.25);
            const bool last = image.finished();
            const uint64_t version = image.version();
            const auto began = clock::now();
            if (version != sent) {
                const std::vector<std::string> layers = image.layer_names();
                const std::vector<std::string> channels = channels_of(layers);
                bool ok = true;
                uint64_t since = sent;
                if (layers != created) {  // a new image in tev: send everything
                    ok = tev.create_image(name, w, h, channels, created.empty());
                    created = layers;
                    since = 0;
                }
                // Only the blocks that changed since the last update, one update per row of blocks.
                for (const Region& r : image.changed_since(since)) {
                    std::vector<float> data(size_t(r.width()) * size_t(r.height()) * channels.size());
                    for (size_t l = 0; l < layers.size() && ok; ++l) {
                        const std::vector<Rgb> values = image.read_region(l, r);
                        for (size_t i = 0; i < values.size(); ++i)
                            for (int c = 0; c < 3; ++c)
                                data[i * channels.size() + l * 3 + size_t(c)] = values[i][c];
                    }
                    ok = ok &&
                         tev.update_image(name, channels, r.x0, r.y0, r.width(), r.height(), data.data());
                }
                bytes_ = tev.bytes_sent();
                if (!ok) {
                    log::warn("--tev: " + tev.error() + "; stopped streaming (the render goes on)");
                    return;
                }
                sent = version;
            }
            if (last && image.version() == sent) break;
            // At most four updates a second (a large image is megabytes per update), and spaced so
            // that streaming takes at most ~2 % of one core.
            const auto pause = clock::now() + std::max<clock::duration>(std::chrono::milliseconds(250),
                                                                        (clock::now() - began) * 50);
            while (!image.finished() && clock::now() < pause) image.wait(image.version(), 0.05);
        }
        tev.close();
    });
}

void TevStream::finish() {
    if (thread_.joinable()) thread_.join();
}

}  // namespace phos::display
