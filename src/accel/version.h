// The versions of the ray-tracing and threading libraries phos was built with (for --version).
#pragma once

#include <string>

namespace phos::accel {

std::string embree_version();  // e.g. "3.13.5"
std::string tbb_version();     // compile-time and run-time oneTBB versions

}  // namespace phos::accel
