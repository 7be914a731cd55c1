#pragma once
// "Did you mean" suggestions for unknown keys and names.
#include <string>
#include <string_view>
#include <vector>

namespace relief {

/// Levenshtein distance between two ASCII strings.
int editDistance(std::string_view a, std::string_view b);

/// The closest candidate within a distance of max(2, |word|/3), or "" if none.
std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates);

/// " (did you mean \"best\"?)" for closestMatch's answer, or "" when there is none.
std::string didYouMean(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace relief
