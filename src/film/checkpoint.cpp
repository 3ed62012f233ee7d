// Binary checkpoint format (see checkpoint.h). Layout, little-endian as the machine stores it:
//   "PHOSCKPT" | u32 version | u32 integrator-name length | name bytes | u32 width, height,
//   slots_per_pixel | u64 seed, scene_hash, options_hash, iterations, photons_emitted,
//   target_iterations | u32 argument count, then per argument u32 length + bytes | u64 slot count |
//   slot count x SlotStats (8 doubles) | u64 checksum of all
//   preceding bytes.
#include "film/checkpoint.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "io/image/atomic_write.h"

namespace phos::film {
namespace {

constexpr char kMagic[8] = {'P', 'H', 'O', 'S', 'C', 'K', 'P', 'T'};
static_assert(sizeof(SlotStats) == 8 * sizeof(double));

template <class T>
void put(std::string& out, const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof(T));
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
        std::memcpy(dst, bytes_.data() + pos_, n);
        pos_ += n;
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

std::string encode_checkpoint(const ProgressiveState& s) {
    std::string out;
    out.reserve(128 + s.slots.size() * sizeof(SlotStats));
    out.append(kMagic, sizeof(kMagic));
    put(out, ProgressiveState::kVersion);
    put(out, uint32_t(s.integrator.size()));
    out.append(s.integrator);
    put(out, s.width);
    put(out, s.height);
    put(out, s.slots_per_pixel);
    for (uint64_t v :
         {s.seed, s.scene_hash, s.options_hash, s.iterations, s.photons_emitted, s.target_iterations})
        put(out, v);
    put(out, uint32_t(s.command_line.size()));
    for (const std::string& a : s.command_line) {
        put(out, uint32_t(a.size()));
        out.append(a);
    }
    put(out, uint64_t(s.slots.size()));
    out.append(reinterpret_cast<const char*>(s.slots.data()), s.slots.size() * sizeof(SlotStats));
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
    const auto argc = r.get<uint32_t>();
    if (argc > 4096) r.fail("bad argument count");
    for (uint32_t i = 0; i < argc; ++i) {
        const auto len = r.get<uint32_t>();
        if (len > r.remaining()) r.fail("file is truncated");
        std::string a(len, '\0');
        r.get_bytes(a.data(), len);
        s.command_line.push_back(std::move(a));
    }
    const auto count = r.get<uint64_t>();
    if (count != uint64_t(s.width) * s.height * s.slots_per_pixel)
        r.fail("slot count does not match the image size");
    if (r.remaining() != count * sizeof(SlotStats) + sizeof(uint64_t))
        r.fail("file size does not match its header");
    s.slots.resize(count);
    r.get_bytes(s.slots.data(), count * sizeof(SlotStats));
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
    std::string diff;
    auto note = [&](bool differs, const std::string& what) {
        if (differs) diff += (diff.empty() ? "" : ", ") + what;
    };
    note(saved.integrator != expected.integrator,
         "integrator (" + saved.integrator + " in the checkpoint, " + expected.integrator + " now)");
    note(saved.width != expected.width || saved.height != expected.height,
         "image size (" + std::to_string(saved.width) + "x" + std::to_string(saved.height) +
             " in the checkpoint)");
    note(saved.slots_per_pixel != expected.slots_per_pixel, "hit points per pixel");
    note(saved.seed != expected.seed, "seed (" + std::to_string(saved.seed) + " in the checkpoint)");
    note(saved.scene_hash != expected.scene_hash, "scene file contents");
    note(saved.options_hash != expected.options_hash, "render options");
    if (!diff.empty())
        throw InputError("checkpoint '" + path + "' was made by a different render: " + diff +
                         " differ; rerun with the same scene and options, or start afresh");
}

}  // namespace phos::film
