// pbrt's `curve` shape: its parameters (P, basis, degree, type, N, width, width0, width1,
// splitdepth) read and checked as pbrt-v4 does, and its segments as a scene::CurveSet of cubic
// segments (quadratic curves raised to cubic, quadratic B-splines and ribbons made Bezier).
#pragma once

#include <functional>
#include <string>

#include "io/pbrt/params.h"
#include "scene/curves.h"

namespace phos::io::pbrt {

// The curves of a `Shape "curve"` (`directive` names it in messages) in its object space, radius
// half pbrt's width. A bad count, basis, degree, type or width is a located error; `warn` receives
// the parameters pbrt-v4 ignores with a warning (N on a curve that is not a ribbon).
scene::CurveSet read_curves(const ParamList& params, const Loc& loc, const std::string& directive,
                            const std::function<void(const Loc&, const std::string&)>& warn);

}  // namespace phos::io::pbrt
