// pbrt-v3 files read directly: each directive's type and parameters are rewritten to their pbrt-v4
// form by the parser, before any ParserTarget (the scene builder, `phos upgrade`) sees them, by the rules
// pbrt-v4's own `pbrt --upgrade` applies (listed in docs/formats/pbrt.md, "pbrt-v3 files"). A rule applies
// where a pbrt-v3 name or parameter type appears (`Material "matte"`, `"rgb scale"` on a light,
// `AreaLightSource "area"`, `Film "image"`), none of which pbrt-v4 defines, so a pbrt-v4 file passes
// unchanged and no flag is needed. Something pbrt-v4's upgrade also refuses (a coloured light "scale" on a
// spectral emission, two "rgb" values for one "scale" texture) is an error at its parameter.
#pragma once

#include <string>

#include "io/pbrt/params.h"

namespace phos::io::pbrt {

// The rules for one directive, applied by the parser before its ParserTarget sees the directive
// (`type` is the directive's first argument: a material's name for MakeNamedMaterial):
// - Material and MakeNamedMaterial's "type": matte, plastic, metal, glass, mirror, uber, substrate,
//   translucent, kdsubsurface, disney, mix's namedmaterial1/2 and RGB amount, glass/uber "index",
//   "bumpmap"; "" and "none" become "interface".
// - LightSource and AreaLightSource: a spectrum-valued "scale" (pbrt-v3: "rgb"/"color"/"spectrum")
//   becomes the float "scale" (a grey value multiplies it; a coloured one multiplies an "rgb" L or
//   I), a two-value blackbody [T s] keeps T and multiplies "scale" by s, "mapname" becomes
//   "filename" (with an infinite light's constant L folded into "scale"; a goniometric light's
//   lat-long "mapname" stays for the scene builder), "samples"/"nsamples" are
//   dropped, and AreaLightSource "area" is "diffuse".
// - Film "image" is "rgb"; its "scale" multiplies the image (pbrt-v4: "iso" = 100 × scale) and
//   "maxsampleluminance" is "maxcomponentvalue".
// - Shape: loopsubdiv's "nlevels" is "levels"; "discarddegenerateUVs" and "shadowalpha" are dropped.
// - Integrator: "directlighting" is "path" with "maxdepth" 1; "rrthreshold" and SPPM's
//   "imagewritefrequency" are dropped, "lightsamplestrategy" "spatial" is "bvh". SPPM's
//   "numiterations", which pbrt-v4 takes from the Sampler's pixel samples, stays for the target:
//   the scene builder takes it as the iterations, `phos upgrade` writes it as a comment.
// - MakeNamedMedium: "heterogeneous" is "uniformgrid" (the same parameters).
// - PixelFilter: "xwidth"/"ywidth" are "xradius"/"yradius"; the Gaussian's "alpha" is
//   "sigma" = 1 / sqrt(2 alpha).
// - Sampler: "lowdiscrepancy"/"02sequence" are "paddedsobol", "maxmindist" "pmj02bn", "random"
//   "independent".
void upgrade_directive(const std::string& directive, std::string& type, ParamList& params, const Loc& loc);

// Texture: type "color" is "spectrum"; the "scale" texture's "tex1"/"tex2" become "tex"/"scale" (a
// spectrum "scale" texture takes its one grey "rgb" as the float scale); imagemap's "gamma" (a bool
// or a float) becomes "encoding" and "trilinear" becomes "filter".
void upgrade_texture(std::string& type, const std::string& cls, ParamList& params);

}  // namespace phos::io::pbrt
