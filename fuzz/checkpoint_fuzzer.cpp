// libFuzzer harness for the checkpoint decoder (render/progressive_checkpoint.h). The input is
// decoded as given and, so the fuzzer gets past the checksum, once more with a valid checksum
// appended. A decoded state must be self-consistent and re-encode to exactly the same bytes.
#include <string>

#include "fuzz/fuzz_support.h"
#include "render/progressive_checkpoint.h"

namespace {

void check(const std::string& bytes) {
    using phos::fuzz::invariant_failed;
    phos::fuzz::expect_reader_errors([&] {
        const phos::render::ProgressiveState s = phos::render::decode_checkpoint(bytes, "'fuzz'");
        const unsigned __int128 pixels = static_cast<unsigned __int128>(s.width) * s.height;
        if (static_cast<unsigned __int128>(s.slots.size()) != pixels * s.slots_per_pixel)
            invariant_failed("slot count does not match width x height x slots per pixel");
        for (const auto& [name, sums] : s.film)
            if (static_cast<unsigned __int128>(sums.size()) != pixels * 4)
                invariant_failed("film layer size does not match width x height x 4");
        if (phos::render::encode_checkpoint(s) != bytes) invariant_failed("decode/encode round trip");
    });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    check(bytes);
    const uint64_t sum = phos::render::hash_bytes(bytes.data(), bytes.size());
    bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
    check(bytes);
    return 0;
}
