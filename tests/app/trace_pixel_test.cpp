// --trace-pixel and --trace-json through the phos binary: for every integrator the JSON holds one
// path per camera sample (SPPM: per iteration), each with vertices whose events are from the
// documented set, and the pixel in the image is the mean of the paths' contributions (SPPM: the
// reported value, which the last photon pass's statistics reproduce); tracing leaves the image
// unchanged; a pixel outside the image exits 2 before anything is written.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos::testing {
namespace {

// A JSON value and a minimal recursive-descent parser (enough for the trace: no \u escapes).
struct Json {
    enum Kind { Null, Bool, Number, String, Array, Object } kind = Null;
    bool b = false;
    double num = 0;
    std::string str;
    std::vector<Json> items;
    std::map<std::string, Json> fields;
    const Json& operator[](const std::string& k) const {
        static const Json none;
        const auto it = fields.find(k);
        return it == fields.end() ? none : it->second;
    }
    const Json& operator[](size_t i) const { return items.at(i); }
    bool has(const std::string& k) const { return fields.count(k) > 0; }
};

class JsonParser {
public:
    explicit JsonParser(const std::string& text) : s_(text) {}
    Json parse() {
        Json v = value();
        skip();
        if (i_ != s_.size()) fail("trailing characters");
        return v;
    }

private:
    [[noreturn]] void fail(const std::string& why) {
        throw std::runtime_error("JSON: " + why + " at " + std::to_string(i_));
    }
    void skip() {
        while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
    }
    bool eat(char c) {
        skip();
        if (i_ < s_.size() && s_[i_] == c) return ++i_, true;
        return false;
    }
    void expect(char c) {
        if (!eat(c)) fail(std::string("expected ") + c);
    }
    std::string string() {
        expect('"');
        std::string out;
        while (i_ < s_.size() && s_[i_] != '"') {
            if (s_[i_] == '\\') {
                const char e = s_.at(++i_);
                out += e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e;
            } else {
                out += s_[i_];
            }
            ++i_;
        }
        expect('"');
        return out;
    }
    Json value() {
        skip();
        Json v;
        if (i_ >= s_.size()) fail("unexpected end");
        const char c = s_[i_];
        if (c == '{') {
            v.kind = Json::Object;
            ++i_;
            if (eat('}')) return v;
            do {
                const std::string k = string();
                expect(':');
                v.fields[k] = value();
            } while (eat(','));
            expect('}');
        } else if (c == '[') {
            v.kind = Json::Array;
            ++i_;
            if (eat(']')) return v;
            do v.items.push_back(value());
            while (eat(','));
            expect(']');
        } else if (c == '"') {
            v.kind = Json::String;
            v.str = string();
        } else if (s_.compare(i_, 4, "null") == 0) {
            i_ += 4;
        } else if (s_.compare(i_, 4, "true") == 0 || s_.compare(i_, 5, "false") == 0) {
            v.kind = Json::Bool;
            v.b = c == 't';
            i_ += v.b ? 4 : 5;
        } else {
            v.kind = Json::Number;
            size_t used = 0;
            v.num = std::stod(s_.substr(i_, 40), &used);
            i_ += used;
        }
        return v;
    }
    const std::string& s_;
    size_t i_ = 0;
};

Json read_json(const std::string& path) { return JsonParser(read_bytes(path)).parse(); }

const std::string kScene = shared_path("bench/scn/cornell-glass-mirror.scn");
const std::string kArgs = " --width 16 --height 16 --threads 2 -q --seed 3";
const std::set<std::string> kEvents = {"diffuse", "glossy",  "specular", "transmission",
                                       "medium",  "emitter", "escaped"};

// Float rounding of the film's mean (a double sum written as a float): relative 1e-5, or absolute
// 1e-6 for dark pixels.
void expect_close(double got, double want, const std::string& what) {
    EXPECT_LE(std::fabs(got - want), std::max(1e-6, 1e-5 * std::fabs(want)))
        << what << ": " << got << " vs " << want;
}

struct Traced {
    Json json;
    Rgb pixel;  // the image's value at the traced pixel
};

// Renders with --trace-pixel x y --trace-json and reads both outputs back.
Traced render_traced(const TempDir& dir, const std::string& args, int x, int y) {
    const std::string json = dir.file("trace.json"), out = dir.file("out.pfm");
    const auto r = run_phos("render " + kScene + kArgs + args + " --trace-pixel " + std::to_string(x) + " " +
                            std::to_string(y) + " --trace-json " + json + " -o " + out);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("trace of pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")"),
              std::string::npos)
        << r.output.substr(0, 2000);
    Traced t;
    t.json = read_json(json);
    t.pixel = io::read_image(out, false).at(x, y);
    return t;
}

// Every path has vertices with known events; returns the number of paths.
size_t check_paths(const Json& j, int x, int y) {
    EXPECT_EQ(j["pixel"][0].num, x);
    EXPECT_EQ(j["pixel"][1].num, y);
    const Json& paths = j["paths"];
    for (const Json& p : paths.items) {
        EXPECT_GE(p["vertices"].items.size(), 1u);
        for (const Json& v : p["vertices"].items) {
            EXPECT_EQ(kEvents.count(v["event"].str), 1u) << v["event"].str;
            EXPECT_EQ(v["throughput"].items.size(), 4u);  // at the path's four wavelengths
        }
        EXPECT_EQ(p["contribution"].items.size(), 3u);
    }
    return paths.items.size();
}

// The pixel is the mean of the paths' contributions (the box filter).
void expect_mean(const Traced& t, const std::string& what) {
    const Json& paths = t.json["paths"];
    ASSERT_FALSE(paths.items.empty());
    for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (const Json& p : paths.items) sum += p["contribution"][size_t(c)].num;
        expect_close(sum / double(paths.items.size()), t.pixel[c], what + " channel " + std::to_string(c));
        expect_close(t.json["value"][size_t(c)].num, t.pixel[c], what + " value");
    }
}

TEST(TracePixel, WhittedPathsAverageToThePixel) {
    TempDir dir;
    // Through the glass sphere (specular and transmission events).
    const Traced t = render_traced(dir, " --integrator whitted --spp 4", 11, 10);
    EXPECT_EQ(check_paths(t.json, 11, 10), 4u);
    expect_mean(t, "whitted");
}

TEST(TracePixel, PathPathsAverageToThePixelAndTheImageIsUnchanged) {
    TempDir dir;
    const Traced t = render_traced(dir, " --integrator path --spp 4 --dof 2 3 0.01", 7, 9);
    EXPECT_EQ(check_paths(t.json, 7, 9), 8u);  // spp x lens samples
    expect_mean(t, "path");
    // Light samples carry their visibility; what the vertices add sums to the contribution.
    size_t lights = 0;
    for (const Json& p : t.json["paths"].items) {
        double sum = 0;
        for (const Json& v : p["vertices"].items) {
            lights += v["lights"].items.size();
            for (const auto& [term, c] : v["radiance"].fields) sum += c[0].num;
        }
        expect_close(sum, p["contribution"][0].num, "path terms");
    }
    EXPECT_GT(lights, 0u);
    const auto plain = run_phos("render " + kScene + kArgs + " --integrator path --spp 4 --dof 2 3 0.01 -o " +
                                dir.file("plain.pfm"));
    ASSERT_EQ(plain.exit_code, 0) << plain.output;
    EXPECT_TRUE(read_bytes(dir.file("plain.pfm")) == read_bytes(dir.file("out.pfm")));
}

TEST(TracePixel, PhotonMapPathsAverageToThePixelAndListLookups) {
    TempDir dir;
    const Traced t = render_traced(
        dir, " --integrator photonmap --spp 4 --global 20000 --caustic 10000 --gather-rays 4", 7, 9);
    EXPECT_EQ(check_paths(t.json, 7, 9), 4u);
    expect_mean(t, "photonmap");
    size_t caustic = 0;
    for (const Json& p : t.json["paths"].items)
        for (const Json& v : p["vertices"].items)
            for (const Json& l : v["lookups"].items)
                if (l["map"].str == "caustic") {
                    ++caustic;
                    EXPECT_GT(l["radius"].num, 0);
                }
    EXPECT_GT(caustic, 0u);
}

TEST(TracePixel, SppmReportsVisiblePointsPhotonsAndTheFinalValue) {
    TempDir dir;
    const std::string args = " --integrator sppm --iterations 3 --photons-per-iter 20000";
    const Traced t = render_traced(dir, args, 7, 9);
    EXPECT_EQ(check_paths(t.json, 7, 9), 3u);  // one eye path per iteration
    for (int c = 0; c < 3; ++c) expect_close(t.json["value"][size_t(c)].num, t.pixel[c], "sppm value");
    // The last iteration's statistics give the pixel: direct sum / iterations + τ / (π R² N_emitted).
    const Json& last = t.json["paths"][2];
    ASSERT_TRUE(last.has("visible_point"));
    const Json& pass = last["visible_point"]["passes"][0];
    EXPECT_EQ(pass["found"].num, double(pass["photons"].items.size()));
    EXPECT_GT(pass["photons"].items.size(), 0u);
    // The trace lists the photons each pass gathered by a search of its own, photon by photon;
    // the statistics come from the photon pass's binned gather. Each pass after the pilot adds
    // alpha = 0.7 of its photon count to N (eq. 9): both must have found the same photons.
    const double alpha = double(0.7f);  // --alpha's default, a float
    double n_before = 0;
    for (size_t it = 1; it < 3; ++it) {
        const Json& p = t.json["paths"][it]["visible_point"]["passes"][0];
        const double m = double(p["photons"].items.size());
        EXPECT_NEAR(p["n"].num, n_before + alpha * m, 1e-9 * (1 + m)) << "iteration " << it;
        n_before = p["n"].num;
    }
    for (int c = 0; c < 3; ++c) {
        const double v = pass["direct_sum"][size_t(c)].num / 3 +
                         pass["tau"][size_t(c)].num / (M_PI * pass["r2"].num * pass["photons_emitted"].num);
        expect_close(v, t.pixel[c], "sppm statistics");
    }
    const auto plain = run_phos("render " + kScene + kArgs + args + " -o " + dir.file("plain.pfm"));
    ASSERT_EQ(plain.exit_code, 0) << plain.output;
    EXPECT_TRUE(read_bytes(dir.file("plain.pfm")) == read_bytes(dir.file("out.pfm")));
}

TEST(TracePixel, PpmReportsItsHitPointsAndTheFinalValue) {
    TempDir dir;
    const Traced t = render_traced(dir, " --integrator ppm --iterations 2 --photons-per-iter 20000", 7, 9);
    EXPECT_EQ(check_paths(t.json, 7, 9), 1u);  // one hit point per pixel
    for (int c = 0; c < 3; ++c) expect_close(t.json["value"][size_t(c)].num, t.pixel[c], "ppm value");
    ASSERT_TRUE(t.json["paths"][0].has("visible_point"));
    EXPECT_EQ(t.json["paths"][0]["visible_point"]["passes"].items.size(), 2u);  // one per iteration
}

TEST(TracePixel, PixelOutsideTheImageExits2WithNoOutput) {
    TempDir dir;
    for (const char* pixel : {"16 0", "0 16", "-1 3"}) {
        const auto r = run_phos("render " + kScene + kArgs + " --integrator path --spp 1 --trace-pixel " +
                                pixel + " --trace-json " + dir.file("t.json") + " -o " + dir.file("o.pfm"));
        EXPECT_EQ(r.exit_code, 2) << pixel << ": " << r.output;
        EXPECT_NE(r.output.find("--trace-pixel"), std::string::npos) << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir.file("o.pfm")));
        EXPECT_FALSE(std::filesystem::exists(dir.file("t.json")));
    }
    const auto r = run_phos("render " + kScene + kArgs + " --spp 1 --trace-json " + dir.file("t.json") +
                            " -o " + dir.file("o.pfm"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("o.pfm")));
    // bdpt and vcm record no traces: refused before any work rather than an empty trace.
    for (const char* integrator : {"bdpt", "vcm"}) {
        const auto b = run_phos("render " + kScene + kArgs + " --integrator " + integrator +
                                " --spp 1 --trace-pixel 3 3 -o " + dir.file("o.pfm"));
        EXPECT_EQ(b.exit_code, 2) << b.output;
        EXPECT_NE(b.output.find("does not record pixel traces"), std::string::npos) << b.output;
        EXPECT_FALSE(std::filesystem::exists(dir.file("o.pfm")));
    }
}

}  // namespace
}  // namespace phos::testing
