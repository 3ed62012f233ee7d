// Typo suggestions: edit distance and the nearest known name.
#include "core/spelling.h"

#include <algorithm>

namespace phos {

size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diag = up;
        }
    }
    return row[b.size()];
}

std::string nearest_name(const std::string& word, const std::vector<std::string>& names) {
    std::string best;
    size_t best_d = 3;
    for (const auto& n : names) {
        const size_t d = edit_distance(word, n);
        if (d < best_d || (d == best_d && best.empty() && n.rfind(word, 0) == 0)) best = n, best_d = d;
    }
    return best;
}

}  // namespace phos
