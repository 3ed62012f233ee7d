// Progressive-render checkpoints: exact round trip (option list included), and refusal
// (InputError with a clear reason) of truncated, corrupted, foreign, other-version and
// other-render files, naming each differing option with both values.
#include "render/progressive_checkpoint.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace phos::render {
namespace {

ProgressiveState sample_state() {
    ProgressiveState s;
    s.integrator = "sppm";
    s.width = 5;
    s.height = 3;
    s.slots_per_pixel = 2;
    s.seed = 42;
    s.scene_hash = 0x1234;
    s.options = {{"--alpha", "0.7"}, {"--max-depth", "16"}, {"--radius", "0"}, {"--dof", ""}};
    s.options_hash = hash_options(s.options);
    s.iterations = 17;
    s.photons_emitted = 17 * 1000;
    s.target_iterations = 64;
    s.command_line = {"/abs/scene.scn", "--integrator", "sppm", "-o", "out file.exr", ""};
    s.slots.resize(30);
    for (size_t i = 0; i < s.slots.size(); ++i) {
        s.slots[i].n = 0.1 * double(i) + 1e-17;
        s.slots[i].r2 = 1.0 / (3.0 + double(i));
        for (int c = 0; c < 3; ++c) {
            s.slots[i].tau[c] = std::sqrt(double(i + c));
            s.slots[i].direct[c] = -1.0 / 7.0 * double(c + 1);
        }
    }
    // The sample-based integrators' parts (a real checkpoint has either these or slots).
    s.rejected_samples = 3;
    s.tile_samples = {7, 8, 7};
    for (const char* layer : {"", "caustic"}) {
        std::vector<double> sums(5 * 3 * 4);
        for (size_t i = 0; i < sums.size(); ++i) sums[i] = std::sin(double(i) + double(layer[0]));
        s.film.emplace_back(layer, sums);
    }
    s.payload = std::string("maps\0with\xff bytes", 16);
    return s;
}

std::string error_of(const std::string& bytes) {
    try {
        decode_checkpoint(bytes, "'x'");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(Checkpoint, RoundTripIsExact) {
    const ProgressiveState s = sample_state();
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("phos-checkpoint-test-" + std::to_string(getpid()) + ".ckpt"))
                                 .string();
    save_checkpoint(path, s);
    const ProgressiveState t = load_checkpoint(path);
    std::filesystem::remove(path);
    EXPECT_EQ(t.integrator, s.integrator);
    EXPECT_EQ(t.command_line, s.command_line);
    EXPECT_EQ(t.width, s.width);
    EXPECT_EQ(t.height, s.height);
    EXPECT_EQ(t.slots_per_pixel, s.slots_per_pixel);
    EXPECT_EQ(t.seed, s.seed);
    EXPECT_EQ(t.scene_hash, s.scene_hash);
    EXPECT_EQ(t.options, s.options);
    EXPECT_EQ(t.options_hash, s.options_hash);
    EXPECT_EQ(t.iterations, s.iterations);
    EXPECT_EQ(t.photons_emitted, s.photons_emitted);
    EXPECT_EQ(t.target_iterations, s.target_iterations);
    ASSERT_EQ(t.slots.size(), s.slots.size());
    EXPECT_EQ(std::memcmp(t.slots.data(), s.slots.data(), s.slots.size() * sizeof(PixelStats)), 0);
    EXPECT_EQ(t.rejected_samples, s.rejected_samples);
    EXPECT_EQ(t.tile_samples, s.tile_samples);
    EXPECT_EQ(t.film, s.film);
    EXPECT_EQ(t.payload, s.payload);
}

TEST(Checkpoint, TruncatedFilesAreRefused) {
    const std::string bytes = encode_checkpoint(sample_state());
    for (size_t n : {size_t(0), size_t(4), size_t(12), size_t(40), bytes.size() / 2, bytes.size() - 1}) {
        const std::string e = error_of(bytes.substr(0, n));
        EXPECT_FALSE(e.empty()) << n;
    }
    EXPECT_NE(error_of(bytes.substr(0, bytes.size() / 2)).find("checksum"), std::string::npos);
}

TEST(Checkpoint, EveryFlippedByteIsDetected) {
    const std::string bytes = encode_checkpoint(sample_state());
    for (size_t i = 0; i < bytes.size(); i += 7) {
        std::string b = bytes;
        b[i] = char(b[i] ^ 0x10);
        EXPECT_FALSE(error_of(b).empty()) << "byte " << i;
    }
}

TEST(Checkpoint, ForeignFileAndOtherVersion) {
    EXPECT_NE(error_of("P6\n2 2\n255\nabcdefghijkl").find("not a phos checkpoint"), std::string::npos);
    std::string b = encode_checkpoint(sample_state());
    b[8] = char(99);  // version field
    EXPECT_NE(error_of(b).find("version 99"), std::string::npos);
    b[8] = char(3);  // the previous format (no film) is refused by version, not misread
    EXPECT_NE(error_of(b).find("format version 3 is not supported (this phos reads version 4)"),
              std::string::npos)
        << error_of(b);
    EXPECT_THROW(load_checkpoint("/nonexistent/dir/x.ckpt"), InputError);
}

TEST(Checkpoint, OtherRenderIsRefused) {
    const ProgressiveState s = sample_state();
    EXPECT_NO_THROW(check_resumable(s, s, "f"));
    auto expect_refused = [&](ProgressiveState other, const char* word) {
        try {
            check_resumable(s, other, "f");
            ADD_FAILURE() << word;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
        }
    };
    ProgressiveState o = s;
    o.scene_hash ^= 1;
    expect_refused(o, "scene file contents differ");
    o = s;
    o.options[0].second = "0.5";
    expect_refused(o, "option --alpha differs: checkpoint 0.7, now 0.5");
    o = s;
    o.options.emplace_back("--photons-per-iter", "1000");
    expect_refused(o, "option --photons-per-iter differs: checkpoint not recorded, now 1000");
    o = s;
    o.options.pop_back();
    expect_refused(o, "option --dof differs: checkpoint , now not an option");
    // An identity given by hash alone (no list) is compared by hash.
    o = s;
    o.options.clear();
    o.options_hash ^= 1;
    expect_refused(o, "render options differ");
    o.options_hash = s.options_hash;
    EXPECT_NO_THROW(check_resumable(s, o, "f"));
    o = s;
    o.seed = 7;
    expect_refused(o, "seed differs: checkpoint 42, now 7");
    o = s;
    o.width = 6;
    expect_refused(o, "image size differs: checkpoint 5x3, now 6x3");
    o = s;
    o.integrator = "ppm";
    expect_refused(o, "integrator differs: checkpoint sppm, now ppm");
    o = s;
    o.slots_per_pixel = 1;
    expect_refused(o, "hit points per pixel differ: checkpoint 2, now 1");
}

TEST(Checkpoint, EveryDifferenceIsNamedInOneMessage) {
    const ProgressiveState s = sample_state();
    ProgressiveState o = s;
    o.seed = 1;
    o.options[0].second = "0.5";
    o.options[1].second = "4";
    try {
        check_resumable(s, o, "run.ckpt");
        ADD_FAILURE();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "checkpoint 'run.ckpt' was made by a different render: seed differs: checkpoint 42, now 1; "
                  "option --alpha differs: checkpoint 0.7, now 0.5; option --max-depth differs: checkpoint "
                  "16, now 4; rerun with the same scene and options, or start afresh");
    }
}

TEST(Checkpoint, OptionsHashIsTheListsHash) {
    const OptionValues a = {{"--alpha", "0.7"}}, b = {{"--alpha", "0.5"}};
    EXPECT_NE(hash_options(a), hash_options(b));
    EXPECT_NE(hash_options(a), hash_options({}));
    const std::string listed = "--alpha=0.7\n";
    EXPECT_EQ(hash_options(a), hash_bytes(listed.data(), listed.size()));
}

}  // namespace
}  // namespace phos::render
