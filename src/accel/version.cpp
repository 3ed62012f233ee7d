// Library versions for --version (see version.h).
#include "accel/version.h"

#include <embree3/rtcore_config.h>
#include <tbb/version.h>

namespace phos::accel {

std::string embree_version() { return RTC_VERSION_STRING; }

std::string tbb_version() {
    std::string s = TBB_VERSION_STRING;
    const std::string runtime = TBB_runtime_version();
    if (runtime != s) s += " (run time " + runtime + ")";
    return s;
}

}  // namespace phos::accel
