// A minimal streaming JSON writer: objects, arrays, strings with full escaping, and numbers at full
// precision (floats with 9 significant digits, doubles with 17, so both read back exactly);
// non-finite numbers, which JSON cannot hold, are written as null.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/format.h"
#include "core/vec.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::app {

class JsonWriter {
public:
    // `indent` >= 0 starts the value on a new line indented by that many spaces (for readability).
    JsonWriter& begin_object(int indent = -1) { return open('{', indent); }
    JsonWriter& end_object() { return close('}'); }
    JsonWriter& begin_array(int indent = -1) { return open('[', indent); }
    JsonWriter& end_array() { return close(']'); }

    // The key of the next value in an object.
    JsonWriter& key(const std::string& k) {
        separate();
        quote(k);
        out_ += ':';
        after_key_ = true;
        return *this;
    }

    JsonWriter& value(const std::string& s) {
        prefix();
        quote(s);
        return *this;
    }
    JsonWriter& value(const char* s) { return value(std::string(s)); }
    JsonWriter& value(bool b) {
        prefix();
        out_ += b ? "true" : "false";
        return *this;
    }
    JsonWriter& null() {
        prefix();
        out_ += "null";
        return *this;
    }
    JsonWriter& value(int64_t v) {
        prefix();
        out_ += std::to_string(v);
        return *this;
    }
    JsonWriter& value(uint64_t v) {
        prefix();
        out_ += std::to_string(v);
        return *this;
    }
    JsonWriter& value(int v) { return value(int64_t(v)); }
    JsonWriter& value(uint32_t v) { return value(uint64_t(v)); }
    JsonWriter& value(float v) { return number(double(v), 9); }
    JsonWriter& value(double v) { return number(v, 17); }
    JsonWriter& value(Vec3 v) { return begin_array().value(v.x).value(v.y).value(v.z).end_array(); }
    JsonWriter& value(const Spectrum& s) {
        begin_array();
        for (float x : s.v) value(x);
        return end_array();
    }
    JsonWriter& value(Rgb c) { return begin_array().value(c.r).value(c.g).value(c.b).end_array(); }

    // key(k).value(v)
    template <class T>
    JsonWriter& field(const std::string& k, const T& v) {
        return key(k).value(v);
    }

    const std::string& str() const { return out_; }

private:
    JsonWriter& open(char c, int indent) {
        prefix();
        if (indent >= 0) out_ += '\n' + std::string(size_t(indent), ' ');
        out_ += c;
        first_.push_back(true);
        return *this;
    }
    JsonWriter& close(char c) {
        out_ += c;
        first_.pop_back();
        return *this;
    }
    // Before a value: the comma that separates it from the previous element, unless it follows a key.
    void prefix() {
        if (after_key_)
            after_key_ = false;
        else
            separate();
    }
    void separate() {
        if (first_.empty()) return;
        if (!first_.back()) out_ += ',';
        first_.back() = false;
    }
    JsonWriter& number(double v, int digits) {
        prefix();
        if (!std::isfinite(v)) {
            out_ += "null";
            return *this;
        }
        out_ += printf_string("%.*g", digits, v);
        return *this;
    }
    void quote(const std::string& s) {
        out_ += '"';
        for (const char ch : s) {
            const auto c = static_cast<unsigned char>(ch);
            if (c == '"' || c == '\\') {
                out_ += '\\';
                out_ += ch;
            } else if (c == '\n') {
                out_ += "\\n";
            } else if (c == '\t') {
                out_ += "\\t";
            } else if (c == '\r') {
                out_ += "\\r";
            } else if (c < 0x20) {
                out_ += printf_string("\\u%04x", unsigned(c));
            } else {
                out_ += ch;  // UTF-8 bytes pass through
            }
        }
        out_ += '"';
    }

    std::string out_;
    std::vector<bool> first_;  // per open container: no element written yet
    bool after_key_ = false;
};

}  // namespace phos::app
