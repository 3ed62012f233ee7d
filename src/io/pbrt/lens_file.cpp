// Reading pbrt-v4's lens description files (the format of its scenes' lenses/*.dat, read by
// pbrt-v4's RealisticCamera::Create: PBR 4th ed., sec. 5.4.1), with located errors.
#include "io/pbrt/lens_file.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace phos::io::pbrt {

namespace {

struct Value {
    double v = 0;
    int line = 0, col = 0;
};

}  // namespace

std::vector<scene::LensElement> parse_lens_file(const std::string& file, const std::string& text) {
    std::vector<Value> values;
    int line = 1, col = 1;
    size_t i = 0;
    const auto fail = [&](int l, int c, const std::string& message) {
        throw ParseError(file, l, c, message);
    };
    while (i < text.size()) {
        const char ch = text[i];
        if (ch == '\n') {
            ++line, col = 1, ++i;
        } else if (ch == '#') {
            while (i < text.size() && text[i] != '\n') ++i, ++col;
        } else if (ch == ' ' || ch == '\t' || ch == '\r' || ch == ',') {
            ++i, ++col;
        } else {
            size_t j = i;
            while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j])) && text[j] != '#' &&
                   text[j] != ',')
                ++j;
            const std::string word = text.substr(i, j - i);
            Value v{0, line, col};
            const char* first = word.data() + (word[0] == '+' ? 1 : 0);
            const auto [end, ec] = std::from_chars(first, word.data() + word.size(), v.v);
            if (ec != std::errc() || end != word.data() + word.size() || !std::isfinite(v.v))
                fail(line, col, "lens file: '" + word + "' is not a number");
            values.push_back(v);
            col += int(j - i);
            i = j;
        }
    }
    if (values.empty()) fail(line, col, "lens file: no lens elements (4 numbers each)");
    if (values.size() % 4 != 0) {
        const Value& v = values[values.size() - values.size() % 4];
        fail(v.line, v.col,
             "lens file: " + std::to_string(values.size() % 4) +
                 " number(s) left over from here: each element is 4 numbers (curvature radius, "
                 "thickness, index of refraction, aperture diameter)");
    }
    std::vector<scene::LensElement> elements;
    for (size_t k = 0; k < values.size(); k += 4) {
        const Value &radius = values[k], &thickness = values[k + 1], &eta = values[k + 2],
                    &aperture = values[k + 3];
        if (thickness.v < 0)
            fail(thickness.line, thickness.col, "lens file: a thickness must not be negative");
        if (eta.v < 0 || (eta.v > 0 && eta.v < 1))
            fail(eta.line, eta.col, "lens file: an index of refraction must be 0 (air) or at least 1");
        if (!(aperture.v > 0))
            fail(aperture.line, aperture.col, "lens file: an aperture diameter must be positive");
        scene::LensElement e;
        e.curvature_radius = float(radius.v / 1000);
        e.thickness = float(thickness.v / 1000);
        e.eta = eta.v == 0 ? 1.0f : float(eta.v);
        e.aperture_radius = float(aperture.v / 2000);
        elements.push_back(e);
    }
    if (elements.back().thickness <= 0) {
        const Value& t = values[values.size() - 3];
        fail(t.line, t.col, "lens file: the rear element's distance to the film must be positive");
    }
    return elements;
}

std::vector<scene::LensElement> read_lens_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ParseError(path, 0, 0, "cannot open the lens file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parse_lens_file(path, ss.str());
}

}  // namespace phos::io::pbrt
