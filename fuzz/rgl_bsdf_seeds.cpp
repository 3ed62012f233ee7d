// Writes the rgl_bsdf fuzz target's seeds (scripts/fuzz.sh runs it): small valid RGL `.bsdf` files
// written by phos's own writer (io/bsdf): spectral isotropic, rgb-only, and anisotropic.
// Usage: rgl_bsdf_seeds OUT_DIR
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "io/bsdf/rgl_bsdf_file.h"

namespace {

phos::scene::MeasuredBsdfTables tables(bool spectral, bool isotropic) {
    phos::scene::MeasuredBsdfTables t;
    t.description = "fuzz seed";
    t.theta_i = {0.0f, 0.7f, 1.5f};
    t.phi_i = isotropic ? std::vector<float>{0.0f} : std::vector<float>{-3.14159265f, 0.0f, 3.14159265f};
    if (spectral) t.wavelengths = {400, 550, 700};
    t.ndf_nx = t.ndf_ny = t.sigma_nx = t.sigma_ny = 3;
    t.ndf = {2, 1, 0.5f, 2, 1, 0.5f, 2, 1, 0.5f};
    t.sigma = {1, 1.1f, 1.3f, 1, 1.1f, 1.3f, 1, 1.1f, 1.3f};
    t.vndf_nx = t.vndf_ny = 3;
    t.n = 3;
    const size_t slices = t.theta_i.size() * t.phi_i.size(), channels = 3;  // wavelengths or RGB
    for (size_t s = 0; s < slices; ++s) {
        for (int i = 0; i < 9; ++i) t.vndf.push_back(0.2f + float((i * 7 + int(s)) % 5));
        for (int i = 0; i < 9; ++i) t.luminance.push_back(0.1f + float((i * 3 + int(s)) % 4) * 0.2f);
        for (size_t c = 0; c < channels; ++c)
            for (int i = 0; i < 9; ++i)
                (spectral ? t.spectra : t.rgb).push_back(0.1f + float((i * 5 + int(c)) % 4) * 0.25f);
    }
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: rgl_bsdf_seeds OUT_DIR\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    phos::io::write_rgl_bsdf((dir / "spectral.bsdf").string(), tables(true, true));
    phos::io::write_rgl_bsdf((dir / "rgb.bsdf").string(), tables(false, true));
    phos::io::write_rgl_bsdf((dir / "anisotropic.bsdf").string(), tables(true, false));
    return 0;
}
