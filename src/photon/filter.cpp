// Filter names for the command line and the -v report (see filter.h).
#include "photon/filter.h"

namespace phos::photon {

bool parse_filter_kind(const std::string& name, FilterKind& kind) {
    if (name == "none" || name == "box") {
        kind = FilterKind::Box;
    } else if (name == "cone") {
        kind = FilterKind::Cone;
    } else if (name == "gauss" || name == "gaussian") {
        kind = FilterKind::Gauss;
    } else {
        return false;
    }
    return true;
}

const char* filter_name(FilterKind kind) {
    switch (kind) {
        case FilterKind::Box:
            return "none";
        case FilterKind::Cone:
            return "cone";
        case FilterKind::Gauss:
            return "gauss";
    }
    return "none";
}

}  // namespace phos::photon
