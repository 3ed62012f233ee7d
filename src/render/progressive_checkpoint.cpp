// Binary checkpoint format (see progressive_checkpoint.h). Layout, little-endian as the machine
// stores it (version 4):
//   "PHOSCKPT" | u32 version | u32 integrator-name length | name bytes | u32 width, height,
//   slots_per_pixel | u64 seed, scene_hash, options_hash, iterations, photons_emitted,
//   target_iterations, rejected_samples | u32 option count, then per option a string flag and a
//   string value | u32 argument count, then per argument a string | u64 slot count | slot count x
//   PixelStats (8 doubles) | u32 tile count | tile count x u32 samples | u32 layer count, then per
//   layer a string name and width x height x 4 doubles | u64 payload length | payload bytes (the
//   integrator's own data: the photon mapper's maps) | u64 checksum of all preceding bytes. A
//   string is u32 length + bytes. Version 3 had no film (ppm / sppm only); older files are refused
//   by version.
#include "render/progressive_checkpoint.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "io/image/atomic_write.h"

namespace phos::render {
namespace {

constexpr char kMagic[8] = {'P', 'H', 'O', 'S', 'C', 'K', 'P', 'T'};
static_assert(sizeof(PixelStats) == 8 * sizeof(double));

template <class T>
void put(std::string& out, const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

void put_string(std::string& out, const std::string& s) {
    put(out, uint32_t(s.size()));
    out.append(s);
}

class Reader {
public:
    Reader(const std::string& bytes, const std::string& what) : bytes_(bytes), what_(what) {}
    template <class T>
    T get() {
        T v;
        need(sizeof(T));
        std::memcpy(&v, bytes_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    void get_bytes(void* dst, size_t n) {
        need(n);
        // An empty vector's data() may be null, and memcpy from or to null is undefined even for 0 bytes.
        if (n > 0) std::memcpy(dst, bytes_.data() + pos_, n);
        pos_ += n;
    }
    std::string get_string() {
        const auto len = get<uint32_t>();
        if (len > remaining()) fail("file is truncated");
        std::string s(len, '\0');
        get_bytes(s.data(), len);
        return s;
    }
    size_t pos() const { return pos_; }
    size_t remaining() const { return bytes_.size() - pos_; }
    [[noreturn]] void fail(const std::string& why) const {
        throw InputError("checkpoint " + what_ + ": " + why);
    }

private:
    void need(size_t n) const {
        if (bytes_.size() - pos_ < n) fail("file is truncated (" + std::to_string(bytes_.size()) + " bytes)");
    }
    const std::string& bytes_;
    std::string what_;
    size_t pos_ = 0;
};

}  // namespace

uint64_t hash_bytes(const void* data, size_t size, uint64_t seed) {
    const auto* p = static_cast<const unsigned char*>(data);
    uint64_t h = 0xcbf29ce484222325ULL ^ (seed * 0x9e3779b97f4a7c15ULL);
    for (size_t i = 0; i < size; ++i) h = (h ^ p[i]) * 0x100000001b3ULL;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    return h;
}

uint64_t hash_options(const OptionValues& options) {
    std::string listed;
    for (const auto& [flag, value] : options) listed += flag + "=" + value + "\n";
    return hash_bytes(listed.data(), listed.size());
}

std::string encode_checkpoint(const ProgressiveState& s) {
    std::string out;
    out.reserve(128 + s.slots.size() * sizeof(PixelStats));
    out.append(kMagic, sizeof(kMagic));
    put(out, ProgressiveState::kVersion);
    put(out, uint32_t(s.integrator.size()));
    out.append(s.integrator);
    put(out, s.width);
    put(out, s.height);
    put(out, s.slots_per_pixel);
    for (uint64_t v : {s.seed, s.scene_hash, s.options_hash, s.iterations, s.photons_emitted,
                       s.target_iterations, s.rejected_samples})
        put(out, v);
    put(out, uint32_t(s.options.size()));
    for (const auto& [flag, value] : s.options) {
        put_string(out, flag);
        put_string(out, value);
    }
    put(out, uint32_t(s.command_line.size()));
    for (const std::string& a : s.command_line) put_string(out, a);
    put(out, uint64_t(s.slots.size()));
    out.append(reinterpret_cast<const char*>(s.slots.data()), s.slots.size() * sizeof(PixelStats));
    put(out, uint32_t(s.tile_samples.size()));
    out.append(reinterpret_cast<const char*>(s.tile_samples.data()),
               s.tile_samples.size() * sizeof(uint32_t));
    put(out, uint32_t(s.film.size()));
    for (const auto& [name, sums] : s.film) {
        put_string(out, name);
        out.append(reinterpret_cast<const char*>(sums.data()), sums.size() * sizeof(double));
    }
    put(out, uint64_t(s.payload.size()));
    out.append(s.payload);
    put(out, hash_bytes(out.data(), out.size()));
    return out;
}

ProgressiveState decode_checkpoint(const std::string& bytes, const std::string& what) {
    Reader r(bytes, what);
    char magic[8];
    if (bytes.size() < sizeof(magic) || std::memcmp(bytes.data(), kMagic, sizeof(magic)) != 0)
        r.fail("not a phos checkpoint file");
    r.get_bytes(magic, sizeof(magic));
    const auto version = r.get<uint32_t>();
    if (version != ProgressiveState::kVersion)
        r.fail("format version " + std::to_string(version) + " is not supported (this phos reads version " +
               std::to_string(ProgressiveState::kVersion) + ")");
    // Verify the checksum before trusting any size field.
    if (bytes.size() < sizeof(magic) + sizeof(uint32_t) + sizeof(uint64_t)) r.fail("file is truncated");
    uint64_t stored;
    std::memcpy(&stored, bytes.data() + bytes.size() - sizeof(uint64_t), sizeof(uint64_t));
    if (stored != hash_bytes(bytes.data(), bytes.size() - sizeof(uint64_t)))
        r.fail("checksum mismatch: the file is corrupt or truncated");

    ProgressiveState s;
    const auto name_len = r.get<uint32_t>();
    if (name_len > 64) r.fail("bad integrator name length");
    s.integrator.resize(name_len);
    r.get_bytes(s.integrator.data(), name_len);
    s.width = r.get<uint32_t>();
    s.height = r.get<uint32_t>();
    s.slots_per_pixel = r.get<uint32_t>();
    s.seed = r.get<uint64_t>();
    s.scene_hash = r.get<uint64_t>();
    s.options_hash = r.get<uint64_t>();
    s.iterations = r.get<uint64_t>();
    s.photons_emitted = r.get<uint64_t>();
    s.target_iterations = r.get<uint64_t>();
    s.rejected_samples = r.get<uint64_t>();
    const auto optc = r.get<uint32_t>();
    if (optc > 4096) r.fail("bad option count");
    for (uint32_t i = 0; i < optc; ++i) {
        std::string flag = r.get_string();
        s.options.emplace_back(std::move(flag), r.get_string());
    }
    const auto argc = r.get<uint32_t>();
    if (argc > 4096) r.fail("bad argument count");
    for (uint32_t i = 0; i < argc; ++i) s.command_line.push_back(r.get_string());
    const auto count = r.get<uint64_t>();
    // width x height fits 64 bits; times the slots per pixel, or times 4 film values, it may not: a
    // product that wraps around would let a forged header claim a huge image backed by no data.
    const uint64_t pixels = uint64_t(s.width) * s.height;
    uint64_t slot_count = 0, values = 0;
    if (__builtin_mul_overflow(pixels, uint64_t(s.slots_per_pixel), &slot_count) ||
        __builtin_mul_overflow(pixels, uint64_t(4), &values))
        r.fail("image size is too large");
    if (count != slot_count) r.fail("slot count does not match the image size");
    if (count > r.remaining() / sizeof(PixelStats)) r.fail("file size does not match its header");
    s.slots.resize(count);
    r.get_bytes(s.slots.data(), count * sizeof(PixelStats));
    const auto tiles = r.get<uint32_t>();
    if (tiles > r.remaining() / sizeof(uint32_t)) r.fail("file size does not match its header");
    s.tile_samples.resize(tiles);
    r.get_bytes(s.tile_samples.data(), tiles * sizeof(uint32_t));
    const auto layers = r.get<uint32_t>();
    if (layers > 64) r.fail("bad layer count");
    for (uint32_t i = 0; i < layers; ++i) {
        std::string name = r.get_string();
        if (values > r.remaining() / sizeof(double)) r.fail("file size does not match its header");
        std::vector<double> sums(values);
        r.get_bytes(sums.data(), values * sizeof(double));
        s.film.emplace_back(std::move(name), std::move(sums));
    }
    const auto payload = r.get<uint64_t>();
    if (payload > r.remaining()) r.fail("file size does not match its header");
    s.payload.resize(size_t(payload));
    r.get_bytes(s.payload.data(), size_t(payload));
    if (r.remaining() != sizeof(uint64_t)) r.fail("file size does not match its header");
    return s;
}

void save_checkpoint(const std::string& path, const ProgressiveState& state) {
    const std::string bytes = encode_checkpoint(state);
    io::atomic_write(path, [&](const std::string& temp) {
        std::ofstream f(temp, std::ios::binary);
        f.write(bytes.data(), std::streamsize(bytes.size()));
        if (!f) throw InputError("write failed");
    });
}

ProgressiveState load_checkpoint(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw InputError("checkpoint '" + path + "': cannot open file");
    const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    return decode_checkpoint(bytes, "'" + path + "'");
}

void check_resumable(const ProgressiveState& saved, const ProgressiveState& expected,
                     const std::string& path) {
    std::vector<std::string> diff;
    auto differs = [&](const std::string& what, const std::string& then, const std::string& now) {
        if (then != now) diff.push_back(what + ": checkpoint " + then + ", now " + now);
    };
    auto size = [](const ProgressiveState& s) {
        return std::to_string(s.width) + "x" + std::to_string(s.height);
    };
    differs("integrator differs", saved.integrator, expected.integrator);
    differs("image size differs", size(saved), size(expected));
    differs("hit points per pixel differ", std::to_string(saved.slots_per_pixel),
            std::to_string(expected.slots_per_pixel));
    differs("seed differs", std::to_string(saved.seed), std::to_string(expected.seed));
    if (saved.scene_hash != expected.scene_hash) diff.push_back("scene file contents differ");
    if (saved.options.empty() || expected.options.empty()) {
        // A side without the list (an identity given by hash alone): the hash decides.
        if (saved.options_hash != expected.options_hash) diff.push_back("render options differ");
    } else {
        auto find = [](const OptionValues& list, const std::string& flag) -> const std::string* {
            for (const auto& [f, v] : list)
                if (f == flag) return &v;
            return nullptr;
        };
        for (const auto& [flag, value] : expected.options) {
            const std::string* then = find(saved.options, flag);
            differs("option " + flag + " differs", then ? *then : "not recorded", value);
        }
        for (const auto& [flag, value] : saved.options)
            if (!find(expected.options, flag)) differs("option " + flag + " differs", value, "not an option");
    }
    if (diff.empty()) return;
    std::string listed;
    for (const std::string& d : diff) listed += (listed.empty() ? "" : "; ") + d;
    throw InputError("checkpoint '" + path + "' was made by a different render: " + listed +
                     "; rerun with the same scene and options, or start afresh");
}

}  // namespace phos::render
