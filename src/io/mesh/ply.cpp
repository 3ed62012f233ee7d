// PLY triangle-mesh reader (ASCII and binary little/big endian) and writer. Only the vertex
// positions, normals and texture coordinates and the face index lists are used; every other
// element and property is parsed (so binary offsets stay right) and discarded.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/gzip/gzip_file.h"
#include "io/mesh/mesh_io.h"

namespace phos::io {
namespace {

enum class Format { Ascii, BinaryLE, BinaryBE };
enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64, None };

int type_size(Type t) {
    switch (t) {
        case Type::Int8:
        case Type::UInt8:
            return 1;
        case Type::Int16:
        case Type::UInt16:
            return 2;
        case Type::Int32:
        case Type::UInt32:
        case Type::Float32:
            return 4;
        case Type::Float64:
            return 8;
        case Type::None:
            return 0;
    }
    return 0;
}

Type parse_type(const std::string& s) {
    if (s == "char" || s == "int8") return Type::Int8;
    if (s == "uchar" || s == "uint8") return Type::UInt8;
    if (s == "short" || s == "int16") return Type::Int16;
    if (s == "ushort" || s == "uint16") return Type::UInt16;
    if (s == "int" || s == "int32") return Type::Int32;
    if (s == "uint" || s == "uint32") return Type::UInt32;
    if (s == "float" || s == "float32") return Type::Float32;
    if (s == "double" || s == "float64") return Type::Float64;
    return Type::None;
}

bool is_integer(Type t) { return t != Type::Float32 && t != Type::Float64; }

// Whether `v` (already known to be a whole number for integer types) fits the declared type.
bool in_range(Type t, double v) {
    switch (t) {
        case Type::Int8:
            return v >= -128 && v <= 127;
        case Type::UInt8:
            return v >= 0 && v <= 255;
        case Type::Int16:
            return v >= -32768 && v <= 32767;
        case Type::UInt16:
            return v >= 0 && v <= 65535;
        case Type::Int32:
            return v >= -2147483648.0 && v <= 2147483647.0;
        case Type::UInt32:
            return v >= 0 && v <= 4294967295.0;
        default:
            return true;
    }
}

// What a vertex property means to us.
enum class Role { None, X, Y, Z, NX, NY, NZ, U, V, FaceIndices };

struct Property {
    std::string name;
    Type type = Type::None;
    Type count_type = Type::None;  // != None: a list property
    Role role = Role::None;
};

struct Element {
    std::string name;
    size_t count = 0;
    std::vector<Property> props;
    int header_line = 0;
};

Role vertex_role(const std::string& n) {
    if (n == "x") return Role::X;
    if (n == "y") return Role::Y;
    if (n == "z") return Role::Z;
    if (n == "nx") return Role::NX;
    if (n == "ny") return Role::NY;
    if (n == "nz") return Role::NZ;
    if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s") return Role::U;
    if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t") return Role::V;
    return Role::None;
}

// Sequential reader of property values from the body, ASCII or binary, that knows where it is
// (line for ASCII, byte offset for binary) so errors can say so.
class BodyReader {
public:
    BodyReader(std::istream& in, Format f, const std::string& path, int line)
        : in_(in), format_(f), path_(path), line_(line) {
        offset_ = size_t(in_.tellg());
    }

    [[noreturn]] void fail(const std::string& msg) const {
        if (format_ == Format::Ascii) throw ParseError(path_, line_, col_, msg);
        throw ParseError(path_, 0, 0, "at byte offset " + std::to_string(offset_) + ": " + msg);
    }
    // Like fail(), but pointing at the value just read (a bad index rather than a missing one).
    [[noreturn]] void fail_last(const std::string& msg, int bytes) {
        if (format_ == Format::Ascii) throw ParseError(path_, line_, token_col_, msg);
        offset_ -= size_t(bytes);
        throw ParseError(path_, 0, 0, "at byte offset " + std::to_string(offset_) + ": " + msg);
    }

    double read(Type t) { return format_ == Format::Ascii ? read_ascii(t) : read_binary(t); }

    // Called at the end of each element instance in ASCII: the rest of the line must be empty.
    void end_record() {
        if (format_ != Format::Ascii) return;
        int c;
        while ((c = in_.peek()) == ' ' || c == '\t' || c == '\r') in_.get(), ++col_;
        if (c == '\n') {
            in_.get();
            ++line_;
            col_ = 1;
        } else if (c != EOF) {
            fail("extra values at the end of an element line");
        }
    }

private:
    double read_ascii(Type t) {
        // Skip blanks (and empty lines) to the next token.
        int c;
        for (;;) {
            c = in_.peek();
            if (c == ' ' || c == '\t' || c == '\r') {
                in_.get();
                ++col_;
            } else if (c == '\n' && !in_line_) {
                in_.get();
                ++line_;
                col_ = 1;
            } else {
                break;
            }
        }
        if (c == EOF) fail("unexpected end of file (fewer elements than the header declares)");
        if (c == '\n') fail("too few values on this line");
        std::string tok;
        const int start = col_;
        while ((c = in_.peek()) != EOF && c != ' ' && c != '\t' && c != '\r' && c != '\n') {
            tok.push_back(char(in_.get()));
            ++col_;
        }
        in_line_ = true;
        token_col_ = start;
        const char* b = tok.c_str();
        char* e = nullptr;
        const double v = std::strtod(b, &e);
        if (e == b || *e != '\0' || !std::isfinite(v)) {
            col_ = start;
            fail("malformed number '" + tok + "'");
        }
        if (is_integer(t) && v != std::floor(v)) {
            col_ = start;
            fail("expected an integer, got '" + tok + "'");
        }
        if (!in_range(t, v)) {
            col_ = start;
            fail("'" + tok + "' is out of range for its property type");
        }
        return v;
    }

    double read_binary(Type t) {
        unsigned char buf[8];
        const int n = type_size(t);
        in_.read(reinterpret_cast<char*>(buf), n);
        if (in_.gcount() != n) fail("unexpected end of file (fewer elements than the header declares)");
        const bool swap = (format_ == Format::BinaryBE) != (std::endian::native == std::endian::big);
        if (swap)
            for (int i = 0; i < n / 2; ++i) std::swap(buf[i], buf[n - 1 - i]);
        offset_ += size_t(n);
        switch (t) {
            case Type::Int8:
                return double(int8_t(buf[0]));
            case Type::UInt8:
                return double(buf[0]);
            case Type::Int16: {
                int16_t v;
                std::memcpy(&v, buf, 2);
                return v;
            }
            case Type::UInt16: {
                uint16_t v;
                std::memcpy(&v, buf, 2);
                return v;
            }
            case Type::Int32: {
                int32_t v;
                std::memcpy(&v, buf, 4);
                return v;
            }
            case Type::UInt32: {
                uint32_t v;
                std::memcpy(&v, buf, 4);
                return v;
            }
            case Type::Float32: {
                float v;
                std::memcpy(&v, buf, 4);
                if (!std::isfinite(v)) {
                    offset_ -= 4;
                    fail("non-finite value");
                }
                return v;
            }
            case Type::Float64: {
                double v;
                std::memcpy(&v, buf, 8);
                if (!std::isfinite(v)) {
                    offset_ -= 8;
                    fail("non-finite value");
                }
                return v;
            }
            case Type::None:
                break;
        }
        return 0;
    }

public:
    void begin_record() { in_line_ = false; }
    size_t offset() const { return offset_; }

private:
    std::istream& in_;
    Format format_;
    const std::string& path_;
    int line_ = 1;
    int col_ = 1;
    int token_col_ = 1;
    size_t offset_ = 0;
    bool in_line_ = false;
};

}  // namespace

scene::TriangleMesh read_ply(const std::string& path) {
    const std::unique_ptr<std::istream> stream = open_maybe_gzip(path);  // .ply or .ply.gz
    if (!stream) throw ParseError(path, 0, 0, "cannot open PLY file");
    std::istream& in = *stream;

    // ---- header ----
    std::string line;
    int line_no = 0;
    auto next_line = [&]() -> bool {
        if (!std::getline(in, line)) return false;
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        return true;
    };
    if (!next_line() || line != "ply") throw ParseError(path, 1, 1, "not a PLY file (missing 'ply' magic)");
    Format format = Format::Ascii;
    bool have_format = false;
    std::vector<Element> elements;
    for (;;) {
        if (!next_line()) throw ParseError(path, line_no, 1, "unexpected end of file in the PLY header");
        std::istringstream ls(line);
        std::string kw;
        ls >> kw;
        if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
        if (kw == "end_header") break;
        if (kw == "format") {
            std::string f, version;
            ls >> f >> version;
            if (f == "ascii")
                format = Format::Ascii;
            else if (f == "binary_little_endian")
                format = Format::BinaryLE;
            else if (f == "binary_big_endian")
                format = Format::BinaryBE;
            else
                throw ParseError(path, line_no, 8, "unknown PLY format '" + f + "'");
            have_format = true;
        } else if (kw == "element") {
            Element e;
            long long count = -1;
            ls >> e.name >> count;
            if (e.name.empty() || !ls || count < 0)
                throw ParseError(path, line_no, 1, "malformed element line (want: element NAME COUNT)");
            e.count = size_t(count);
            e.header_line = line_no;
            elements.push_back(std::move(e));
        } else if (kw == "property") {
            if (elements.empty()) throw ParseError(path, line_no, 1, "property before any element");
            Property p;
            std::string t;
            ls >> t;
            if (t == "list") {
                std::string ct, it;
                ls >> ct >> it >> p.name;
                p.count_type = parse_type(ct);
                p.type = parse_type(it);
                if (p.count_type == Type::None || p.type == Type::None || p.name.empty())
                    throw ParseError(path, line_no, 1, "malformed list property: '" + line + "'");
                if (!is_integer(p.count_type))
                    throw ParseError(path, line_no, 1, "list count type must be an integer type");
            } else {
                p.type = parse_type(t);
                ls >> p.name;
                if (p.type == Type::None || p.name.empty())
                    throw ParseError(path, line_no, 1, "malformed property: '" + line + "'");
            }
            Element& e = elements.back();
            if (e.name == "vertex" && p.count_type == Type::None) p.role = vertex_role(p.name);
            if (e.name == "face" && p.count_type != Type::None &&
                (p.name == "vertex_indices" || p.name == "vertex_index")) {
                if (!is_integer(p.type)) throw ParseError(path, line_no, 1, "face indices must be integers");
                p.role = Role::FaceIndices;
            }
            e.props.push_back(std::move(p));
        } else {
            throw ParseError(path, line_no, 1, "unknown PLY header keyword '" + kw + "'");
        }
    }
    if (!have_format) throw ParseError(path, line_no, 1, "PLY header has no 'format' line");

    // ---- which attributes are present ----
    const Element* vertex_el = nullptr;
    for (const Element& e : elements)
        if (e.name == "vertex") vertex_el = &e;
    if (!vertex_el) throw ParseError(path, line_no, 1, "PLY file has no vertex element");
    int roles_present = 0;
    for (const Property& p : vertex_el->props) roles_present |= 1 << int(p.role);
    auto has = [&](Role r) { return (roles_present >> int(r)) & 1; };
    if (!has(Role::X) || !has(Role::Y) || !has(Role::Z))
        throw ParseError(path, vertex_el->header_line, 1, "vertex element lacks x, y or z");
    const bool normals = has(Role::NX) && has(Role::NY) && has(Role::NZ);
    const bool uvs = has(Role::U) && has(Role::V);

    // ---- body ----
    // Every element instance takes at least one byte per property (a character in ASCII; the value,
    // or a list's count, in binary), so a count the rest of the file cannot hold is a corrupt
    // header: refusing it here keeps it from reserving gigabytes or looping for ages.
    {
        in.clear();  // a header ending at the end of the file leaves eofbit set
        const std::streamoff body_start = in.tellg();
        in.seekg(0, std::ios::end);
        const std::streamoff file_end = in.tellg();
        in.seekg(body_start);
        if (body_start < 0 || file_end < body_start || !in)
            throw ParseError(path, line_no, 1, "cannot determine the size of the PLY body");
        uint64_t left = uint64_t(file_end - body_start);
        for (const Element& e : elements) {
            uint64_t per_instance = 0;
            for (const Property& p : e.props)
                per_instance += format == Format::Ascii
                                    ? 1
                                    : uint64_t(type_size(p.count_type != Type::None ? p.count_type : p.type));
            per_instance = std::max<uint64_t>(per_instance, 1);
            if (e.count > left / per_instance)
                throw ParseError(path, e.header_line, 1,
                                 "unexpected end of file: element '" + e.name + "' declares " +
                                     std::to_string(e.count) + " instances of at least " +
                                     std::to_string(per_instance) + " byte(s) each, but only " +
                                     std::to_string(left) + " bytes are left");
            left -= e.count * per_instance;
        }
    }
    scene::TriangleMesh mesh;
    BodyReader body(in, format, path, line_no + 1);
    std::vector<uint32_t> poly;
    for (const Element& e : elements) {
        const bool is_vertex = &e == vertex_el;
        if (is_vertex) {
            mesh.positions.reserve(e.count);
            if (normals) mesh.normals.reserve(e.count);
            if (uvs) mesh.uvs.reserve(e.count);
        }
        for (size_t i = 0; i < e.count; ++i) {
            body.begin_record();
            Vec3 p{0.0f}, n{0.0f};
            Vec2 uv;
            for (const Property& prop : e.props) {
                if (prop.count_type != Type::None) {
                    const double c = body.read(prop.count_type);
                    if (c < 0) body.fail("negative list length");
                    const size_t count = size_t(c);
                    if (prop.role == Role::FaceIndices) {
                        if (count < 3) body.fail("face with fewer than 3 vertices");
                        poly.clear();
                        for (size_t k = 0; k < count; ++k) {
                            const double v = body.read(prop.type);
                            if (v < 0 || v >= double(vertex_el->count))
                                body.fail_last("vertex index " + std::to_string(static_cast<long long>(v)) +
                                                   " out of range (" + std::to_string(vertex_el->count) +
                                                   " vertices)",
                                               type_size(prop.type));
                            poly.push_back(uint32_t(v));
                        }
                        for (size_t k = 1; k + 1 < count; ++k) {
                            mesh.indices.push_back(poly[0]);
                            mesh.indices.push_back(poly[k]);
                            mesh.indices.push_back(poly[k + 1]);
                        }
                    } else {
                        for (size_t k = 0; k < count; ++k) body.read(prop.type);
                    }
                    continue;
                }
                const float v = float(body.read(prop.type));
                switch (prop.role) {
                    case Role::X:
                        p.x = v;
                        break;
                    case Role::Y:
                        p.y = v;
                        break;
                    case Role::Z:
                        p.z = v;
                        break;
                    case Role::NX:
                        n.x = v;
                        break;
                    case Role::NY:
                        n.y = v;
                        break;
                    case Role::NZ:
                        n.z = v;
                        break;
                    case Role::U:
                        uv.x = v;
                        break;
                    case Role::V:
                        uv.y = v;
                        break;
                    default:
                        break;
                }
            }
            body.end_record();
            if (is_vertex) {
                mesh.positions.push_back(p);
                if (normals) mesh.normals.push_back(n);
                if (uvs) mesh.uvs.push_back(uv);
            }
        }
    }
    if (mesh.indices.empty()) throw ParseError(path, 0, 0, "PLY file has no faces");
    return mesh;
}

}  // namespace phos::io
