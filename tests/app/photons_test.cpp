// `phos photons`: the PLY dump holds exactly the photons each map of `phos render --integrator
// photonmap` stores (counts from its -v statistics) with the same total power (from build_maps in
// this process), its header parses, ASCII and the viewer's text format agree, the output does not
// depend on --threads, and bad input exits 2 with nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <regex>
#include <sstream>

#include "integrators/photon_map.h"
#include "io/load_scene.h"
#include "render/prepared.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kScene = shared_path("bench/scn/cornell-glass-mirror.scn");
const std::string kBudget = " --global 5000 --caustic 2000 --seed 3";

// A parsed PLY file with one vertex element: its header, and every property as doubles.
struct Ply {
    std::string format;
    std::vector<std::string> comments;
    size_t count = 0;
    std::vector<std::pair<std::string, std::string>> properties;  // (type, name)
    std::map<std::string, std::vector<double>> values;
    size_t header_bytes = 0;
};

// A tiny PLY reader for what `phos photons` writes: float and uchar vertex properties, binary
// little-endian or ASCII. Fails the test on anything else.
Ply read_ply(const std::string& bytes) {
    Ply ply;
    std::istringstream in(bytes);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "ply");
    while (std::getline(in, line) && line != "end_header") {
        std::istringstream words(line);
        std::string key;
        words >> key;
        if (key == "format") {
            std::string version;
            words >> ply.format >> version;
            EXPECT_EQ(version, "1.0");
        } else if (key == "comment") {
            ply.comments.push_back(line.substr(8));
        } else if (key == "element") {
            std::string name;
            words >> name >> ply.count;
            EXPECT_EQ(name, "vertex");
        } else if (key == "property") {
            std::string type, name;
            words >> type >> name;
            EXPECT_TRUE(type == "float" || type == "uchar") << line;
            ply.properties.emplace_back(type, name);
        } else {
            ADD_FAILURE() << "unexpected header line: " << line;
        }
    }
    EXPECT_EQ(line, "end_header");
    ply.header_bytes = size_t(in.tellg());
    for (const auto& [type, name] : ply.properties) ply.values[name].reserve(ply.count);
    if (ply.format == "ascii") {
        for (size_t i = 0; i < ply.count; ++i)
            for (const auto& [type, name] : ply.properties) {
                std::string word;
                EXPECT_TRUE(in >> word) << "point " << i;
                // Floats as floats: the shortest text of a float reads back to it exactly.
                ply.values[name].push_back(type == "float" ? double(std::strtof(word.c_str(), nullptr))
                                                           : double(std::stoi(word)));
            }
        std::string rest;
        EXPECT_FALSE(in >> rest) << "data after the points";
        return ply;
    }
    EXPECT_EQ(ply.format, "binary_little_endian");
    size_t row = 0;
    for (const auto& p : ply.properties) row += p.first == "float" ? 4 : 1;
    EXPECT_EQ(bytes.size(), ply.header_bytes + row * ply.count);
    if (bytes.size() != ply.header_bytes + row * ply.count) return ply;
    const unsigned char* at = reinterpret_cast<const unsigned char*>(bytes.data()) + ply.header_bytes;
    for (size_t i = 0; i < ply.count; ++i)
        for (const auto& [type, name] : ply.properties) {
            if (type == "uchar") {
                ply.values[name].push_back(*at++);
                continue;
            }
            const uint32_t bits =
                uint32_t(at[0]) | uint32_t(at[1]) << 8 | uint32_t(at[2]) << 16 | uint32_t(at[3]) << 24;
            float f;
            std::memcpy(&f, &bits, 4);
            ply.values[name].push_back(f);
            at += 4;
        }
    return ply;
}

// "global map: 5003 photons from 81234 emitted" from phos render -v -> {"global": 5003}.
std::map<std::string, size_t> map_counts(const std::string& verbose) {
    std::map<std::string, size_t> out;
    const std::regex line(R"(([a-z ]+) map: (\d+) photons from \d+ emitted)");
    for (auto it = std::sregex_iterator(verbose.begin(), verbose.end(), line); it != std::sregex_iterator();
         ++it) {
        std::string name = (*it)[1];
        name = name.substr(name.find_first_not_of(' '));
        out[name] = std::stoul((*it)[2]);
    }
    return out;
}

// Per map id, the number of photons and the summed power (r, g, b) in a parsed dump.
struct MapSums {
    size_t count = 0;
    double power[3] = {0, 0, 0};
};
std::map<int, MapSums> sums_by_map(const Ply& ply) {
    std::map<int, MapSums> out;
    const auto& id = ply.values.at("map");
    for (size_t i = 0; i < ply.count; ++i) {
        MapSums& s = out[int(id[i])];
        ++s.count;
        s.power[0] += ply.values.at("power_r")[i];
        s.power[1] += ply.values.at("power_g")[i];
        s.power[2] += ply.values.at("power_b")[i];
    }
    return out;
}

TEST(Photons, PlyHoldsEveryStoredPhotonWithTheMapsPower) {
    TempDir dir;
    const auto render = run_phos("render " + kScene + " --integrator photonmap" + kBudget +
                                 " --width 8 --height 8 --spp 1 -v -o " + dir.file("r.pfm"));
    ASSERT_EQ(render.exit_code, 0) << render.output;
    const auto counts = map_counts(render.output);
    ASSERT_EQ(counts.size(), 2u) << render.output;
    ASSERT_GT(counts.at("global"), 0u);
    ASSERT_GT(counts.at("caustic"), 0u);

    const std::string out = dir.file("p.ply");
    const auto r = run_phos("photons " + kScene + kBudget + " -o " + out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const Ply ply = read_ply(read_bytes(out));
    const std::vector<std::string> names{"x",       "y",       "z",       "red", "green",  "blue",
                                         "power_r", "power_g", "power_b", "dx",  "dy",     "dz",
                                         "nx",      "ny",      "nz",      "map", "bounces"};
    ASSERT_EQ(ply.properties.size(), names.size());
    for (size_t i = 0; i < names.size(); ++i) {
        EXPECT_EQ(ply.properties[i].second, names[i]);
        const bool byte = names[i] == "red" || names[i] == "green" || names[i] == "blue" ||
                          names[i] == "map" || names[i] == "bounces";
        EXPECT_EQ(ply.properties[i].first, byte ? "uchar" : "float") << names[i];
    }
    EXPECT_EQ(ply.count, counts.at("global") + counts.at("caustic"));
    bool named = false;
    for (const std::string& c : ply.comments) named |= c.find("0 global, 1 caustic") != std::string::npos;
    EXPECT_TRUE(named) << "a comment names the map ids";

    // The maps' own photons and power, traced in this process.
    const scene::Scene scene = io::load_scene(kScene, {});
    render::RenderOptions ro;
    ro.seed = 3;
    Stats stats;
    const render::Prepared prepared(scene, ro, {}, stats);
    integrators::PhotonMapOptions pm;
    pm.global.photons = 5000;
    pm.caustic.photons = 2000;
    pm.irradiance_cache = false;
    const integrators::PhotonMaps maps = integrators::PhotonMapIntegrator(pm).build_maps(prepared, true);

    const auto sums = sums_by_map(ply);
    ASSERT_EQ(sums.size(), 2u);
    for (const int m : {int(photon::kGlobalMap), int(photon::kCausticMap)}) {
        const MapSums& s = sums.at(m);
        EXPECT_EQ(s.count, maps.map[m].size()) << photon::map_name(m);
        EXPECT_EQ(s.count, counts.at(photon::map_name(m)));
        double total[3] = {0, 0, 0};
        for (const photon::Photon& p : maps.map[m].photons()) {
            const Rgb power = p.colour();  // the dump's power columns: the photon's colour
            total[0] += power.r, total[1] += power.g, total[2] += power.b;
        }
        for (int c = 0; c < 3; ++c) {
            EXPECT_GT(total[c], 0);
            EXPECT_NEAR(s.power[c], total[c], 1e-6 * total[c]) << photon::map_name(m) << " channel " << c;
        }
    }
    // Bounce counts: the dump's are the maps' (k-d tree order, global map first); caustic photons
    // came through glass or off the mirror (>= 1 bounce); the global map holds direct photons (0).
    std::vector<uint8_t> expected(maps.bounces[photon::kGlobalMap].begin(),
                                  maps.bounces[photon::kGlobalMap].end());
    expected.insert(expected.end(), maps.bounces[photon::kCausticMap].begin(),
                    maps.bounces[photon::kCausticMap].end());
    ASSERT_EQ(expected.size(), ply.count);
    size_t direct = 0, mismatched = 0;
    for (size_t i = 0; i < ply.count; ++i) {
        const double b = ply.values.at("bounces")[i];
        mismatched += b != double(expected[i]);
        if (int(ply.values.at("map")[i]) == photon::kCausticMap) {
            EXPECT_GE(b, 1.0);
        }
        direct += b == 0;
    }
    EXPECT_EQ(mismatched, 0u);
    EXPECT_GT(direct, counts.at("global") / 4);  // most light reaches the walls directly
    EXPECT_LT(direct, counts.at("global"));

    // Directions are unit vectors; surface photons carry unit normals.
    for (size_t i = 0; i < ply.count; i += 97) {
        const auto& v = ply.values;
        const double d = std::hypot(v.at("dx")[i], v.at("dy")[i], v.at("dz")[i]);
        const double n = std::hypot(v.at("nx")[i], v.at("ny")[i], v.at("nz")[i]);
        EXPECT_NEAR(d, 1.0, 1e-5);
        EXPECT_NEAR(n, 1.0, 1e-5);
    }
}

TEST(Photons, AsciiTextAndThreadsAgreeWithTheBinaryDump) {
    TempDir dir;
    const std::string bin = dir.file("b.ply"), two = dir.file("two.ply");
    ASSERT_EQ(run_phos("photons " + kScene + kBudget + " --threads 1 -q -o " + bin).exit_code, 0);
    ASSERT_EQ(run_phos("photons " + kScene + kBudget + " --threads 2 -q -o " + two).exit_code, 0);
    EXPECT_TRUE(read_bytes(bin) == read_bytes(two)) << "the dump depends on --threads";
    const Ply b = read_ply(read_bytes(bin));
    const auto sums = sums_by_map(b);

    // ASCII PLY of the caustic map alone: the same photons (in the same order), floats exact.
    const std::string ascii = dir.file("a.ply");
    const auto r = run_phos("photons " + kScene + kBudget + " --ascii --maps caustic -q -o " + ascii);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const Ply a = read_ply(read_bytes(ascii));
    EXPECT_EQ(a.format, "ascii");
    ASSERT_EQ(a.count, sums.at(photon::kCausticMap).count);
    const size_t first = sums.at(photon::kGlobalMap).count;  // maps are written in id order
    for (const auto& [type, name] : a.properties)
        for (size_t i = 0; i < a.count; ++i)
            ASSERT_EQ(a.values.at(name)[i], b.values.at(name)[first + i]) << name << " " << i;

    // The viewer's text format: the count, then position, power, direction per photon.
    const std::string text = dir.file("p.txt");
    ASSERT_EQ(run_phos("photons " + kScene + kBudget + " --format text -q -o " + text).exit_code, 0);
    std::istringstream in(read_bytes(text));
    std::string line;
    ASSERT_TRUE(std::getline(in, line));
    EXPECT_EQ(std::stoul(line), b.count);
    size_t lines = 0;
    double power_r = 0;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::vector<double> v;
        for (std::string w; words >> w;) v.push_back(std::strtof(w.c_str(), nullptr));
        ASSERT_EQ(v.size(), 9u) << line;
        if (lines < 3) {
            EXPECT_EQ(v[0], b.values.at("x")[lines]);
            EXPECT_EQ(v[8], b.values.at("dz")[lines]);
        }
        power_r += v[3];
        ++lines;
    }
    EXPECT_EQ(lines, b.count);
    const double want = sums.at(photon::kGlobalMap).power[0] + sums.at(photon::kCausticMap).power[0];
    EXPECT_NEAR(power_r, want, 1e-6 * want);
}

TEST(Photons, BadInputExits2AndWritesNothing) {
    TempDir dir;
    const std::string out = dir.file("p.ply");
    for (const std::string& args : {"photons " + kScene + " --global -5 -o " + out,
                                    "photons " + kScene + " --caustic-samples 0 -o " + out,
                                    "photons " + kScene + " --maps global,sky -o " + out,
                                    "photons " + kScene + " --format xyz -o " + out,
                                    "photons " + kScene + " --format text --ascii -o " + out,
                                    "photons " + kScene, "photons " + dir.file("missing.scn") + " -o " + out,
                                    "photons " + kScene + " --global 500 --maps indirect -o " + out,
                                    "photons " + kScene + " -o " + dir.file("no/such/dir/p.ply")}) {
        const auto r = run_phos(args);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
        EXPECT_FALSE(r.output.empty()) << args;
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << "a failed run wrote something";
}

TEST(Photons, HelpListsTheOptions) {
    const auto r = run_phos("photons --help");
    EXPECT_EQ(r.exit_code, 0);
    for (const char* opt : {"--output", "--format", "--ascii", "--maps", "--global", "--caustic",
                            "--volume-photons", "--photons", "--max-photon-depth", "--seed", "--threads",
                            "--schlick", "--emission-lights", "--quality"})
        EXPECT_NE(r.output.find(opt), std::string::npos) << opt;
    const auto h = run_phos("help photons");
    EXPECT_EQ(h.exit_code, 0);
    EXPECT_NE(h.output.find("--maps"), std::string::npos);
}

}  // namespace
}  // namespace phos::testing
