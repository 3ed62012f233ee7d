// Reader and writer of the RGL `.bsdf` tensor files (rgl_bsdf_file.h): the container, the fields a
// measured BSDF needs, and every bound checked before it is used.
#include "io/bsdf/rgl_bsdf_file.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <vector>

#include "core/error.h"

namespace phos::io {

namespace {

constexpr char kMagic[12] = {'t', 'e', 'n', 's', 'o', 'r', '_', 'f', 'i', 'l', 'e', '\0'};
constexpr size_t kHeaderBytes = 12 + 2 + 4;
enum Dtype : uint8_t { kUInt8 = 1, kFloat32 = 10, kLastDtype = 11 };

size_t dtype_size(uint8_t t) {
    static constexpr size_t sizes[] = {0, 1, 1, 2, 2, 4, 4, 8, 8, 2, 4, 8};
    return t <= kLastDtype ? sizes[t] : 0;
}

const char* dtype_name(uint8_t t) {
    static constexpr const char* names[] = {"invalid", "uint8",  "int8",  "uint16",  "int16",   "uint32",
                                            "int32",   "uint64", "int64", "float16", "float32", "float64"};
    return t <= kLastDtype ? names[t] : "unknown";
}

struct Field {
    std::string name;
    uint8_t dtype = 0;
    uint64_t offset = 0;
    std::vector<uint64_t> shape;
    uint64_t bytes = 0;
};

// A field name as messages print it: printable ASCII, others as '?', at most 40 characters.
std::string printable(const std::string& s) {
    std::string out;
    for (char c : s.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
    if (s.size() > 40) out += "...";
    return out;
}

std::string shape_text(const std::vector<uint64_t>& shape) {
    std::string s = "[";
    for (size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
    return s + "]";
}

class Parser {
public:
    Parser(std::string_view bytes, const std::string& path) : b_(bytes), path_(path) {}

    [[noreturn]] void fail(const std::string& message) const { throw ParseError(path_, 0, 0, message); }

    uint64_t get(size_t width, const std::string& what) {
        if (b_.size() - pos_ < width)
            fail("the file is truncated (" + what + " at byte " + std::to_string(pos_) + ", file of " +
                 std::to_string(b_.size()) + " bytes)");
        uint64_t v = 0;
        for (size_t i = 0; i < width; ++i) v |= uint64_t(uint8_t(b_[pos_ + i])) << (8 * i);
        pos_ += width;
        return v;
    }

    std::map<std::string, Field> fields() {
        if (b_.size() < kHeaderBytes)
            fail("the file is truncated (" + std::to_string(b_.size()) +
                 " bytes; a tensor file's header alone is " + std::to_string(kHeaderBytes) + ")");
        if (std::memcmp(b_.data(), kMagic, sizeof kMagic) != 0)
            fail("not an RGL tensor file (it does not start with \"tensor_file\\0\")");
        pos_ = 12;
        const unsigned major = unsigned(get(1, "version")), minor = unsigned(get(1, "version"));
        if (major != 1 || minor != 0)
            fail("tensor file version " + std::to_string(major) + "." + std::to_string(minor) +
                 " (phos reads version 1.0)");
        const uint64_t count = get(4, "field count");
        // Each field's description takes at least 13 bytes.
        if (count > (b_.size() - pos_) / 13)
            fail("the file is truncated (its header announces " + std::to_string(count) + " fields, which " +
                 std::to_string(b_.size() - pos_) + " bytes cannot describe)");
        std::map<std::string, Field> out;
        for (uint64_t k = 0; k < count; ++k) {
            const std::string which = "field " + std::to_string(k);
            Field f;
            const size_t name_length = size_t(get(2, which + "'s name length"));
            if (b_.size() - pos_ < name_length)
                fail("the file is truncated (" + which + "'s name at byte " + std::to_string(pos_) + ")");
            f.name.assign(b_.data() + pos_, name_length);
            pos_ += name_length;
            const std::string named = "field \"" + printable(f.name) + "\"";
            const size_t rank = size_t(get(2, named + "'s rank"));
            f.dtype = uint8_t(get(1, named + "'s dtype"));
            f.offset = get(8, named + "'s offset");
            if (rank > (b_.size() - pos_) / 8)
                fail("the file is truncated (" + named + " has rank " + std::to_string(rank) + ", at byte " +
                     std::to_string(pos_) + ")");
            for (size_t d = 0; d < rank; ++d) f.shape.push_back(get(8, named + "'s shape"));
            if (dtype_size(f.dtype) == 0)
                fail(named + " has an unknown dtype (" + std::to_string(f.dtype) + ")");
            // Its byte size, checked against the file as it is multiplied (no overflow: each factor
            // is at most the file's size once the product so far is not 0).
            uint64_t bytes = dtype_size(f.dtype);
            for (uint64_t dim : f.shape) {
                if (dim != 0 && bytes > uint64_t(b_.size()) / dim)
                    fail(named + " of shape " + shape_text(f.shape) + " (" + dtype_name(f.dtype) +
                         ") holds more bytes than the file (" + std::to_string(b_.size()) + ")");
                bytes *= dim;
            }
            if (f.shape.empty()) bytes = 0;
            f.bytes = bytes;
            if (f.offset > b_.size() || bytes > b_.size() - f.offset)
                fail(named + " (" + std::to_string(bytes) + " bytes at offset " + std::to_string(f.offset) +
                     ") lies beyond the end of the file (" + std::to_string(b_.size()) + " bytes)");
            if (out.count(f.name)) fail("two fields are named \"" + printable(f.name) + "\"");
            out.emplace(f.name, std::move(f));
        }
        // Data lies after the field table and no two fields share bytes.
        const uint64_t table_end = pos_;
        std::vector<const Field*> sorted;
        for (const auto& [name, f] : out)
            if (f.bytes > 0) sorted.push_back(&f);
        std::sort(sorted.begin(), sorted.end(),
                  [](const Field* a, const Field* b) { return a->offset < b->offset; });
        for (size_t i = 0; i < sorted.size(); ++i) {
            const Field& f = *sorted[i];
            if (f.offset < table_end)
                fail("field \"" + printable(f.name) + "\"'s data (offset " + std::to_string(f.offset) +
                     ") overlaps the field table (which ends at byte " + std::to_string(table_end) + ")");
            if (i + 1 < sorted.size() && f.offset + f.bytes > sorted[i + 1]->offset)
                fail("fields \"" + printable(f.name) + "\" and \"" + printable(sorted[i + 1]->name) +
                     "\" overlap in the file (offsets " + std::to_string(f.offset) + " and " +
                     std::to_string(sorted[i + 1]->offset) + ")");
        }
        return out;
    }

    std::vector<float> floats(const Field& f) const {
        std::vector<float> v(size_t(f.bytes / 4));
        const char* p = b_.data() + f.offset;
        for (size_t i = 0; i < v.size(); ++i) {
            uint32_t bits = 0;
            for (int k = 0; k < 4; ++k) bits |= uint32_t(uint8_t(p[4 * i + size_t(k)])) << (8 * k);
            v[i] = std::bit_cast<float>(bits);
        }
        return v;
    }
    std::string text(const Field& f) const {
        return std::string(b_.substr(size_t(f.offset), size_t(f.bytes)));
    }

private:
    std::string_view b_;
    const std::string& path_;
    size_t pos_ = 0;
};

}  // namespace

scene::MeasuredBsdfTables parse_rgl_bsdf(std::string_view bytes, const std::string& path) {
    Parser p(bytes, path);
    const std::map<std::string, Field> fields = p.fields();

    // A field the measured BSDF needs: present, of its dtype and rank, no empty dimension, each
    // dimension an int.
    const auto need = [&](const std::string& name, uint8_t dtype, size_t rank) -> const Field& {
        const auto it = fields.find(name);
        if (it == fields.end()) p.fail("no field \"" + name + "\" (a measured BSDF file needs it)");
        const Field& f = it->second;
        if (f.dtype != dtype)
            p.fail("field \"" + name + "\" is " + dtype_name(f.dtype) + ", not " + dtype_name(dtype));
        if (f.shape.size() != rank)
            p.fail("field \"" + name + "\" has rank " + std::to_string(f.shape.size()) + " (shape " +
                   shape_text(f.shape) + "), not " + std::to_string(rank));
        for (uint64_t d : f.shape)
            if (d == 0 || d > uint64_t(std::numeric_limits<int>::max()))
                p.fail("field \"" + name + "\" has shape " + shape_text(f.shape) + ": a dimension is " +
                       (d == 0 ? "empty" : "too large"));
        return f;
    };
    const Field& description = need("description", kUInt8, 1);
    const Field& jacobian = need("jacobian", kUInt8, 1);
    const Field& theta_i = need("theta_i", kFloat32, 1);
    const Field& phi_i = need("phi_i", kFloat32, 1);
    const Field& ndf = need("ndf", kFloat32, 2);
    const Field& sigma = need("sigma", kFloat32, 2);
    const Field& vndf = need("vndf", kFloat32, 4);
    const Field& luminance = need("luminance", kFloat32, 4);
    const bool spectral = fields.count("spectra") != 0;
    const Field& spectra = spectral ? need("spectra", kFloat32, 5) : need("rgb", kFloat32, 5);
    const Field* wavelengths = spectral ? &need("wavelengths", kFloat32, 1) : nullptr;

    if (jacobian.shape[0] != 1)
        p.fail("field \"jacobian\" has shape " + shape_text(jacobian.shape) + ", not [1]");
    const uint64_t n_phi = phi_i.shape[0], n_theta = theta_i.shape[0];
    const auto conditioned = [&](const Field& f) {
        if (f.shape[0] != n_phi || f.shape[1] != n_theta)
            p.fail("field \"" + f.name + "\" has shape " + shape_text(f.shape) +
                   ": its first two dimensions must be phi_i's " + std::to_string(n_phi) + " and theta_i's " +
                   std::to_string(n_theta));
    };
    conditioned(vndf);
    conditioned(luminance);
    conditioned(spectra);
    if (luminance.shape[2] != luminance.shape[3])
        p.fail("field \"luminance\" has shape " + shape_text(luminance.shape) + ": its grid must be square");
    if (spectra.shape[3] != luminance.shape[2] || spectra.shape[4] != luminance.shape[3])
        p.fail("field \"" + spectra.name + "\" has shape " + shape_text(spectra.shape) +
               ": its grid must be luminance's (" + std::to_string(luminance.shape[2]) + " x " +
               std::to_string(luminance.shape[3]) + ")");
    const uint64_t channels = spectral ? wavelengths->shape[0] : 3;
    if (spectra.shape[2] != channels)
        p.fail(
            "field \"" + spectra.name + "\" has shape " + shape_text(spectra.shape) +
            ": its third dimension must be " +
            (spectral ? "the number of wavelengths (" + std::to_string(channels) + ")" : std::string("3")));

    scene::MeasuredBsdfTables t;
    t.description = p.text(description);
    while (!t.description.empty() && t.description.back() == '\0') t.description.pop_back();
    t.jacobian = p.text(jacobian)[0] != 0;
    t.theta_i = p.floats(theta_i);
    t.phi_i = p.floats(phi_i);
    if (wavelengths) t.wavelengths = p.floats(*wavelengths);
    t.ndf_ny = int(ndf.shape[0]);
    t.ndf_nx = int(ndf.shape[1]);
    t.ndf = p.floats(ndf);
    t.sigma_ny = int(sigma.shape[0]);
    t.sigma_nx = int(sigma.shape[1]);
    t.sigma = p.floats(sigma);
    t.vndf_ny = int(vndf.shape[2]);
    t.vndf_nx = int(vndf.shape[3]);
    t.vndf = p.floats(vndf);
    t.n = int(luminance.shape[2]);
    t.luminance = p.floats(luminance);
    (spectral ? t.spectra : t.rgb) = p.floats(spectra);
    if (const std::string e = t.check(); !e.empty()) p.fail(e);
    return t;
}

std::shared_ptr<const scene::MeasuredBsdf> read_rgl_bsdf(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ParseError(path, 0, 0, "cannot open the measured BSDF file");
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw ParseError(path, 0, 0, "cannot read the measured BSDF file");
    return std::make_shared<const scene::MeasuredBsdf>(parse_rgl_bsdf(bytes, path));
}

namespace {

struct OutField {
    std::string name;
    uint8_t dtype;
    std::vector<uint64_t> shape;
    std::string data;
};

void put(std::string& s, uint64_t v, size_t width) {
    for (size_t i = 0; i < width; ++i) s += char(uint8_t(v >> (8 * i)));
}

std::string float_bytes(const std::vector<float>& v) {
    std::string s;
    s.reserve(v.size() * 4);
    for (float x : v) put(s, std::bit_cast<uint32_t>(x), 4);
    return s;
}

}  // namespace

std::string rgl_bsdf_bytes(const scene::MeasuredBsdfTables& t) {
    const uint64_t n_phi = t.phi_i.size(), n_theta = t.theta_i.size(), n = uint64_t(t.n);
    std::vector<OutField> f;
    f.push_back({"description", kUInt8, {t.description.size() + 1}, t.description + '\0'});
    f.push_back({"jacobian", kUInt8, {1}, std::string(1, char(t.jacobian ? 1 : 0))});
    f.push_back({"theta_i", kFloat32, {n_theta}, float_bytes(t.theta_i)});
    f.push_back({"phi_i", kFloat32, {n_phi}, float_bytes(t.phi_i)});
    f.push_back({"ndf", kFloat32, {uint64_t(t.ndf_ny), uint64_t(t.ndf_nx)}, float_bytes(t.ndf)});
    f.push_back({"sigma", kFloat32, {uint64_t(t.sigma_ny), uint64_t(t.sigma_nx)}, float_bytes(t.sigma)});
    f.push_back(
        {"vndf", kFloat32, {n_phi, n_theta, uint64_t(t.vndf_ny), uint64_t(t.vndf_nx)}, float_bytes(t.vndf)});
    f.push_back({"luminance", kFloat32, {n_phi, n_theta, n, n}, float_bytes(t.luminance)});
    if (t.spectral()) {
        f.push_back({"wavelengths", kFloat32, {t.wavelengths.size()}, float_bytes(t.wavelengths)});
        f.push_back(
            {"spectra", kFloat32, {n_phi, n_theta, t.wavelengths.size(), n, n}, float_bytes(t.spectra)});
    }
    if (!t.rgb.empty()) f.push_back({"rgb", kFloat32, {n_phi, n_theta, 3, n, n}, float_bytes(t.rgb)});

    uint64_t offset = kHeaderBytes;
    for (const OutField& x : f) offset += 2 + x.name.size() + 2 + 1 + 8 + 8 * x.shape.size();
    std::vector<uint64_t> offsets;
    for (const OutField& x : f) {
        offset = (offset + 7) / 8 * 8;
        offsets.push_back(offset);
        offset += x.data.size();
    }
    std::string s(kMagic, sizeof kMagic);
    put(s, 1, 1);
    put(s, 0, 1);
    put(s, f.size(), 4);
    for (size_t i = 0; i < f.size(); ++i) {
        put(s, f[i].name.size(), 2);
        s += f[i].name;
        put(s, f[i].shape.size(), 2);
        put(s, f[i].dtype, 1);
        put(s, offsets[i], 8);
        for (uint64_t d : f[i].shape) put(s, d, 8);
    }
    for (size_t i = 0; i < f.size(); ++i) {
        s.resize(size_t(offsets[i]), '\0');
        s += f[i].data;
    }
    return s;
}

void write_rgl_bsdf(const std::string& path, const scene::MeasuredBsdfTables& tables) {
    const std::string bytes = rgl_bsdf_bytes(tables);
    std::ofstream out(path, std::ios::binary);
    if (!out) throw InputError("cannot write measured BSDF file '" + path + "'");
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out) throw InputError("cannot write measured BSDF file '" + path + "'");
}

}  // namespace phos::io
