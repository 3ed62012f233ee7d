// Sellmeier dispersion and the named glasses (see dispersion.h).
#include "spectrum/dispersion.h"

#include <cmath>

namespace phos::spectrum {

double Sellmeier::ior(double lambda_nm) const {
    const double l2 = (lambda_nm * 1e-3) * (lambda_nm * 1e-3);
    double n2 = 1;
    for (int i = 0; i < 3; ++i) n2 += B[size_t(i)] * l2 / (l2 - C[size_t(i)]);
    return std::sqrt(n2);
}

double abbe_number(const Sellmeier& s) { return (s.ior(kLineD) - 1) / (s.ior(kLineF) - s.ior(kLineC)); }

const std::vector<NamedGlass>& named_glasses() {
    // SCHOTT data sheets: B1 B2 B3, C1 C2 C3 (µm²), n_d, V_d. SF5 and SF10 are the lead-free
    // N-SF5 and N-SF10 of today's catalogue (n_d within 3e-5 of the old lead glasses').
    static const std::vector<NamedGlass> glasses = [] {
        struct Row {
            const char* names[2];
            double b1, b2, b3, c1, c2, c3, nd, vd;
        };
        // clang-format off
        const Row rows[] = {
            //  names                        B1           B2           B3           C1             C2            C3          n_d      V_d
            {{"glass-BK7", nullptr},       1.03961212,  0.231792344, 1.01046945,  0.00600069867, 0.0200179144, 103.560653, 1.51680, 64.17},
            {{"glass-BAF10", nullptr},     1.5851495,   0.143559385, 1.08521269,  0.00926681282, 0.0424489805, 105.613573, 1.67003, 47.11},
            {{"glass-FK51A", nullptr},     0.971247817, 0.216901417, 0.904651666, 0.00472301995, 0.0153575612, 168.68133,  1.48656, 84.47},
            {{"glass-LASF9", nullptr},     2.00029547,  0.298926886, 1.80691843,  0.0121426017,  0.0538736236, 156.530829, 1.85025, 32.17},
            {{"glass-SF5", "glass-F5"},    1.52481889,  0.187085527, 1.42729015,  0.011254756,   0.0588995392, 129.141675, 1.67271, 32.25},
            {{"glass-SF10", "glass-F10"},  1.62153902,  0.256287842, 1.64447552,  0.0122241457,  0.0595736775, 147.468793, 1.72828, 28.53},
            {{"glass-SF11", "glass-F11"},  1.73759695,  0.313747346, 1.89878101,  0.013188707,   0.0623068142, 155.23629,  1.78472, 25.68},
        };
        // clang-format on
        std::vector<NamedGlass> out;
        for (const Row& r : rows)
            for (const char* name : r.names)
                if (name) out.push_back({name, {{r.b1, r.b2, r.b3}, {r.c1, r.c2, r.c3}}, r.nd, r.vd});
        return out;
    }();
    return glasses;
}

std::optional<Sellmeier> named_glass(const std::string& name) {
    for (const NamedGlass& g : named_glasses())
        if (g.name == name) return g.sellmeier;
    return std::nullopt;
}

}  // namespace phos::spectrum
