// tools/tabulate_bsdf: writes an RGL `.bsdf` measured-BRDF file (Dupuy & Jakob 2018's tables, as
// pbrt-v4's `measured` material reads them) tabulated from an analytic model
// (shading/measured_tabulation.h): a Trowbridge-Reitz conductor of a named metal's eta, k (phos's
// named metals: Ag, Al, Au, Cu, CuZn, MgO, TiO2) or a Lambertian reflector. For test and gallery
// materials: no public measured files can be fetched here.
// Usage: tabulate_bsdf OUT.bsdf conductor METAL ALPHA_X [ALPHA_Y]
//        tabulate_bsdf OUT.bsdf lambert REFLECTANCE
// Spectral over 360-830 nm every 10 nm; 16 incident elevations (x 9 azimuths when anisotropic),
// 64 x 64 ndf and sigma, 48 x 48 vndf, 48 x 48 reduced-BRDF grids.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>

#include "io/bsdf/rgl_bsdf_file.h"
#include "shading/measured_tabulation.h"
#include "spectrum/named_metals.h"

int main(int argc, char** argv) {
    using namespace phos;
    const auto usage = [] {
        std::fprintf(stderr,
                     "usage: tabulate_bsdf OUT.bsdf conductor METAL ALPHA_X [ALPHA_Y]\n"
                     "       tabulate_bsdf OUT.bsdf lambert REFLECTANCE\n");
        return 2;
    };
    if (argc < 4) return usage();
    const std::string out = argv[1], kind = argv[2];
    shading::TabulatedModel model;
    shading::TabulationGrid grid;
    grid.n_theta_i = 16;
    grid.vndf_n = 48;
    grid.n = 48;
    for (int l = 360; l <= 830; l += 10) grid.wavelengths.push_back(float(l));
    std::optional<spectrum::NamedMetal> metal;
    if (kind == "conductor" && (argc == 5 || argc == 6)) {
        metal = spectrum::named_metal(argv[3]);
        if (!metal) {
            std::fprintf(stderr, "tabulate_bsdf: unknown metal '%s'\n", argv[3]);
            return 2;
        }
        model.kind = shading::TabulatedModel::Kind::Conductor;
        model.alpha_x = std::strtof(argv[4], nullptr);
        model.alpha_y = argc == 6 ? std::strtof(argv[5], nullptr) : model.alpha_x;
        if (!(model.alpha_x > 0 && model.alpha_y > 0)) return usage();
        model.eta = [&](float l) { return metal->eta(l); };
        model.k = [&](float l) { return metal->k(l); };
        grid.description = "phos tabulate_bsdf: Trowbridge-Reitz conductor " + std::string(argv[3]) +
                           ", alpha " + argv[4] + (argc == 6 ? std::string(" x ") + argv[5] : "");
    } else if (kind == "lambert" && argc == 4) {
        model.kind = shading::TabulatedModel::Kind::Lambert;
        model.alpha_x = model.alpha_y = 1;
        model.reflectance = std::strtof(argv[3], nullptr);
        if (!(model.reflectance > 0 && model.reflectance <= 1)) return usage();
        grid.description = "phos tabulate_bsdf: Lambertian, reflectance " + std::string(argv[3]);
    } else {
        return usage();
    }
    try {
        io::write_rgl_bsdf(out, shading::tabulate_brdf(model, grid));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tabulate_bsdf: %s\n", e.what());
        return 1;
    }
    return 0;
}
