// The seed renderer's flags: a table from each flag to its phos equivalent or to the reason it has
// no effect, and the rewrite of a command line through it.
#include "app/lib/seed_flags.h"

#include <cctype>
#include <cstdlib>
#include <cstring>

namespace phos::app {

namespace {

struct SeedFlag {
    const char* flag;
    int values;          // how many values follow it
    const char* phos;    // replacement option ("" = none); its values follow it
    const char* reason;  // why it has no effect (warned), or "" when phos already behaves so
};

// The seed's README flags that phos does not accept under the same name.
constexpr SeedFlag kSeedFlags[] = {
    {"-no_fresnel", 0, "",
     "phos always applies Fresnel reflection at dielectric boundaries (without it, glass would create or "
     "lose "
     "energy)"},
    {"-ir", 1, "",
     "phos reads each material's index of refraction relative to the medium outside it; vacuum and air are "
     "1"},
    {"-no_ambient", 0, "", ""},  // ambient light is already off unless --ambient asks for it
    {"-no-monte", 0, "",
     "phos always traces specular and transmissive paths (mirrors and glass would be black otherwise); "
     "--no-specular and --no-transmissive leave those components out"},
    {"-md", 1, "--max-depth", ""},
    {"-pd", 1, "--max-photon-depth", ""},
    {"-absorb", 1, "",
     "photons are absorbed by Russian roulette on each surface's own reflectance, not with a fixed "
     "probability"},
    {"-no_rs", 0, "",
     "shadows seen through mirrors and glass are part of the light transport; phos always computes them"},
    {"-no_dt", 0, "",
     "frosted transmission is sampled from the material's own lobe; there is no separate switch"},
    {"-no_ds", 0, "",
     "glossy reflection is sampled from the material's own lobe; there is no separate switch"},
    {"-tt", 1, "",
     "phos follows one transmitted direction per path vertex; raise --spp for smoother frosted glass"},
    {"-st", 1, "",
     "phos follows one reflected direction per path vertex; raise --spp for smoother glossy surfaces"},
    {"-it", 1, "--gather-rays", ""},
    {"-gs", 1, "--global-samples", ""},
    {"-gd", 1, "--global-radius", ""},
    {"-cs", 1, "--caustic-samples", ""},
    {"-cd", 1, "--caustic-radius", ""},
    {"-cache", 0, "--irradiance-cache", ""},
    {"-no_shadow", 0, "",
     "shadows are part of the light transport; a physically based renderer cannot turn them off"},
    {"-no_ss", 0, "", "soft shadows follow from sampling the area lights; they cannot be turned off"},
    {"-lt", 1, "", "phos samples each light once per path vertex; raise --spp for smoother shadows"},
    {"-ss", 1, "", "phos samples each light once per path vertex; raise --spp for smoother shadows"},
    {"-s", 1, "", "phos samples each light once per path vertex; raise --spp for smoother shadows"},
};

bool is_number(const std::string& s) {
    if (s.empty()) return false;
    char* end = nullptr;
    std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size();
}

}  // namespace

SeedFlagResult translate_seed_flags(const std::vector<std::string>& args) {
    SeedFlagResult r;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        // -gf / -cf: the estimate's filter, `cone K` (two words after the flag) or `gauss`.
        if (a == "-gf" || a == "-cf") {
            const std::string map = a == "-gf" ? "global" : "caustic";
            if (i + 1 < args.size() && args[i + 1] == "cone") {
                r.args.push_back("--" + map + "-filter");
                r.args.push_back("cone");
                ++i;
                if (i + 1 < args.size() && is_number(args[i + 1])) {
                    r.args.push_back("--" + map + "-cone-k");
                    r.args.push_back(args[++i]);
                }
                continue;
            }
            if (i + 1 < args.size() && (args[i + 1] == "gauss" || args[i + 1] == "gaussian")) {
                r.args.push_back("--" + map + "-filter");
                r.args.push_back("gauss");
                ++i;
                continue;
            }
            r.args.push_back("--" + map + "-filter");  // the parser names the bad or missing value
            continue;
        }
        const SeedFlag* flag = nullptr;
        for (const SeedFlag& f : kSeedFlags)
            if (a == f.flag) flag = &f;
        if (!flag || i + size_t(flag->values) >= args.size()) {  // not a seed flag, or its value is missing
            r.args.push_back(a);
            continue;
        }
        if (*flag->phos) {
            r.args.push_back(flag->phos);
            for (int v = 0; v < flag->values; ++v) r.args.push_back(args[i + 1 + size_t(v)]);
        } else if (*flag->reason) {
            r.warnings.push_back(std::string(flag->flag) + " has no effect: " + flag->reason);
        }
        i += size_t(flag->values);
    }
    return r;
}

void move_trailing_output(std::vector<std::string>& args) {
    if (args.size() < 4 || args[0] != "render" || args[1].empty() || args[1][0] == '-' || args[2].empty() ||
        args[2][0] != '-')
        return;
    const std::string& last = args.back();
    const std::string& before = args[args.size() - 2];
    if (last.empty() || last[0] == '-' || before == "-o" || before == "--output") return;
    const size_t dot = last.rfind('.');
    if (dot == std::string::npos) return;
    std::string ext = last.substr(dot);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const char* image : {".png", ".exr", ".pfm", ".bmp", ".jpg", ".jpeg", ".hdr", ".ppm"})
        if (ext == image) {
            const std::string out = last;
            args.pop_back();
            args.insert(args.begin() + 2, out);
            return;
        }
}

}  // namespace phos::app
