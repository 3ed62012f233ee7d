// Inputs found by fuzzing the checkpoint decoder (fuzz/checkpoint_fuzzer.cpp, scripts/fuzz.sh), kept
// as regression tests: a decoded checkpoint must be consistent with its own image size, and empty
// parts must decode without undefined behaviour.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "core/error.h"
#include "render/progressive_checkpoint.h"

namespace phos::render {
namespace {

template <class T>
void put(std::string& out, T v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// A version-4 checkpoint, checksum appended, with no options, arguments, slots or tiles, and one
// film layer holding `film_values` doubles.
std::string forged(uint32_t width, uint32_t height, uint32_t slots_per_pixel, size_t film_values) {
    std::string b = "PHOSCKPT";
    put(b, ProgressiveState::kVersion);
    put(b, uint32_t(4));
    b += "path";
    put(b, width);
    put(b, height);
    put(b, slots_per_pixel);
    for (int i = 0; i < 7; ++i) put(b, uint64_t(i));
    put(b, uint32_t(0));  // options
    put(b, uint32_t(0));  // arguments
    put(b, uint64_t(0));  // slots
    put(b, uint32_t(0));  // tiles
    put(b, uint32_t(1));  // layers
    put(b, uint32_t(0));  // layer name ""
    for (size_t i = 0; i < film_values; ++i) put(b, 1.0);
    put(b, uint64_t(0));  // payload
    put(b, hash_bytes(b.data(), b.size()));
    return b;
}

// 2^31 x 2^31 pixels times 4 slots per pixel, or times 4 film values, is 2^64, which wrapped to 0:
// a header claiming a huge image decoded with no slots or empty film layers (the harness's
// consistency check caught both).
TEST(CheckpointFuzz, ImageSizesThatOverflowAreRejected) {
    for (const uint32_t slots_per_pixel : {4u, 0u}) {
        try {
            decode_checkpoint(forged(1u << 31, 1u << 31, slots_per_pixel, 0), "'forged'");
            ADD_FAILURE() << "accepted a checkpoint whose size overflows, " << slots_per_pixel << " slots";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("image size is too large"), std::string::npos) << e.what();
        }
    }
}

// Empty slot and tile lists were copied with memcpy into a null pointer (undefined even for 0 bytes,
// reported by UBSan); such a checkpoint decodes and re-encodes unchanged.
TEST(CheckpointFuzz, EmptyPartsDecode) {
    const std::string bytes = forged(1, 2, 0, 8);
    const ProgressiveState s = decode_checkpoint(bytes, "'empty parts'");
    EXPECT_TRUE(s.slots.empty());
    EXPECT_TRUE(s.tile_samples.empty());
    ASSERT_EQ(s.film.size(), 1u);
    EXPECT_EQ(s.film[0].second.size(), 8u);
    EXPECT_EQ(encode_checkpoint(s), bytes);
}

}  // namespace
}  // namespace phos::render
