// Measured optical constants of the named metals and oxides (see named_metals.h), from the
// refractiveindex.info database (public domain, CC0): the tabulated points that cover [360, 830]
// nm (one beyond each end) for Ag, Au, Cu (Johnson & Christy 1972) and Al (Rakic 1995); MgO
// (Stephens & Malitson 1952) and TiO2 (rutile, ordinary ray, Devore 1951) from their dispersion
// formulas at every 10 nm, with k = 0 (Devore's formula is fitted from 430 nm: below it the
// table extrapolates it).
#include "spectrum/named_metals.h"

namespace phos::spectrum {

namespace {
// Ag: P. B. Johnson and R. W. Christy, Phys. Rev. B 6, 4370 (1972); lambda (nm), eta, k.
const OpticalConstant kAg[] = {
    {354.2f, 0.1f, 1.419f},  {367.9f, 0.07f, 1.657f}, {381.5f, 0.05f, 1.864f}, {397.4f, 0.05f, 2.07f},
    {413.3f, 0.05f, 2.275f}, {430.5f, 0.04f, 2.462f}, {450.9f, 0.04f, 2.657f}, {471.4f, 0.05f, 2.869f},
    {495.9f, 0.05f, 3.093f}, {520.9f, 0.05f, 3.324f}, {548.6f, 0.06f, 3.586f}, {582.1f, 0.05f, 3.858f},
    {616.8f, 0.06f, 4.152f}, {659.5f, 0.05f, 4.483f}, {704.5f, 0.04f, 4.838f}, {756.0f, 0.03f, 5.242f},
    {821.1f, 0.04f, 5.727f}, {892.0f, 0.04f, 6.312f},
};

// Al: A. D. Rakic, Appl. Opt. 34, 4755 (1995); lambda (nm), eta, k.
const OpticalConstant kAl[] = {
    {326.3f, 0.31474f, 3.9165f}, {364.7f, 0.39877f, 4.3957f}, {413.3f, 0.52135f, 5.0008f},
    {442.8f, 0.6079f, 5.3676f},  {476.9f, 0.7278f, 5.7781f},  {516.6f, 0.8734f, 6.2418f},
    {563.6f, 1.0728f, 6.7839f},  {619.9f, 1.366f, 7.4052f},   {652.2f, 1.5724f, 7.7354f},
    {688.8f, 1.8301f, 8.0601f},  {729.3f, 2.1606f, 8.3565f},  {774.9f, 2.6154f, 8.4914f},
    {794.8f, 2.7675f, 8.3866f},  {815.7f, 2.7668f, 8.2573f},  {837.7f, 2.6945f, 8.1878f},
};

// Au: Johnson and Christy (1972); lambda (nm), eta, k.
const OpticalConstant kAu[] = {
    {354.2f, 1.5f, 1.866f},  {367.9f, 1.48f, 1.895f}, {381.5f, 1.46f, 1.933f}, {397.4f, 1.47f, 1.952f},
    {413.3f, 1.46f, 1.958f}, {430.5f, 1.45f, 1.948f}, {450.9f, 1.38f, 1.914f}, {471.4f, 1.31f, 1.849f},
    {495.9f, 1.04f, 1.833f}, {520.9f, 0.62f, 2.081f}, {548.6f, 0.43f, 2.455f}, {582.1f, 0.29f, 2.863f},
    {616.8f, 0.21f, 3.272f}, {659.5f, 0.14f, 3.697f}, {704.5f, 0.13f, 4.103f}, {756.0f, 0.14f, 4.542f},
    {821.1f, 0.16f, 5.083f}, {892.0f, 0.17f, 5.663f},
};

// Cu: Johnson and Christy (1972); lambda (nm), eta, k.
const OpticalConstant kCu[] = {
    {354.2f, 1.37f, 1.916f}, {367.9f, 1.36f, 1.975f}, {381.5f, 1.33f, 2.045f}, {397.4f, 1.32f, 2.116f},
    {413.3f, 1.28f, 2.207f}, {430.5f, 1.25f, 2.305f}, {450.9f, 1.24f, 2.397f}, {471.4f, 1.25f, 2.483f},
    {495.9f, 1.22f, 2.564f}, {520.9f, 1.18f, 2.608f}, {548.6f, 1.02f, 2.577f}, {582.1f, 0.7f, 2.704f},
    {616.8f, 0.3f, 3.205f},  {659.5f, 0.22f, 3.747f}, {704.5f, 0.21f, 4.205f}, {756.0f, 0.24f, 4.665f},
    {821.1f, 0.26f, 5.18f},  {892.0f, 0.3f, 5.768f},
};

// MgO: R. E. Stephens and I. H. Malitson, J. Res. NBS 49, 249 (1952); lambda (nm), eta, k.
const OpticalConstant kMgO[] = {
    {360.0f, 1.7735f, 0.0f}, {370.0f, 1.7703f, 0.0f}, {380.0f, 1.7674f, 0.0f}, {390.0f, 1.7647f, 0.0f},
    {400.0f, 1.7622f, 0.0f}, {410.0f, 1.7599f, 0.0f}, {420.0f, 1.7578f, 0.0f}, {430.0f, 1.7559f, 0.0f},
    {440.0f, 1.7541f, 0.0f}, {450.0f, 1.7524f, 0.0f}, {460.0f, 1.7508f, 0.0f}, {470.0f, 1.7494f, 0.0f},
    {480.0f, 1.748f, 0.0f},  {490.0f, 1.7467f, 0.0f}, {500.0f, 1.7455f, 0.0f}, {510.0f, 1.7444f, 0.0f},
    {520.0f, 1.7433f, 0.0f}, {530.0f, 1.7423f, 0.0f}, {540.0f, 1.7414f, 0.0f}, {550.0f, 1.7405f, 0.0f},
    {560.0f, 1.7397f, 0.0f}, {570.0f, 1.7388f, 0.0f}, {580.0f, 1.7381f, 0.0f}, {590.0f, 1.7374f, 0.0f},
    {600.0f, 1.7367f, 0.0f}, {610.0f, 1.736f, 0.0f},  {620.0f, 1.7354f, 0.0f}, {630.0f, 1.7348f, 0.0f},
    {640.0f, 1.7342f, 0.0f}, {650.0f, 1.7337f, 0.0f}, {660.0f, 1.7332f, 0.0f}, {670.0f, 1.7327f, 0.0f},
    {680.0f, 1.7322f, 0.0f}, {690.0f, 1.7317f, 0.0f}, {700.0f, 1.7313f, 0.0f}, {710.0f, 1.7308f, 0.0f},
    {720.0f, 1.7304f, 0.0f}, {730.0f, 1.73f, 0.0f},   {740.0f, 1.7297f, 0.0f}, {750.0f, 1.7293f, 0.0f},
    {760.0f, 1.7289f, 0.0f}, {770.0f, 1.7286f, 0.0f}, {780.0f, 1.7283f, 0.0f}, {790.0f, 1.7279f, 0.0f},
    {800.0f, 1.7276f, 0.0f}, {810.0f, 1.7273f, 0.0f}, {820.0f, 1.727f, 0.0f},  {830.0f, 1.7267f, 0.0f},
};

// TiO2: J. R. Devore, JOSA 41, 416 (1951), ordinary ray; lambda (nm), eta, k.
const OpticalConstant kTiO2[] = {
    {360.0f, 3.2961f, 0.0f}, {370.0f, 3.1978f, 0.0f}, {380.0f, 3.1179f, 0.0f}, {390.0f, 3.0517f, 0.0f},
    {400.0f, 2.996f, 0.0f},  {410.0f, 2.9484f, 0.0f}, {420.0f, 2.9074f, 0.0f}, {430.0f, 2.8717f, 0.0f},
    {440.0f, 2.8403f, 0.0f}, {450.0f, 2.8126f, 0.0f}, {460.0f, 2.7878f, 0.0f}, {470.0f, 2.7657f, 0.0f},
    {480.0f, 2.7458f, 0.0f}, {490.0f, 2.7277f, 0.0f}, {500.0f, 2.7114f, 0.0f}, {510.0f, 2.6964f, 0.0f},
    {520.0f, 2.6827f, 0.0f}, {530.0f, 2.6702f, 0.0f}, {540.0f, 2.6586f, 0.0f}, {550.0f, 2.6479f, 0.0f},
    {560.0f, 2.638f, 0.0f},  {570.0f, 2.6289f, 0.0f}, {580.0f, 2.6203f, 0.0f}, {590.0f, 2.6124f, 0.0f},
    {600.0f, 2.6049f, 0.0f}, {610.0f, 2.598f, 0.0f},  {620.0f, 2.5915f, 0.0f}, {630.0f, 2.5853f, 0.0f},
    {640.0f, 2.5796f, 0.0f}, {650.0f, 2.5742f, 0.0f}, {660.0f, 2.5691f, 0.0f}, {670.0f, 2.5642f, 0.0f},
    {680.0f, 2.5597f, 0.0f}, {690.0f, 2.5553f, 0.0f}, {700.0f, 2.5512f, 0.0f}, {710.0f, 2.5473f, 0.0f},
    {720.0f, 2.5437f, 0.0f}, {730.0f, 2.5401f, 0.0f}, {740.0f, 2.5368f, 0.0f}, {750.0f, 2.5336f, 0.0f},
    {760.0f, 2.5306f, 0.0f}, {770.0f, 2.5277f, 0.0f}, {780.0f, 2.5249f, 0.0f}, {790.0f, 2.5223f, 0.0f},
    {800.0f, 2.5197f, 0.0f}, {810.0f, 2.5173f, 0.0f}, {820.0f, 2.515f, 0.0f},  {830.0f, 2.5128f, 0.0f},
};

}  // namespace

const std::vector<NamedMetal>& named_metals() {
    static const std::vector<NamedMetal> metals = {
        {"Ag", std::vector<OpticalConstant>(std::begin(kAg), std::end(kAg))},
        {"Al", std::vector<OpticalConstant>(std::begin(kAl), std::end(kAl))},
        {"Au", std::vector<OpticalConstant>(std::begin(kAu), std::end(kAu))},
        {"Cu", std::vector<OpticalConstant>(std::begin(kCu), std::end(kCu))},
        {"MgO", std::vector<OpticalConstant>(std::begin(kMgO), std::end(kMgO))},
        {"TiO2", std::vector<OpticalConstant>(std::begin(kTiO2), std::end(kTiO2))},
    };
    return metals;
}

}  // namespace phos::spectrum
