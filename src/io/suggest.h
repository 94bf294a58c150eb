// "Did you mean" suggestions for misspelt keys, enum values and material names.
#pragma once
#include <string>
#include <vector>

namespace penumbra {

// Optimal-string-alignment (Damerau-Levenshtein) distance, ASCII case-folded.
int editDistance(const std::string& a, const std::string& b);

// The candidate closest to `word`: edit distance <= 2 (and smaller than the
// candidate itself, so "x" does not suggest "up"), else the longest shared
// prefix of at least 3 characters. Empty when nothing is close.
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

// " (did you mean \"fov\"?)" or "" when there is no close candidate.
std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace penumbra
