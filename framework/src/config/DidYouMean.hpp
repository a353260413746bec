// Suggestions for misspelt names ("cutof" -> "cutoff", "fdl" -> "fld").
#pragma once

#include <string>
#include <vector>

namespace fldsim {

// Optimal-string-alignment distance: Levenshtein plus adjacent transpositions, so the common
// typo "fdl" for "fld" costs 1 rather than 2.
std::size_t edit_distance(const std::string& a, const std::string& b);

// The closest of `known` to `key` (case-insensitive) within edit distance 2, or a name that
// `key` is a prefix of (or that is a prefix of `key`); "" if none.
std::string did_you_mean(const std::string& key, const std::vector<std::string>& known);

}  // namespace fldsim
