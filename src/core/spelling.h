// Typo suggestions for messages ("unknown key 'difuse'; did you mean 'diffuse'?").
#pragma once

#include <string>
#include <vector>

namespace phos {

// Levenshtein distance (insertions, deletions, substitutions).
size_t edit_distance(const std::string& a, const std::string& b);

// The nearest of `names` to `word` when it is close enough to be a likely typo, else "".
std::string nearest_name(const std::string& word, const std::vector<std::string>& names);

}  // namespace phos
