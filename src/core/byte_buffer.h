// Plain binary buffers for saved state (checkpoints): a writer that appends values and arrays of
// trivially copyable types to a string in the machine's byte order, and a reader that takes them
// back with bounds checks, so a truncated or forged buffer is an InputError, never a wild read.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/error.h"

namespace phos {

class ByteWriter {
public:
    explicit ByteWriter(std::string& out) : out_(out) {}
    template <class T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
    }
    // A u64 count, then the elements.
    template <class T>
    void put_vector(const std::vector<T>& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        put(uint64_t(v.size()));
        if (!v.empty()) out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }

private:
    std::string& out_;
};

class ByteReader {
public:
    // `what` names the buffer in errors ("checkpoint 'run.ckpt': photon maps").
    ByteReader(std::string_view bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}
    template <class T>
    T get() {
        static_assert(std::is_trivially_copyable_v<T>);
        if (bytes_.size() - pos_ < sizeof(T)) fail("truncated");
        T v;
        std::memcpy(&v, bytes_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    template <class T>
    std::vector<T> get_vector() {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto n = get<uint64_t>();
        if (n > (bytes_.size() - pos_) / sizeof(T)) fail("truncated");
        std::vector<T> v(static_cast<size_t>(n));
        if (n > 0) std::memcpy(v.data(), bytes_.data() + pos_, size_t(n) * sizeof(T));
        pos_ += size_t(n) * sizeof(T);
        return v;
    }
    bool at_end() const { return pos_ == bytes_.size(); }
    [[noreturn]] void fail(const std::string& why) const { throw InputError(what_ + ": " + why); }

private:
    std::string_view bytes_;
    std::string what_;
    size_t pos_ = 0;
};

}  // namespace phos
